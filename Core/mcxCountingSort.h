// Parallel, deterministic counting sort of voxel ids by level ("bucket
// sorting" in section 6 of the paper).
//
// The voxels are cut into chunks whose layout depends only on the voxel and
// bin counts, never on the thread count; each chunk is counted and scattered
// on its own, and the (bin, chunk) prefix sum puts the chunks of one bin in
// order, so the ids of a bin come out ascending for any number of threads.
#ifndef mcxCountingSort_h
#define mcxCountingSort_h

#include <algorithm>
#include <cstdint>
#include <vector>

namespace mcx
{

struct CountingSortLayout
{
  std::int64_t NumberOfChunks;
  std::int64_t ChunkSize;
};

/// Chunks of at least 2^16 voxels, and at most 2^24 (chunk, bin) counters.
inline CountingSortLayout MakeCountingSortLayout(
  std::int64_t numberOfVoxels, std::int64_t numberOfBins)
{
  const std::int64_t minimumChunk = std::int64_t(1) << 16;
  const std::int64_t counterBudget = std::int64_t(1) << 24;
  std::int64_t chunks = std::max<std::int64_t>(1, numberOfVoxels / minimumChunk);
  chunks = std::min<std::int64_t>(
    chunks, std::max<std::int64_t>(1, counterBudget / std::max<std::int64_t>(numberOfBins, 1)));
  chunks = std::min<std::int64_t>(chunks, 1024);
  const std::int64_t size = numberOfVoxels == 0 ? 1 : (numberOfVoxels + chunks - 1) / chunks;
  return { chunks, size };
}

/// Sorts the ids 0 .. numberOfVoxels-1 by binOf(id), a bin in [0, numberOfBins)
/// or -1 for a voxel to leave out. On return binOffsets (numberOfBins + 1
/// entries) delimits each bin's ids in sortedIds, which must hold room for
/// every voxel that is not left out. Returns the number left out. Chunks run
/// in parallel on `executor` (see mcxExecutor.h).
template <typename IdType, typename BinFunction, typename Executor>
std::int64_t CountingSortByBin(const Executor& executor, std::int64_t numberOfVoxels,
  std::int64_t numberOfBins, const BinFunction& binOf, std::vector<std::int64_t>& binOffsets,
  IdType* sortedIds)
{
  const CountingSortLayout layout = MakeCountingSortLayout(numberOfVoxels, numberOfBins);
  const std::int64_t nb = numberOfBins;
  std::vector<std::int64_t> counters(static_cast<std::size_t>(layout.NumberOfChunks * nb), 0);
  std::vector<std::int64_t> skipped(static_cast<std::size_t>(layout.NumberOfChunks), 0);

  auto chunkRange = [&](std::int64_t c, std::int64_t& begin, std::int64_t& end)
  {
    begin = c * layout.ChunkSize;
    end = std::min(numberOfVoxels, begin + layout.ChunkSize);
  };

  executor.For(0, layout.NumberOfChunks, 1,
    [&](std::int64_t c0, std::int64_t c1)
    {
      for (std::int64_t c = c0; c < c1; ++c)
      {
        std::int64_t* count = counters.data() + c * nb;
        std::int64_t begin, end, left = 0;
        chunkRange(c, begin, end);
        for (std::int64_t id = begin; id < end; ++id)
        {
          const std::int64_t b = binOf(id);
          if (b < 0)
          {
            ++left;
          }
          else
          {
            ++count[b];
          }
        }
        skipped[static_cast<std::size_t>(c)] = left;
      }
    });

  // Exclusive prefix sum in (bin, chunk) order turns counts into write cursors.
  binOffsets.assign(static_cast<std::size_t>(nb + 1), 0);
  std::int64_t running = 0;
  for (std::int64_t b = 0; b < nb; ++b)
  {
    binOffsets[static_cast<std::size_t>(b)] = running;
    for (std::int64_t c = 0; c < layout.NumberOfChunks; ++c)
    {
      std::int64_t& slot = counters[static_cast<std::size_t>(c * nb + b)];
      const std::int64_t n = slot;
      slot = running;
      running += n;
    }
  }
  binOffsets[static_cast<std::size_t>(nb)] = running;

  executor.For(0, layout.NumberOfChunks, 1,
    [&](std::int64_t c0, std::int64_t c1)
    {
      for (std::int64_t c = c0; c < c1; ++c)
      {
        std::int64_t* cursor = counters.data() + c * nb;
        std::int64_t begin, end;
        chunkRange(c, begin, end);
        for (std::int64_t id = begin; id < end; ++id)
        {
          const std::int64_t b = binOf(id);
          if (b >= 0)
          {
            sortedIds[cursor[b]++] = static_cast<IdType>(id);
          }
        }
      }
    });

  std::int64_t total = 0;
  for (std::int64_t s : skipped)
  {
    total += s;
  }
  return total;
}

} // namespace mcx

#endif
