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
// The sort is two passes over every voxel, like the index build (the first
// locates each voxel and keeps its cell and position for the second), then
// three over each run of a few cells (a count, and a stable scatter by
// position, then by cell), so it pays where one view takes many TF edits.
// The order depends on the index, the cells and the bins alone, never on
// the thread count.
#ifndef mcxViewOrder_h
#define mcxViewOrder_h

#include "mcxCountingSort.h"
#include "mcxHugePageAllocator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <type_traits>
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
    // Truncation where it is the floor (the image's pixel coordinates are
    // non-negative): without SSE 4.1, std::floor is a call, and two of them
    // per voxel were about a fifth of a later view's sort of 402 M voxels.
    const double whole =
      f >= 0 && f < 0x1p52 ? static_cast<double>(static_cast<std::int64_t>(f)) : std::floor(f);
    const double sixteenths = (f - whole) * 16.0; // in [0, 16], or not a number
    return sixteenths >= 15.0 ? 15u : sixteenths > 0.0 ? static_cast<unsigned>(sixteenths) : 0u;
  };
  // Each 4-bit step's bits spread to the even bits of a byte.
  static constexpr std::uint8_t Spread[16] = { 0x00, 0x01, 0x04, 0x05, 0x10, 0x11, 0x14, 0x15, 0x40,
    0x41, 0x44, 0x45, 0x50, 0x51, 0x54, 0x55 };
  return static_cast<std::uint8_t>(Spread[step(fx)] << 1 | Spread[step(fy)]);
}

/// How ViewOrder::Build splits a (bin, cell) key into two digits. The high
/// digit, the bin and the cell's top bits, takes about 2^11 values, so
/// that a chunk's write cursors, and the cache lines they write, stay in
/// cache while voxels are scattered by it; the last cell (off the image)
/// has a digit of its own in each bin, so that its voxels, all at position
/// 0 and often the most of them, are never sorted again. The low digit
/// (LowBits bits, 0 when the cells are few) orders each other digit's run
/// of at most 2^LowBits cells in a second pass.
struct ViewOrderDigits
{
  static constexpr int HighBits = 11;
  /// The low digit and the position (8 bits) share 32 bits.
  static constexpr int MaximumLowBits = 24;
  std::int64_t Cells = 1;
  int LowBits = 0;
  std::int64_t DigitsPerBin = 1;
  std::int64_t HighDigits = 1;

  ViewOrderDigits(std::int64_t bins, std::int64_t cells)
    : Cells(std::max<std::int64_t>(cells, 1))
  {
    const std::int64_t inImage = this->Cells - 1;
    const std::int64_t budget = std::max<std::int64_t>(
      1, (std::int64_t(1) << HighBits) / std::max<std::int64_t>(bins, 1) - 1);
    while (this->LowBits < 62 && ((inImage - 1) >> this->LowBits) + 1 > budget)
    {
      ++this->LowBits;
    }
    this->DigitsPerBin = (inImage > 0 ? ((inImage - 1) >> this->LowBits) + 1 : 0) + 1;
    this->HighDigits = std::max<std::int64_t>(bins, 0) * this->DigitsPerBin;
  }
  /// Whether the low digit and the position fit their 32 bits.
  bool Fit() const { return this->LowBits <= MaximumLowBits; }
  /// The bytes ViewOrder::Build keeps per voxel between its passes, its
  /// cell and position: 4 where a cell fits 24 bits (up to 2^24 cells, a
  /// view of fewer than 2^24 pixels and the cell off it), else 8.
  static int SlotKeyBytes(std::int64_t cells) { return cells <= (std::int64_t(1) << 24) ? 4 : 8; }
  std::int64_t High(std::int64_t bin, std::int64_t cell) const
  {
    return bin * this->DigitsPerBin +
      (cell == this->Cells - 1 ? this->DigitsPerBin - 1 : cell >> this->LowBits);
  }
  std::uint32_t Low(std::int64_t cell) const
  {
    return cell == this->Cells - 1
      ? 0u
      : static_cast<std::uint32_t>(cell & ((std::int64_t(1) << this->LowBits) - 1));
  }
  /// The cells of high digit d's run: [first, first + count) of its bin.
  void CellsOf(std::int64_t d, std::int64_t& bin, std::int64_t& first, std::int64_t& count) const
  {
    bin = d / this->DigitsPerBin;
    const std::int64_t top = d % this->DigitsPerBin;
    if (top == this->DigitsPerBin - 1)
    {
      first = this->Cells - 1;
      count = 1;
      return;
    }
    first = top << this->LowBits;
    count = std::min(this->Cells - 1, (top + 1) << this->LowBits) - first;
  }
};

template <typename IdType>
struct ViewOrder
{
  /// The voxel ids by (bin, cell, position, level, id); BinOffsets (bins + 1 entries)
  /// delimits each bin and KeyStarts (bins x cells + 1) each (bin, cell)
  /// run, LevelInBin is each entry's level minus its bin's first level,
  /// BinFirstLevel (bins + 1) the bins' levels.
  std::vector<IdType, HugePageAllocator<IdType>> Ids;
  std::vector<std::uint16_t, HugePageAllocator<std::uint16_t>> LevelInBin;
  std::vector<std::int64_t> BinOffsets;
  std::vector<std::int64_t> KeyStarts;
  std::vector<std::int64_t> BinFirstLevel;
  /// Build's scratch, each entry's low digit and position (what its run
  /// is sorted by): kept for the next Build, whose pages it then finds
  /// touched already (4 bytes a voxel).
  std::vector<std::uint32_t, HugePageAllocator<std::uint32_t>> Rest;
  /// Build's scratch in the index's order, each voxel's cell and position
  /// (ViewOrderDigits::SlotKeyBytes), kept like Rest: one array of each width.
  std::vector<std::uint32_t, HugePageAllocator<std::uint32_t>> SlotKeys;
  std::vector<std::uint64_t, HugePageAllocator<std::uint64_t>> WideSlotKeys;

  std::int64_t NumberOfBins() const
  {
    return static_cast<std::int64_t>(this->BinFirstLevel.size()) - 1;
  }

  /// The cells each bin is sorted by: the pixels of the view the order was
  /// sorted for, and one off its image.
  std::int64_t NumberOfCells() const
  {
    return (static_cast<std::int64_t>(this->KeyStarts.size()) - 1) /
      std::max<std::int64_t>(this->NumberOfBins(), 1);
  }

  /// Takes the arrays of an order no longer needed, so that the next Build
  /// of as many voxels writes into pages already touched: the first touch
  /// of a page, which the kernel zeroes, cost a third of a sort.
  void Recycle(ViewOrder&& old)
  {
    this->Ids = std::move(old.Ids);
    this->LevelInBin = std::move(old.LevelInBin);
    this->Rest = std::move(old.Rest);
    this->SlotKeys = std::move(old.SlotKeys);
    this->WideSlotKeys = std::move(old.WideSlotKeys);
  }

  /// The bytes of this order's arrays (a recycled one's) that a Build of
  /// `voxels` and `cells` writes again; it lets the others go.
  double RecyclableBytes(std::int64_t voxels, std::int64_t cells) const
  {
    const std::size_t n = static_cast<std::size_t>(voxels);
    auto reused = [n](const auto& array)
    {
      using Value = typename std::decay_t<decltype(array)>::value_type;
      return array.size() == n ? static_cast<double>(sizeof(Value)) * static_cast<double>(n) : 0.0;
    };
    return reused(this->Ids) + reused(this->LevelInBin) + reused(this->Rest) +
      (ViewOrderDigits::SlotKeyBytes(cells) == 4 ? reused(this->SlotKeys)
                                                 : reused(this->WideSlotKeys));
  }

  /// Reorders the index's ids (sorted by level, levelOffsets with
  /// numberOfLevels + 1 entries) by bin (binFirstLevel, from
  /// GroupLevelsIntoBins), then by cellOf(id), a ViewCell: its Cell in [0,
  /// cells) (the view's pixel, one more cell for voxels off the image), then
  /// its Position, then as the index lists them; the last cell is the one
  /// off the image. Stable counting sorts: by the (bin, cell) key's high
  /// digit (ViewOrderDigits) in chunks of a layout fixed by the voxel and
  /// digit counts, then each digit's run by its low digit and position, on
  /// `executor`. Each voxel is located once: the first pass keeps its cell
  /// and position (ViewOrderDigits::SlotKeyBytes a voxel) for the second.
  /// After each of three passes it calls progress(fraction), which returns
  /// false to stop: then it returns false and leaves no order. Throws
  /// std::length_error where the digits do not fit (ViewOrderDigits::Fit).
  template <typename Executor, typename CellFunction, typename Progress>
  bool Build(const Executor& executor, const IdType* sortedIds, const std::int64_t* levelOffsets,
    std::int64_t numberOfLevels, std::vector<std::int64_t> binFirstLevel, std::int64_t cells,
    const CellFunction& cellOf, const Progress& progress)
  {
    return ViewOrderDigits::SlotKeyBytes(cells) == sizeof(std::uint32_t)
      ? this->BuildWithSlotKeys<std::uint32_t>(executor, sortedIds, levelOffsets, numberOfLevels,
          std::move(binFirstLevel), cells, cellOf, progress)
      : this->BuildWithSlotKeys<std::uint64_t>(executor, sortedIds, levelOffsets, numberOfLevels,
          std::move(binFirstLevel), cells, cellOf, progress);
  }

  /// Build with each voxel's cell and position kept as a Key (Build takes
  /// the narrowest that holds them; both give the same order).
  template <typename Key, typename Executor, typename CellFunction, typename Progress>
  bool BuildWithSlotKeys(const Executor& executor, const IdType* sortedIds,
    const std::int64_t* levelOffsets, std::int64_t numberOfLevels,
    std::vector<std::int64_t> binFirstLevel, std::int64_t cells, const CellFunction& cellOf,
    const Progress& progress)
  {
    this->BinFirstLevel = std::move(binFirstLevel);
    const std::int64_t bins = this->NumberOfBins();
    const std::int64_t voxels = levelOffsets[numberOfLevels];
    const std::int64_t keys = bins * cells;
    const ViewOrderDigits digits(bins, cells);
    if (!digits.Fit())
    {
      throw std::length_error("a view order of more (bin, cell) keys than its digits hold");
    }
    std::vector<std::int64_t> binOfLevel(static_cast<std::size_t>(numberOfLevels));
    std::vector<std::uint16_t> levelInBin(static_cast<std::size_t>(numberOfLevels));
    for (std::int64_t b = 0; b < bins; ++b)
    {
      const std::int64_t l0 = this->BinFirstLevel[static_cast<std::size_t>(b)];
      for (std::int64_t l = l0; l < this->BinFirstLevel[static_cast<std::size_t>(b + 1)]; ++l)
      {
        binOfLevel[static_cast<std::size_t>(l)] = b;
        levelInBin[static_cast<std::size_t>(l)] = static_cast<std::uint16_t>(l - l0);
      }
    }
    const CountingSortLayout layout = MakeCountingSortLayout(voxels, digits.HighDigits);
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

    // Each voxel located once: its cell and position kept, and each
    // chunk's count of every high digit. A recycled order's keys of the
    // other width are let go first (an assignment of {} keeps the memory).
    auto& otherKeys = this->SlotKeysOf(OtherKey<Key>());
    otherKeys = std::decay_t<decltype(otherKeys)>();
    auto& slotKeys = this->SlotKeysOf(Key());
    Resize(slotKeys, voxels);
    Key* keyOf = slotKeys.data();
    std::vector<std::int64_t> counters(
      static_cast<std::size_t>(layout.NumberOfChunks * digits.HighDigits), 0);
    executor.For(0, layout.NumberOfChunks, 1,
      [&](std::int64_t c0, std::int64_t c1)
      {
        for (std::int64_t c = c0; c < c1; ++c)
        {
          std::int64_t* count = counters.data() + c * digits.HighDigits;
          forEachSlot(c,
            [&](std::int64_t slot, std::int64_t level)
            {
              const ViewCell where = cellOf(sortedIds[slot]);
              keyOf[slot] = static_cast<Key>(static_cast<Key>(where.Cell) << 8 | where.Position);
              ++count[digits.High(binOfLevel[static_cast<std::size_t>(level)], where.Cell)];
            });
        }
      });
    if (!progress(1.0 / 3.0))
    {
      this->BinOffsets.clear();
      return false;
    }

    // Exclusive prefix sum in (digit, chunk) order: the write cursors, and
    // where each digit's run starts.
    std::vector<std::int64_t> runStarts(static_cast<std::size_t>(digits.HighDigits + 1), voxels);
    std::int64_t running = 0;
    for (std::int64_t d = 0; d < digits.HighDigits; ++d)
    {
      runStarts[static_cast<std::size_t>(d)] = running;
      for (std::int64_t c = 0; c < layout.NumberOfChunks; ++c)
      {
        std::int64_t& slot = counters[static_cast<std::size_t>(c * digits.HighDigits + d)];
        const std::int64_t n = slot;
        slot = running;
        running += n;
      }
    }

    Resize(this->Ids, voxels);
    Resize(this->LevelInBin, voxels);
    Resize(this->Rest, voxels);
    std::uint32_t* rest = this->Rest.data();
    executor.For(0, layout.NumberOfChunks, 1,
      [&](std::int64_t c0, std::int64_t c1)
      {
        for (std::int64_t c = c0; c < c1; ++c)
        {
          std::int64_t* cursor = counters.data() + c * digits.HighDigits;
          forEachSlot(c,
            [&](std::int64_t slot, std::int64_t level)
            {
              const Key key = keyOf[slot];
              const std::int64_t cell = static_cast<std::int64_t>(key >> 8);
              const std::size_t to = static_cast<std::size_t>(
                cursor[digits.High(binOfLevel[static_cast<std::size_t>(level)], cell)]++);
              this->Ids[to] = sortedIds[slot];
              this->LevelInBin[to] = levelInBin[static_cast<std::size_t>(level)];
              rest[to] = digits.Low(cell) << 8 | static_cast<std::uint32_t>(key & 0xffu);
            });
        }
      });
    counters = std::vector<std::int64_t>(); // the runs need no cursors
    if (!progress(2.0 / 3.0))
    {
      this->BinOffsets.clear();
      return false;
    }

    // Each run by its low digit and position, which also gives where each
    // key starts.
    std::vector<std::int64_t> keyStarts(static_cast<std::size_t>(keys + 1), voxels);
    typename Executor::template ThreadLocal<RunSorter> sorters;
    executor.For(0, digits.HighDigits, 1,
      [&](std::int64_t d0, std::int64_t d1)
      {
        RunSorter& sorter = sorters.Local();
        for (std::int64_t d = d0; d < d1; ++d)
        {
          std::int64_t bin, first, count;
          digits.CellsOf(d, bin, first, count);
          sorter.Sort(runStarts[static_cast<std::size_t>(d)],
            runStarts[static_cast<std::size_t>(d + 1)], count, rest, this->Ids.data(),
            this->LevelInBin.data(), keyStarts.data() + bin * cells + first);
        }
      });
    this->BinOffsets.assign(static_cast<std::size_t>(bins + 1), voxels);
    for (std::int64_t b = 0; b < bins; ++b)
    {
      this->BinOffsets[static_cast<std::size_t>(b)] =
        keyStarts[static_cast<std::size_t>(b * cells)];
    }
    this->KeyStarts = std::move(keyStarts);
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
  auto& SlotKeysOf(std::uint32_t) { return this->SlotKeys; }
  auto& SlotKeysOf(std::uint64_t) { return this->WideSlotKeys; }
  template <typename Key>
  using OtherKey = typename std::conditional<sizeof(Key) == 4, std::uint64_t, std::uint32_t>::type;

  /// Makes `array` hold n entries, its contents left undefined: a
  /// recycled array of another size is let go rather than copied.
  template <typename Array>
  static void Resize(Array& array, std::int64_t n)
  {
    if (array.size() != static_cast<std::size_t>(n))
    {
      array = Array();
      array.resize(static_cast<std::size_t>(n));
    }
  }

  /// Sorts a high digit's run [begin, end) of `count` keys (its entries'
  /// rest: the key's low digit, then the position in 8 bits) by key and
  /// position, stably, unless it is in order already; writes where each of
  /// its keys starts (keyStarts[0, count)). Reuses its buffers from run to
  /// run.
  class RunSorter
  {
  public:
    void Sort(std::int64_t begin, std::int64_t end, std::int64_t count, std::uint32_t* rest,
      IdType* ids, std::uint16_t* levels, std::int64_t* keyStarts)
    {
      const std::size_t n = static_cast<std::size_t>(end - begin);
      const std::size_t keys = static_cast<std::size_t>(count);
      std::uint32_t* r = rest + begin;
      this->Starts.assign(keys + 1, 0);
      std::size_t positions[257] = {};
      bool ordered = true;
      for (std::size_t i = 0; i < n; ++i)
      {
        ordered = ordered && (i == 0 || r[i - 1] <= r[i]);
        ++this->Starts[(r[i] >> 8) + 1];
        ++positions[(r[i] & 0xffu) + 1];
      }
      for (std::size_t k = 0; k < keys; ++k)
      {
        this->Starts[k + 1] += this->Starts[k];
        keyStarts[k] = begin + static_cast<std::int64_t>(this->Starts[k]);
      }
      if (ordered)
      {
        return; // the off-image cell's run among them: its voxels all have position 0
      }
      // Least significant digit first, both stable: by position into the
      // buffers, then by key back into place.
      for (int p = 0; p < 256; ++p)
      {
        positions[p + 1] += positions[p];
      }
      this->Ids.resize(n);
      this->Levels.resize(n);
      this->Rests.resize(n);
      for (std::size_t i = 0; i < n; ++i)
      {
        const std::size_t slot = positions[r[i] & 0xffu]++;
        this->Ids[slot] = ids[static_cast<std::size_t>(begin) + i];
        this->Levels[slot] = levels[static_cast<std::size_t>(begin) + i];
        this->Rests[slot] = r[i];
      }
      this->Starts.pop_back(); // now each key's write cursor
      for (std::size_t i = 0; i < n; ++i)
      {
        const std::size_t slot = this->Starts[this->Rests[i] >> 8]++;
        ids[static_cast<std::size_t>(begin) + slot] = this->Ids[i];
        levels[static_cast<std::size_t>(begin) + slot] = this->Levels[i];
        r[slot] = this->Rests[i];
      }
    }

  private:
    std::vector<std::size_t> Starts;
    std::vector<IdType> Ids;
    std::vector<std::uint16_t> Levels;
    std::vector<std::uint32_t> Rests;
  };
};

} // namespace mcx

#endif
