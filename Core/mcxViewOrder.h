// The voxels of a density index in the order of one view's pixels (beyond
// the paper), for a Halton voxel choice that stratifies each pixel.
//
// The index lists voxels by density level. With thousands of levels and
// voxels much smaller than pixels, one level's voxels in a pixel's beam are
// scattered through the level, so the Halton sequence, even over the
// level, cannot give a pixel its share to within a count or two: the error
// falls as M^-1/2, like plain Monte Carlo's. Here the levels are grouped
// into a few bins of equal value width, and each bin's voxels are sorted by
// the pixel their centre projects to, then by where in the pixel it falls
// (a Morton order of 16 x 16 squares), then by level, then by id. A bin is
// drawn in proportion to its mass and a voxel uniformly inside it, weighted
// w / (the bin's mean w): unbiased for any view and any TF, and for the
// view it was sorted for, each (bin, pixel) cell gets its expected count to
// within one, and its samples spread evenly over the pixel's area.
//
// Why the position inside the pixel: a voxel's footprint gives part of its
// weight to the neighbouring pixels when its centre lies near an edge, so
// samples at random places in their pixel add noise that falls only as
// M^-1/2; that noise dominated once the cells were stratified (on the CT
// chest upsampled to 50 M and 402 M voxels, 256^2 cone beam, 2^21 - 1
// points: 2.8 and 2.5 % error without, 1.7 and 2.0 % with; a level order
// first, or the level folded into the Morton key, did no better).
//
// The sort is three passes over every voxel, like the index build, so it pays
// where one view takes many TF edits. The order depends on the index, the
// cells and the bins alone, never on the thread count.
#ifndef mcxViewOrder_h
#define mcxViewOrder_h

#include "mcxCountingSort.h"
#include "mcxHugePageAllocator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace mcx
{

/// Groups consecutive levels (values ascending, as the index lists them)
/// into at most `count` bins of equal value width over the levels' range,
/// and opens a new bin after MaximumLevelsPerBin levels so that a level
/// fits 16 bits within its bin. Returns the first level of each bin and the
/// level count last (bins + 1 entries); empty bins are left out.
inline std::vector<std::int64_t> GroupLevelsIntoBins(
  const double* levelValues, std::int64_t numberOfLevels, int count)
{
  constexpr std::int64_t MaximumLevelsPerBin = std::int64_t(1) << 16;
  std::vector<std::int64_t> first;
  if (numberOfLevels <= 0)
  {
    first.push_back(0);
    return first;
  }
  const double lowest = levelValues[0];
  const double width = (levelValues[numberOfLevels - 1] - lowest) / std::max(count, 1);
  auto binOf = [&](double value)
  {
    const double b = width > 0 ? std::floor((value - lowest) / width) : 0.0;
    return static_cast<std::int64_t>(std::max(0.0, std::min<double>(count - 1, b)));
  };
  std::int64_t current = -1;
  for (std::int64_t l = 0; l < numberOfLevels; ++l)
  {
    const std::int64_t b = binOf(levelValues[l]);
    if (b != current || l - first.back() >= MaximumLevelsPerBin)
    {
      first.push_back(l);
      current = b;
    }
  }
  first.push_back(numberOfLevels);
  return first;
}

/// Where a voxel's centre falls in the view: its cell (a pixel, or a cell
/// for voxels off the image) and its position inside that pixel
/// (PositionInPixel).
struct ViewCell
{
  std::int64_t Cell = 0;
  std::uint8_t Position = 0;
};

/// The rank of the 1/16-pixel square that holds the point (fx, fy) (pixel
/// units, pixel i covering [i, i + 1)) within its pixel, in a Morton order:
/// the bits of the column and the row interleaved, so that every aligned
/// block of 2^k x 2^k squares is a contiguous run of ranks.
inline std::uint8_t PositionInPixel(double fx, double fy)
{
  auto step = [](double f)
  {
    const double fraction = f - std::floor(f);
    return static_cast<unsigned>(std::min(15.0, std::max(0.0, std::floor(fraction * 16.0))));
  };
  const unsigned column = step(fx), row = step(fy);
  unsigned rank = 0;
  for (int bit = 3; bit >= 0; --bit)
  {
    rank = (rank << 2) | (((column >> bit) & 1u) << 1) | ((row >> bit) & 1u);
  }
  return static_cast<std::uint8_t>(rank);
}

/// The chunks of ViewOrder::Build: as the index's counting sort, but no
/// more chunks than voxels / (2 keys), so that zeroing and summing the
/// (chunk, key) counters (a pixel grid's worth per bin) never outweighs
/// the voxels.
inline CountingSortLayout MakeViewOrderLayout(std::int64_t voxels, std::int64_t keys)
{
  CountingSortLayout layout = MakeCountingSortLayout(voxels, keys);
  const std::int64_t most = std::max<std::int64_t>(1, voxels / std::max<std::int64_t>(2 * keys, 1));
  if (layout.NumberOfChunks > most)
  {
    layout.NumberOfChunks = most;
    layout.ChunkSize = voxels == 0 ? 1 : (voxels + most - 1) / most;
  }
  return layout;
}

template <typename IdType>
struct ViewOrder
{
  /// The voxel ids by (bin, cell, position, level, id); BinOffsets (bins + 1 entries)
  /// delimits each bin, LevelInBin is each entry's level minus its bin's
  /// first level, BinFirstLevel (bins + 1) the bins' levels.
  std::vector<IdType, HugePageAllocator<IdType>> Ids;
  std::vector<std::uint16_t, HugePageAllocator<std::uint16_t>> LevelInBin;
  std::vector<std::int64_t> BinOffsets;
  std::vector<std::int64_t> BinFirstLevel;

  std::int64_t NumberOfBins() const
  {
    return static_cast<std::int64_t>(this->BinFirstLevel.size()) - 1;
  }

  /// Reorders the index's ids (sorted by level, levelOffsets with
  /// numberOfLevels + 1 entries) by bin (binFirstLevel, from
  /// GroupLevelsIntoBins), then by cellOf(id), a ViewCell: its Cell in [0,
  /// cells) (the view's pixel, one more cell for voxels off the image), then
  /// its Position, then as the index lists them. Runs on `executor` in
  /// chunks of a layout fixed by the voxel and key counts. After each of its
  /// three passes it calls progress(fraction), which returns false to stop:
  /// then it returns false and leaves no order.
  template <typename Executor, typename CellFunction, typename Progress>
  bool Build(const Executor& executor, const IdType* sortedIds, const std::int64_t* levelOffsets,
    std::int64_t numberOfLevels, std::vector<std::int64_t> binFirstLevel, std::int64_t cells,
    const CellFunction& cellOf, const Progress& progress)
  {
    this->BinFirstLevel = std::move(binFirstLevel);
    const std::int64_t bins = this->NumberOfBins();
    const std::int64_t voxels = levelOffsets[numberOfLevels];
    std::vector<std::int64_t> binOfLevel(static_cast<std::size_t>(numberOfLevels));
    for (std::int64_t b = 0; b < bins; ++b)
    {
      std::fill(binOfLevel.begin() + this->BinFirstLevel[static_cast<std::size_t>(b)],
        binOfLevel.begin() + this->BinFirstLevel[static_cast<std::size_t>(b + 1)], b);
    }
    const std::int64_t keys = bins * cells;
    const CountingSortLayout layout = MakeViewOrderLayout(voxels, keys);
    // Visits the slots of chunk c with their level: visit(slot, level).
    auto forEachSlot = [&](std::int64_t c, const auto& visit)
    {
      const std::int64_t begin = c * layout.ChunkSize;
      const std::int64_t end = std::min(voxels, begin + layout.ChunkSize);
      std::int64_t level =
        std::upper_bound(levelOffsets, levelOffsets + numberOfLevels + 1, begin) - levelOffsets - 1;
      for (std::int64_t slot = begin; slot < end; ++slot)
      {
        while (slot >= levelOffsets[level + 1])
        {
          ++level;
        }
        visit(slot, level);
      }
    };
    auto keyOf = [&](std::int64_t level, std::int64_t cell)
    { return binOfLevel[static_cast<std::size_t>(level)] * cells + cell; };

    std::vector<std::int64_t, HugePageAllocator<std::int64_t>> counters(
      static_cast<std::size_t>(layout.NumberOfChunks * keys), 0);
    executor.For(0, layout.NumberOfChunks, 1,
      [&](std::int64_t c0, std::int64_t c1)
      {
        for (std::int64_t c = c0; c < c1; ++c)
        {
          std::int64_t* count = counters.data() + c * keys;
          forEachSlot(c,
            [&](std::int64_t slot, std::int64_t level)
            { ++count[keyOf(level, cellOf(sortedIds[slot]).Cell)]; });
        }
      });
    if (!progress(1.0 / 3.0))
    {
      this->BinOffsets.clear();
      return false;
    }

    // Exclusive prefix sum in (key, chunk) order: the write cursors, and
    // where each key's run starts.
    this->BinOffsets.assign(static_cast<std::size_t>(bins + 1), 0);
    std::vector<std::int64_t> keyStarts(static_cast<std::size_t>(keys + 1), voxels);
    std::int64_t running = 0;
    for (std::int64_t key = 0; key < keys; ++key)
    {
      if (key % cells == 0)
      {
        this->BinOffsets[static_cast<std::size_t>(key / cells)] = running;
      }
      keyStarts[static_cast<std::size_t>(key)] = running;
      for (std::int64_t c = 0; c < layout.NumberOfChunks; ++c)
      {
        std::int64_t& slot = counters[static_cast<std::size_t>(c * keys + key)];
        const std::int64_t n = slot;
        slot = running;
        running += n;
      }
    }
    this->BinOffsets[static_cast<std::size_t>(bins)] = running;

    this->Ids.resize(static_cast<std::size_t>(voxels));
    this->LevelInBin.resize(static_cast<std::size_t>(voxels));
    std::vector<std::uint8_t, HugePageAllocator<std::uint8_t>> positions(
      static_cast<std::size_t>(voxels));
    executor.For(0, layout.NumberOfChunks, 1,
      [&](std::int64_t c0, std::int64_t c1)
      {
        for (std::int64_t c = c0; c < c1; ++c)
        {
          std::int64_t* cursor = counters.data() + c * keys;
          forEachSlot(c,
            [&](std::int64_t slot, std::int64_t level)
            {
              const ViewCell where = cellOf(sortedIds[slot]);
              const std::int64_t to = cursor[keyOf(level, where.Cell)]++;
              this->Ids[static_cast<std::size_t>(to)] = sortedIds[slot];
              this->LevelInBin[static_cast<std::size_t>(to)] = static_cast<std::uint16_t>(level -
                this->BinFirstLevel[static_cast<std::size_t>(
                  binOfLevel[static_cast<std::size_t>(level)])]);
              positions[static_cast<std::size_t>(to)] = where.Position;
            });
        }
      });
    counters = decltype(counters)(); // the third pass needs no cursors
    if (!progress(2.0 / 3.0))
    {
      this->BinOffsets.clear();
      return false;
    }

    executor.For(0, keys, std::max<std::int64_t>(1, keys / 256),
      [&](std::int64_t k0, std::int64_t k1)
      {
        CellSorter sorter;
        for (std::int64_t key = k0; key < k1; ++key)
        {
          sorter.Sort(keyStarts[static_cast<std::size_t>(key)],
            keyStarts[static_cast<std::size_t>(key + 1)], positions.data(), this->Ids.data(),
            this->LevelInBin.data());
        }
      });
    return progress(1.0);
  }

  /// For per-level weights (non-negative, finite): each bin's mean weight
  /// over its voxels (levelOffsets: the index's), and each level's weight
  /// over its bin's mean (0 in a bin of mean 0), the weight a voxel drawn
  /// uniformly from its bin carries.
  void Weights(const double* levelWeights, const std::int64_t* levelOffsets,
    std::vector<double>& binMeans, std::vector<double>& levelRatios) const
  {
    const std::int64_t bins = this->NumberOfBins();
    binMeans.assign(static_cast<std::size_t>(bins), 0.0);
    levelRatios.assign(static_cast<std::size_t>(this->BinFirstLevel.back()), 0.0);
    for (std::int64_t b = 0; b < bins; ++b)
    {
      const std::int64_t l0 = this->BinFirstLevel[static_cast<std::size_t>(b)];
      const std::int64_t l1 = this->BinFirstLevel[static_cast<std::size_t>(b + 1)];
      // The mean as a convex combination: finite for any finite weights.
      const double count = static_cast<double>(levelOffsets[l1] - levelOffsets[l0]);
      double mean = 0.0;
      for (std::int64_t l = l0; l < l1; ++l)
      {
        mean +=
          levelWeights[l] * (static_cast<double>(levelOffsets[l + 1] - levelOffsets[l]) / count);
      }
      binMeans[static_cast<std::size_t>(b)] = mean;
      for (std::int64_t l = l0; l < l1; ++l)
      {
        levelRatios[static_cast<std::size_t>(l)] = mean > 0 ? levelWeights[l] / mean : 0.0;
      }
    }
  }

private:
  /// Sorts the entries [begin, end) of one cell by position, stably (the
  /// level and id order kept within a position), reusing its buffers from
  /// cell to cell.
  class CellSorter
  {
  public:
    void Sort(std::int64_t begin, std::int64_t end, const std::uint8_t* positions, IdType* ids,
      std::uint16_t* levels)
    {
      const std::size_t n = static_cast<std::size_t>(end - begin);
      const std::uint8_t* position = positions + begin;
      if (n < 2 || std::is_sorted(position, position + n))
      {
        return; // the off-image cell among them: its voxels all have position 0
      }
      std::size_t starts[257] = {};
      for (std::size_t i = 0; i < n; ++i)
      {
        ++starts[position[i] + 1];
      }
      for (int p = 0; p < 256; ++p)
      {
        starts[p + 1] += starts[p];
      }
      this->Ids.resize(n);
      this->Levels.resize(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        const std::size_t to = starts[position[i]]++;
        this->Ids[to] = ids[begin + static_cast<std::int64_t>(i)];
        this->Levels[to] = levels[begin + static_cast<std::int64_t>(i)];
      }
      std::copy(this->Ids.begin(), this->Ids.end(), ids + begin);
      std::copy(this->Levels.begin(), this->Levels.end(), levels + begin);
    }

  private:
    std::vector<IdType> Ids;
    std::vector<std::uint16_t> Levels;
  };
};

} // namespace mcx

#endif
