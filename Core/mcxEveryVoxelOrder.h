// The order of an every-voxel cloud: each voxel of the levels a TF keeps
// (non-zero weight) once, weighted by its level's weight instead of drawn
// in proportion to it. Where a TF edit would otherwise draw more samples
// than there are such voxels, this cloud is cheaper and has no voxel-choice
// noise at all.
//
// The order serves both uses of a cloud: the whole of it, deposited at once,
// and its prefixes, which the mapper shows while it refines. The kept voxels
// are cut into runs of up to RunLength consecutive ones in voxel-id order
// (neighbours whose footprints share cache lines), and the runs follow the
// base-2 van der Corput order (run indices bit-reversed, as the Halton
// samples are), so that any prefix holds runs spread evenly over the
// volume. The order depends on the kept levels and the voxel count alone,
// never on the thread count.
#ifndef mcxEveryVoxelOrder_h
#define mcxEveryVoxelOrder_h

#include "mcxHalton.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace mcx
{

template <typename IdType>
struct EveryVoxelOrder
{
  /// Voxels per run: 64 consecutive kept voxels are a row segment (or
  /// several short ones); a prefix is still spread over thousands of runs.
  static constexpr std::uint64_t RunLength = 64;
  /// Voxel ids per work item of the compaction (a fixed layout).
  static constexpr std::int64_t Chunk = std::int64_t(1) << 16;

  /// The cloud's voxels and their levels, point k being voxel Ids[k].
  std::vector<IdType> Ids;
  std::vector<std::uint32_t> Levels;

  std::uint64_t Size() const { return this->Ids.size(); }

  /// Orders the voxels of the levels l with kept[l] != 0, from the index's
  /// ids sorted by level (levelOffsets: numberOfLevels + 1 entries, fewer
  /// than 2^32 - 1 levels). False, and no order, when those ids are not
  /// distinct voxel ids below numberOfVoxels (an index read from a damaged
  /// file).
  template <typename Executor>
  bool Build(const Executor& executor, const IdType* sortedIds, const std::int64_t* levelOffsets,
    std::int64_t numberOfLevels, const std::vector<char>& kept, std::int64_t numberOfVoxels)
  {
    this->Ids.clear();
    this->Levels.clear();
    const std::uint32_t none = ~std::uint32_t(0);
    if (numberOfLevels >= static_cast<std::int64_t>(none))
    {
      return false;
    }
    std::vector<std::uint32_t> levelOf(static_cast<std::size_t>(numberOfVoxels), none);
    // Each voxel's level, kept levels only (every slot written by one item
    // when the ids are distinct; repeated ones show below as a short count).
    std::uint64_t expected = 0;
    for (std::int64_t l = 0; l < numberOfLevels; ++l)
    {
      expected += kept[static_cast<std::size_t>(l)]
        ? static_cast<std::uint64_t>(levelOffsets[l + 1] - levelOffsets[l])
        : 0;
    }
    std::vector<char> outside(static_cast<std::size_t>(numberOfLevels), 0);
    executor.For(0, numberOfLevels, 1,
      [&](std::int64_t l0, std::int64_t l1)
      {
        for (std::int64_t l = l0; l < l1; ++l)
        {
          if (kept[static_cast<std::size_t>(l)])
          {
            for (std::int64_t slot = levelOffsets[l]; slot < levelOffsets[l + 1]; ++slot)
            {
              const std::uint64_t id = static_cast<std::uint64_t>(sortedIds[slot]);
              if (id >= static_cast<std::uint64_t>(numberOfVoxels))
              {
                outside[static_cast<std::size_t>(l)] = 1;
                break;
              }
              levelOf[static_cast<std::size_t>(id)] = static_cast<std::uint32_t>(l);
            }
          }
        }
      });
    if (std::find(outside.begin(), outside.end(), 1) != outside.end())
    {
      return false;
    }
    // The kept voxels in id order: counted per chunk, then written.
    const std::int64_t chunks = (numberOfVoxels + Chunk - 1) / Chunk;
    std::vector<std::uint64_t> start(static_cast<std::size_t>(chunks) + 1, 0);
    auto visitKept = [&](std::int64_t c, auto&& visit)
    {
      const std::int64_t end = std::min(numberOfVoxels, (c + 1) * Chunk);
      for (std::int64_t id = c * Chunk; id < end; ++id)
      {
        if (levelOf[static_cast<std::size_t>(id)] != none)
        {
          visit(id);
        }
      }
    };
    executor.For(0, chunks, 1,
      [&](std::int64_t c0, std::int64_t c1)
      {
        for (std::int64_t c = c0; c < c1; ++c)
        {
          std::uint64_t n = 0;
          visitKept(c, [&n](std::int64_t) { ++n; });
          start[static_cast<std::size_t>(c) + 1] = n;
        }
      });
    std::partial_sum(start.begin(), start.end(), start.begin());
    const std::uint64_t size = start.back();
    if (size != expected)
    {
      return false; // repeated ids
    }
    std::vector<IdType> inIdOrder(static_cast<std::size_t>(size));
    executor.For(0, chunks, 1,
      [&](std::int64_t c0, std::int64_t c1)
      {
        for (std::int64_t c = c0; c < c1; ++c)
        {
          std::uint64_t cursor = start[static_cast<std::size_t>(c)];
          visitKept(c, [&](std::int64_t id) { inIdOrder[cursor++] = static_cast<IdType>(id); });
        }
      });
    // The runs in bit-reversed order (van der Corput, skipping reversals
    // of `runs` or more): slot j holds run runOf[j] at offset at[j].
    this->Ids.resize(static_cast<std::size_t>(size));
    this->Levels.resize(static_cast<std::size_t>(size));
    const std::uint64_t runs = (size + RunLength - 1) / RunLength;
    unsigned bits = 0;
    while ((std::uint64_t(1) << bits) < runs)
    {
      ++bits;
    }
    std::vector<std::uint64_t> runOf, at;
    runOf.reserve(static_cast<std::size_t>(runs));
    at.reserve(static_cast<std::size_t>(runs) + 1);
    at.push_back(0);
    for (std::uint64_t t = 0; runOf.size() < runs; ++t)
    {
      const std::uint64_t run = ReverseLowBits(t, bits);
      if (run < runs)
      {
        runOf.push_back(run);
        at.push_back(at.back() + std::min(RunLength, size - run * RunLength));
      }
    }
    executor.For(0, static_cast<std::int64_t>(runs), 256,
      [&](std::int64_t j0, std::int64_t j1)
      {
        for (std::int64_t j = j0; j < j1; ++j)
        {
          const std::uint64_t first = runOf[static_cast<std::size_t>(j)] * RunLength;
          const std::uint64_t out = at[static_cast<std::size_t>(j)];
          const std::uint64_t length = at[static_cast<std::size_t>(j) + 1] - out;
          for (std::uint64_t i = 0; i < length; ++i)
          {
            const IdType id = inIdOrder[first + i];
            this->Ids[out + i] = id;
            this->Levels[out + i] = levelOf[static_cast<std::size_t>(id)];
          }
        }
      });
    return true;
  }
};

} // namespace mcx

#endif
