// The sampling kernel of hybrid Monte Carlo volume rendering (sections 5 and
// 6 of the paper), without any VTK pipeline around it.
//
// Every sample has an output index k in [0, M). Its voxel is the inverse of
// the TF-weighted cumulative distribution at a number u in (0, 1]: for
// Hybrid and QuasiMonteCarlo u = RadicalInverse2(k + 1) (the base-2 Halton
// sequence), for MonteCarlo u is pseudo-random. Within the chosen level, whose
// voxels share one weight, u picks the voxel by its rank. The sub-voxel offset
// is drawn from the normalised reconstruction kernel: pseudo-randomly (Hybrid,
// MonteCarlo) or from Halton bases 3, 5, 7 with a seeded random shift
// (QuasiMonteCarlo), or left out for the footprint deposit (Centres).
// Everything about sample k depends on (seed, k) alone, so
// the result is the same for any split of the work among threads, and the
// first 2^j - 1 Hybrid samples of a run are exactly a 2^j - 1 sample run.
//
// A volume cut into pieces (one per process, pieces in the global order of
// voxel ids: z-slabs) samples the same way: every piece holds the global
// table (levels, counts, masses) and its own sorted ids, and emits exactly
// the samples whose voxel it holds, with the numbering of a single process.
// Under the Halton choice a piece's samples in a level are a contiguous run
// of ranks (the voxel rank grows with the sample rank), so PieceRanks finds
// them in O(levels log M) and a piece generates only its own.
#ifndef mcxSampleGenerator_h
#define mcxSampleGenerator_h

#include "mcxFastDivide.h"
#include "mcxHalton.h"
#include "mcxPrefetch.h"
#include "mcxRandom.h"
#include "mcxTransferTable.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

namespace mcx
{

enum class Strategy : int
{
  Hybrid = 0,
  MonteCarlo = 1,
  QuasiMonteCarlo = 2
};

enum class Kernel : int
{
  Tent = 0, ///< trilinear reconstruction, support one spacing each side
  Box = 1   ///< nearest-neighbour reconstruction, support half a spacing each side
};

/// Half-width of the kernel's support in voxels.
inline double KernelRadius(Kernel kernel)
{
  return kernel == Kernel::Tent ? 1.0 : 0.5;
}

/// Offset in voxels from a uniform number in [0, 1), by inversion of the
/// kernel's one-dimensional density.
inline double KernelOffsetFromUniform(Kernel kernel, double u)
{
  if (kernel == Kernel::Box)
  {
    return u - 0.5;
  }
  return u < 0.5 ? std::sqrt(2.0 * u) - 1.0 : 1.0 - std::sqrt(2.0 * (1.0 - u));
}

/// The Cranley-Patterson rotation of the QuasiMonteCarlo offsets: one
/// seeded shift per axis for the whole run.
struct RotationShift
{
  explicit RotationShift(std::uint64_t seed)
  {
    for (int a = 0; a < 3; ++a)
    {
      CounterRandom source(SeedKey(seed ^ 0xA5A5A5A5A5A5A5A5ull), static_cast<std::uint64_t>(a));
      this->Value[a] = source.NextOpenClosed();
    }
  }
  double Value[3];
};

template <typename IdType>
struct SampleSource
{
  /// GenerateForStorage's blocks: at most 2^StorageBits ranks per run read
  /// and points per run written; StorageRun MonteCarlo points per item.
  static constexpr unsigned StorageBits = 6;
  static constexpr std::uint64_t StorageRun = 4096;

  const IdType* SortedIds = nullptr;
  const std::int64_t* LevelOffsets = nullptr; // NumberOfLevels + 1 entries
  const double* Cumulative = nullptr;         // NumberOfLevels + 1 entries, see TransferTable
  const double* RankScale = nullptr;          // per level: voxel count / level mass
  const std::int64_t* Guide = nullptr;        // GuideSize entries, see TransferTable
  std::int64_t GuideSize = 0;
  double GuideScale = 0.0; // GuideSize / Cumulative[NumberOfLevels]
  std::int64_t NumberOfLevels = 0;
  VoxelDecoder<IdType> Decoder;
  Strategy Method = Strategy::Hybrid;
  Kernel Reconstruction = Kernel::Tent;
  std::uint64_t Seed = 0;
  unsigned Exponent = 0; // M = 2^Exponent - 1
  /// Emit voxel centres, without the kernel offset (for the footprint
  /// deposit, which spreads the kernel itself).
  bool Centres = false;
  /// A piece of the volume (null: the whole of it). SortedIds are then the
  /// piece's, PieceOffsets (NumberOfLevels + 1 entries) delimit them per
  /// level, PieceFirstRank[l] is the global rank in level l of the piece's
  /// first voxel, LevelOffsets stay global, and the Decoder decodes ids of
  /// the piece's extent, whose first voxel is PieceStart in the whole
  /// volume's voxel coordinates (points are emitted in those).
  const std::int64_t* PieceOffsets = nullptr;
  const std::int64_t* PieceFirstRank = nullptr;
  std::uint64_t PieceStart[3] = { 0, 0, 0 };
  /// A view order (mcxViewOrder.h) instead of the index, whole volume only:
  /// SortedIds and LevelOffsets are then its ids and bin offsets, the table
  /// draws its bins, and sample k of slot s in bin b carries the weight
  /// LevelRatio[BinFirstLevel[b] + LevelInBin[s]] to sinks that take one,
  /// sink(k, p, weight) (1 for every sample otherwise), and the sample's
  /// level of the index (of LevelRatio's levels when binned) to sinks that
  /// take sink(k, p, weight, level).
  const std::uint16_t* LevelInBin = nullptr;
  const std::int64_t* BinFirstLevel = nullptr;
  const double* LevelRatio = nullptr;
  /// Generate emits only the samples k >= FirstSample: the first 2^j - 1
  /// samples of a run are, bit for bit, the 2^j - 1 sample run (the voxel
  /// choice and the offsets of sample k do not depend on M), so a run
  /// extending one already deposited draws the rest alone.
  std::uint64_t FirstSample = 0;

  std::uint64_t NumberOfSamples() const { return SampleCount(this->Exponent); }

  /// Points the source at a table's distribution (the table must outlive it).
  void SetTable(const TransferTable& table)
  {
    this->Cumulative = table.Cumulative.data();
    this->RankScale = table.RankScale.data();
    this->Guide = table.Guide.data();
    this->GuideSize = static_cast<std::int64_t>(table.Guide.size());
    this->GuideScale = table.IsEmpty() ? 0.0 : this->GuideSize / table.Cumulative.back();
  }

  /// Generates the samples of one work item: for Hybrid and QuasiMonteCarlo
  /// the items are ranks in u order (i, with u = (i + 1) / 2^m), so that
  /// levels and ids are visited in order; for MonteCarlo they are the output
  /// indices k. The sink is called as sink(k, p) with p the sample in voxel
  /// coordinates counted from the first voxel of the extent.
  template <typename Sink>
  void Generate(std::uint64_t begin, std::uint64_t end, Sink& sink) const
  {
    if (begin >= end)
    {
      return;
    }
    if (this->Method == Strategy::MonteCarlo)
    {
      this->GenerateInOutputOrder(std::max(begin, this->FirstSample), end, sink);
      return;
    }
    const std::uint64_t key = SeedKey(this->Seed);
    const RotationShift shift(this->Seed);
    const double total = this->Cumulative[this->NumberOfLevels];
    const double step = std::ldexp(total, -static_cast<int>(this->Exponent));
    std::int64_t c = this->FindLevel(static_cast<double>(begin + 1) * step);
    std::int64_t aheadLevel = c;
    // Dense samples read their ids in runs that the hardware's prefetcher follows.
    const bool sparse = this->NumberOfSamples() * SparseIdsPerSample <
      static_cast<std::uint64_t>(this->LevelOffsets[this->NumberOfLevels]);
    for (std::uint64_t i = begin; i < end; ++i)
    {
      if (sparse && i + ReadAhead < end)
      {
        this->PrefetchRank(i + ReadAhead, step, aheadLevel);
      }
      const double target = static_cast<double>(i + 1) * step;
      while (target > this->Cumulative[c])
      {
        ++c;
      }
      const std::uint64_t k = HaltonPosition(i, this->Exponent);
      if (k < this->FirstSample)
      {
        continue;
      }
      CounterRandom random(key, k);
      this->Emit(k, target, c, random, shift, sink);
    }
  }

  /// Work items of GenerateForStorage.
  std::uint64_t NumberOfStorageItems() const
  {
    if (this->Exponent == 0)
    {
      return 0;
    }
    if (this->Method == Strategy::MonteCarlo)
    {
      return (this->NumberOfSamples() + StorageRun - 1) / StorageRun;
    }
    return std::uint64_t(1) << (this->Exponent - 2 * this->StorageBlockBits());
  }

  /// The same samples as Generate, in an order that keeps both the reads of
  /// sorted ids and the writes of output indices in short contiguous runs
  /// (for stored point clouds). The rank j = i + 1 and the output position
  /// k + 1 are each other's m-bit reversal; with j = (a << (middle + q)) |
  /// (r << q) | b (a and b of q bits, r of middle = m - 2q bits),
  /// k + 1 = (rev(b) << (middle + q)) | (rev(r) << q) | rev(a). Item t is the
  /// block rev(r) = t: 2^q runs of 2^q consecutive ranks read (one per a),
  /// 2^q runs of 2^q consecutive points written (one per b), and the next
  /// item writes right after them. A block touches 2^(q+1) pages whatever m
  /// is: looping over every b per item instead (2^(m/2) pages) thrashed the
  /// TLB for large m. MonteCarlo items are
  /// plain runs of output indices.
  template <typename Sink>
  void GenerateForStorage(std::uint64_t itemBegin, std::uint64_t itemEnd, Sink& sink) const
  {
    if (this->Method == Strategy::MonteCarlo)
    {
      this->GenerateInOutputOrder(
        itemBegin * StorageRun, std::min(this->NumberOfSamples(), itemEnd * StorageRun), sink);
      return;
    }
    const unsigned q = this->StorageBlockBits();
    const unsigned middle = this->Exponent - 2 * q;
    const std::uint64_t side = std::uint64_t(1) << q;
    const double step =
      std::ldexp(this->Cumulative[this->NumberOfLevels], -static_cast<int>(this->Exponent));
    const std::uint64_t key = SeedKey(this->Seed);
    const RotationShift shift(this->Seed);
    for (std::uint64_t t = itemBegin; t < itemEnd; ++t)
    {
      const std::uint64_t rankMiddle = ReverseLowBits(t, middle) << q;
      for (std::uint64_t a = 0; a < side; ++a)
      {
        const std::uint64_t runStart = (a << (middle + q)) | rankMiddle; // j of b = 0
        const std::uint64_t outputLow = (t << q) | ReverseLowBits(a, q);
        // Consecutive ranks: one search per run, then a walk (as Generate).
        const std::uint64_t first = runStart == 0 ? 1 : 0; // j = 0 is no sample
        const std::int64_t runLevel = this->FindLevel(static_cast<double>(runStart | first) * step);
        this->PrefetchRun(runStart, first, side, runLevel, step);
        std::int64_t c = runLevel;
        for (std::uint64_t b = first; b < side; ++b)
        {
          const double target = static_cast<double>(runStart | b) * step;
          while (c < this->NumberOfLevels && target > this->Cumulative[c])
          {
            ++c;
          }
          const std::uint64_t k = ((ReverseLowBits(b, q) << (middle + q)) | outputLow) - 1;
          CounterRandom random(key, k);
          this->Emit(k, target, c, random, shift, sink);
        }
      }
    }
  }

  /// The same samples as Generate, visited by output index k in [begin, end).
  template <typename Sink>
  void GenerateInOutputOrder(std::uint64_t begin, std::uint64_t end, Sink& sink) const
  {
    const double total = this->Cumulative[this->NumberOfLevels];
    const double step = std::ldexp(total, -static_cast<int>(this->Exponent));
    const std::uint64_t key = SeedKey(this->Seed);
    const RotationShift shift(this->Seed);
    const bool randomChoice = this->Method == Strategy::MonteCarlo;
    for (std::uint64_t k = begin; k < end; ++k)
    {
      CounterRandom random(key, k);
      const double target = randomChoice
        ? random.NextOpenClosed() * total
        : static_cast<double>(HaltonPosition(k, this->Exponent) + 1) * step;
      this->Emit(k, target, this->FindLevel(target), random, shift, sink);
    }
  }

  /// The ranks i (of Generate) of the samples whose voxels this piece holds,
  /// as sorted, disjoint [begin, end) runs: all of [0, M) for the whole
  /// volume; for MonteCarlo, whose choice is random, also all of [0, M)
  /// (each piece then draws every sample and emits its own).
  std::vector<std::pair<std::uint64_t, std::uint64_t>> PieceRanks() const
  {
    std::vector<std::pair<std::uint64_t, std::uint64_t>> runs;
    const std::uint64_t m = this->NumberOfSamples();
    if (!this->PieceOffsets || this->Method == Strategy::MonteCarlo)
    {
      if (m > 0)
      {
        runs.emplace_back(0, m);
      }
      return runs;
    }
    const double step =
      std::ldexp(this->Cumulative[this->NumberOfLevels], -static_cast<int>(this->Exponent));
    auto target = [step](std::uint64_t i) { return static_cast<double>(i + 1) * step; };
    // First i in [lo, hi) where a monotone predicate holds (hi when none).
    auto first = [](std::uint64_t lo, std::uint64_t hi, const auto& holds)
    {
      while (lo < hi)
      {
        const std::uint64_t mid = lo + (hi - lo) / 2;
        if (holds(mid))
        {
          hi = mid;
        }
        else
        {
          lo = mid + 1;
        }
      }
      return lo;
    };
    for (std::int64_t c = 1; c <= this->NumberOfLevels; ++c)
    {
      const std::int64_t held = this->PieceOffsets[c] - this->PieceOffsets[c - 1];
      if (held <= 0)
      {
        continue;
      }
      // Level c - 1 takes the targets in (Cumulative[c - 1], Cumulative[c]].
      const std::uint64_t levelBegin =
        first(0, m, [&](std::uint64_t i) { return target(i) > this->Cumulative[c - 1]; });
      const std::uint64_t levelEnd =
        first(levelBegin, m, [&](std::uint64_t i) { return target(i) > this->Cumulative[c]; });
      const std::int64_t low = this->PieceFirstRank[c - 1];
      const std::uint64_t begin = first(levelBegin, levelEnd,
        [&](std::uint64_t i) { return this->VoxelRank(target(i), c) >= low; });
      const std::uint64_t end = first(begin, levelEnd,
        [&](std::uint64_t i) { return this->VoxelRank(target(i), c) >= low + held; });
      if (begin < end)
      {
        if (!runs.empty() && runs.back().second == begin)
        {
          runs.back().second = end;
        }
        else
        {
          runs.emplace_back(begin, end);
        }
      }
    }
    return runs;
  }

  /// Rank within level c - 1 of the voxel whose share (rank, rank + 1] of
  /// the level's mass, in units of one voxel, contains target: ceil(x) - 1 of
  /// x = (target - Cumulative[c - 1]) * RankScale[c - 1], kept in [0, count).
  /// Done in floating point, so no product of counts can overflow.
  std::int64_t VoxelRank(double target, std::int64_t c) const
  {
    const std::int64_t count = this->LevelOffsets[c] - this->LevelOffsets[c - 1];
    double position = (target - this->Cumulative[c - 1]) * this->RankScale[c - 1];
    if (!(position < static_cast<double>(count))) // also an infinite scale of a denormal mass
    {
      position = static_cast<double>(count);
    }
    std::int64_t rank = static_cast<std::int64_t>(position);
    rank -= static_cast<double>(rank) == position ? 1 : 0;
    return std::max<std::int64_t>(0, std::min<std::int64_t>(count - 1, rank));
  }

private:
  /// How many ranks ahead of the one it emits Generate asks for the ids'
  /// cache lines: where samples are sparse among the voxels (fewer samples
  /// than voxels on a large CT) each rank reads a line, and often a page, of
  /// its own, and waiting for them one at a time made a floor of 0.1-0.4 s
  /// under 2^24 samples on the 453 M-voxel CT.
  static constexpr std::uint64_t ReadAhead = 24;
  /// Samples are sparse (and read ahead) below one per this many ids, a
  /// 64-byte line of 4-byte ids: denser, the prefetches only cost (10-20 %
  /// of the fused path on a 256^3 CT with 2^22 - 1 samples).
  static constexpr std::uint64_t SparseIdsPerSample = 16;

  /// Asks for the cache line of rank i's id (and level in bin), walking
  /// `level` forward as Generate's own walk (ranks only grow).
  void PrefetchRank(std::uint64_t i, double step, std::int64_t& level) const
  {
    if (this->PieceOffsets)
    {
      return; // a piece's ranks shift: PieceRanks' runs, not worth the search
    }
    const double target = static_cast<double>(i + 1) * step;
    while (level < this->NumberOfLevels && target > this->Cumulative[level])
    {
      ++level;
    }
    const std::int64_t slot = this->LevelOffsets[level - 1] + this->VoxelRank(target, level);
    PrefetchForReading(this->SortedIds + slot);
    if (this->LevelInBin)
    {
      PrefetchForReading(this->LevelInBin + slot);
    }
  }

  /// Asks for the cache lines of the ids (and levels in bin) that the run
  /// of ranks runStart | b, b in [first, side), will read, before any is
  /// read: where the samples are sparse among the voxels (the 402 M-voxel
  /// CT: a sample every hundred voxels) each rank reads a line of its own,
  /// and waiting for them one at a time took most of the generation. The
  /// same walk as the run's; the whole volume only (a piece's ranks shift).
  void PrefetchRun(std::uint64_t runStart, std::uint64_t first, std::uint64_t side, std::int64_t c,
    double step) const
  {
    if (this->PieceOffsets)
    {
      return;
    }
    for (std::uint64_t b = first; b < side; ++b)
    {
      const double target = static_cast<double>(runStart | b) * step;
      while (c < this->NumberOfLevels && target > this->Cumulative[c])
      {
        ++c;
      }
      const std::int64_t slot = this->LevelOffsets[c - 1] + this->VoxelRank(target, c);
      PrefetchForReadingInALoop(this->SortedIds + slot);
      if (this->LevelInBin)
      {
        PrefetchForReadingInALoop(this->LevelInBin + slot);
      }
    }
  }

  /// q of GenerateForStorage's blocks: StorageBits, or m / 2 for small m.
  unsigned StorageBlockBits() const { return std::min(StorageBits, this->Exponent / 2); }

  /// Smallest c in [1, NumberOfLevels] with target <= Cumulative[c]
  /// (level c - 1): a guide-table start, then a short walk.
  std::int64_t FindLevel(double target) const
  {
    const double bucket = target * this->GuideScale;
    const std::int64_t b =
      std::min<std::int64_t>(this->GuideSize - 1, static_cast<std::int64_t>(bucket));
    std::int64_t c = this->Guide[std::max<std::int64_t>(0, b)];
    while (c > 1 && target <= this->Cumulative[c - 1])
    {
      --c;
    }
    while (c < this->NumberOfLevels && target > this->Cumulative[c])
    {
      ++c;
    }
    return c;
  }

  template <typename Sink>
  void Emit(std::uint64_t k, double target, std::int64_t c, CounterRandom& random,
    const RotationShift& shift, Sink& sink) const
  {
    const std::int64_t rank = this->VoxelRank(target, c);
    std::int64_t slot = this->LevelOffsets[c - 1] + rank;
    if (this->PieceOffsets)
    {
      // Another piece's voxel: its process emits this sample.
      const std::int64_t local = rank - this->PieceFirstRank[c - 1];
      if (local < 0 || local >= this->PieceOffsets[c] - this->PieceOffsets[c - 1])
      {
        return;
      }
      slot = this->PieceOffsets[c - 1] + local;
    }
    std::uint64_t voxel[3];
    this->Decoder.Decode(this->SortedIds[slot], voxel[0], voxel[1], voxel[2]);
    for (int a = 0; a < 3; ++a)
    {
      voxel[a] += this->PieceStart[a];
    }
    double p[3];
    if (this->Centres)
    {
      for (int a = 0; a < 3; ++a)
      {
        p[a] = static_cast<double>(voxel[a]);
      }
    }
    else if (this->Method == Strategy::QuasiMonteCarlo)
    {
      // Halton bases 3, 5, 7 with a Cranley-Patterson rotation from the seed.
      static const unsigned bases[3] = { 3, 5, 7 };
      for (int a = 0; a < 3; ++a)
      {
        double u = RadicalInverse(k + 1, bases[a]) + shift.Value[a];
        u -= std::floor(u);
        p[a] = static_cast<double>(voxel[a]) + KernelOffsetFromUniform(this->Reconstruction, u);
      }
    }
    else
    {
      // Pseudo-random offsets in fixed point, 21 bits per axis and draw
      // (2^-21 voxel, far below any pixel): the tent as the sum of two
      // uniforms on (-1, 1), the box as one on [-1/2, 1/2). Each coordinate
      // is an integer multiple of 2^-21 below 2^53, so it converts exactly.
      const std::uint64_t r1 = random.Next();
      const bool tent = this->Reconstruction == Kernel::Tent;
      const std::uint64_t r2 = tent ? random.Next() : 0;
      const std::int64_t centre = tent ? (std::int64_t(1) << 21) : (std::int64_t(1) << 20);
      for (int a = 0; a < 3; ++a)
      {
        const int shift = 43 - 21 * a;
        const std::int64_t fixed = static_cast<std::int64_t>(voxel[a] << 21) +
          static_cast<std::int64_t>((r1 >> shift) & 0x1FFFFF) +
          static_cast<std::int64_t>((r2 >> shift) & 0x1FFFFF) - centre;
        p[a] = static_cast<double>(fixed) * 0x1.0p-21;
      }
    }
    if constexpr (std::is_invocable_v<Sink&, std::uint64_t, const double*, double, std::int64_t>)
    {
      // The level of the index the voxel is in (the bin's level of it when binned).
      const std::int64_t level =
        this->LevelInBin ? this->BinFirstLevel[c - 1] + this->LevelInBin[slot] : c - 1;
      sink(k, p, this->LevelInBin ? this->LevelRatio[level] : 1.0, level);
    }
    else if constexpr (std::is_invocable_v<Sink&, std::uint64_t, const double*, double>)
    {
      sink(k, p,
        this->LevelInBin ? this->LevelRatio[this->BinFirstLevel[c - 1] + this->LevelInBin[slot]]
                         : 1.0);
    }
    else
    {
      sink(k, p);
    }
  }
};

} // namespace mcx

#endif
