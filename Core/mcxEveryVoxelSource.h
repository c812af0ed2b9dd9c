// Every voxel of non-zero weight once, as points to deposit: the fused
// off-line projector's every-voxel image (no cloud stored) and the points of
// a stored every-voxel cloud (mcxEveryVoxelOrder.h orders those) are made of
// the same pieces here.
//
// A voxel of level l counts LevelWeights[l] = (the level's TF weight) / (the mean
// weight of the kept voxels), so that the weights add up to the number of
// voxels kept and the image is normalised as a sampled one is (Integral /
// the sum of the weights deposited). The fused deposit numbers each voxel by
// its id in the whole volume, so that a piece of the volume (one process's
// z-slab) gives its voxels the numbers, and so the random streams (the point
// deposit's kernel offset, the footprint's phase), that one process would.
#ifndef mcxEveryVoxelSource_h
#define mcxEveryVoxelSource_h

#include "mcxFastDivide.h"
#include "mcxRandom.h"
#include "mcxSampleGenerator.h"

#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace mcx
{

/// The point of the voxel at integer coordinates `voxel`: its centre (the
/// footprint deposit spreads the kernel itself) or the centre plus a kernel
/// offset drawn from stream k of `seedKey` (the point deposit).
inline void EveryVoxelPoint(const std::uint64_t voxel[3], Kernel kernel, bool centre,
  std::uint64_t seedKey, std::uint64_t k, double p[3])
{
  CounterRandom random(seedKey, k);
  for (int a = 0; a < 3; ++a)
  {
    p[a] = static_cast<double>(voxel[a]) +
      (centre ? 0.0 : KernelOffsetFromUniform(kernel, 1.0 - random.NextOpenClosed()));
  }
}

/// The weight of a kept voxel whose level weighs `levelWeight`, when `kept`
/// voxels weigh `weightSum` in all: levelWeight over their mean (0 when
/// nothing weighs anything).
inline double EveryVoxelWeight(double levelWeight, double kept, double weightSum)
{
  // The level's share first: at most 1, so the weight stays finite (at most
  // `kept`) however small the mean weight is.
  return weightSum > 0 ? (levelWeight / weightSum) * kept : 0.0;
}

template <typename IdType>
struct EveryVoxelSource
{
  /// The ids sorted by level (the index's, or a piece's), LevelOffsets[l] to
  /// LevelOffsets[l + 1] being level l's; LevelWeights (EveryVoxelWeight,
  /// 0 for a level that keeps none).
  const IdType* SortedIds = nullptr;
  const std::int64_t* LevelOffsets = nullptr;
  std::int64_t NumberOfLevels = 0;
  const double* LevelWeights = nullptr;
  /// Decodes the ids (of a piece's extent); PieceStart is its first voxel in
  /// the whole volume, WholeDimensions the volume's (x and y).
  VoxelDecoder<IdType> Decoder;
  std::uint64_t PieceStart[3] = { 0, 0, 0 };
  std::uint64_t WholeDimensions[2] = { 0, 0 };
  Kernel Reconstruction = Kernel::Tent;
  bool Centres = false;
  std::uint64_t Seed = 0;

  /// Finds the kept levels' ids; call it once the fields are set.
  void Prepare()
  {
    this->Levels.clear();
    this->Ends.clear();
    std::uint64_t total = 0;
    for (std::int64_t l = 0; l < this->NumberOfLevels; ++l)
    {
      const std::int64_t count = this->LevelOffsets[l + 1] - this->LevelOffsets[l];
      if (this->LevelWeights[l] > 0 && count > 0)
      {
        total += static_cast<std::uint64_t>(count);
        this->Levels.push_back(l);
        this->Ends.push_back(total);
      }
    }
  }

  /// The voxels this source emits (the kept levels' ids it holds).
  std::uint64_t Size() const { return this->Ends.empty() ? 0 : this->Ends.back(); }

  /// Emits voxels [begin, end) of the kept levels' ids, laid end to end,
  /// as sink(k, p, weight), or sink(k, p, weight, level) to a sink that
  /// takes the voxel's level: k the voxel's id in the whole volume, p its
  /// point in the whole volume's voxel coordinates (EveryVoxelPoint).
  template <typename Sink>
  void Generate(std::uint64_t begin, std::uint64_t end, Sink&& sink) const
  {
    const std::uint64_t key = SeedKey(this->Seed);
    std::size_t r = static_cast<std::size_t>(
      std::upper_bound(this->Ends.begin(), this->Ends.end(), begin) - this->Ends.begin());
    for (; r < this->Levels.size() && begin < end; ++r)
    {
      const std::int64_t level = this->Levels[r];
      const std::uint64_t runBegin = r == 0 ? 0 : this->Ends[r - 1];
      const std::uint64_t stop = std::min(end, this->Ends[r]);
      const IdType* ids = this->SortedIds + this->LevelOffsets[level] - runBegin;
      const double weight = this->LevelWeights[level];
      for (std::uint64_t i = begin; i < stop; ++i)
      {
        std::uint64_t voxel[3];
        this->Decoder.Decode(ids[i], voxel[0], voxel[1], voxel[2]);
        for (int a = 0; a < 3; ++a)
        {
          voxel[a] += this->PieceStart[a];
        }
        const std::uint64_t k =
          voxel[0] + this->WholeDimensions[0] * (voxel[1] + this->WholeDimensions[1] * voxel[2]);
        double p[3];
        EveryVoxelPoint(voxel, this->Reconstruction, this->Centres, key, k, p);
        if constexpr (std::is_invocable_v<Sink&, std::uint64_t, const double*, double,
                        std::int64_t>)
        {
          sink(k, p, weight, level);
        }
        else
        {
          sink(k, p, weight);
        }
      }
      begin = stop;
    }
  }

private:
  std::vector<std::int64_t> Levels; // the kept levels with ids here
  std::vector<std::uint64_t> Ends;  // the cumulative id counts of those levels
};

} // namespace mcx

#endif
