// Tests of the plain C++ core without VTK: the portable wide integer against
// the compiler's, the executor-driven kernels (counting sort, sample
// accumulation, progressive image, radiograph effects) giving the same
// result on one thread and on several, a thread's 64-bit sums carrying
// exactly, the footprint tables' supports and scale choice, and the view
// order's sort and weights.
#include "mcxChannelSplit.h"
#include "mcxControlImage.h"
#include "mcxCountingSort.h"
#include "mcxEveryVoxelOrder.h"
#include "mcxEveryVoxelSource.h"
#include "mcxExecutor.h"
#include "mcxFixedPoint.h"
#include "mcxGridPixelPositions.h"
#include "mcxHugePageAllocator.h"
#include "mcxObliqueTestGeometry.h"
#include "mcxPixelBinner.h"
#include "mcxProgressiveImage.h"
#include "mcxRadiographEffects.h"
#include "mcxSampleAccumulator.h"
#include "mcxSampleGenerator.h"
#include "mcxViewOrder.h"
#include "mcxWideInteger.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <list>
#include <map>
#include <mutex>
#include <new>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace
{
// An executor of std::threads with small chunks, so that work really is
// split and interleaved (the VTK modules use vtkSMPTools instead).
struct ThreadExecutor
{
  int Threads = 4;

  template <typename F>
  void For(std::int64_t begin, std::int64_t end, std::int64_t grain, const F& f) const
  {
    const std::int64_t chunk = std::max<std::int64_t>(1, std::min<std::int64_t>(grain, 97));
    std::mutex mutex;
    std::int64_t next = begin;
    auto worker = [&]()
    {
      for (;;)
      {
        std::int64_t b;
        {
          std::lock_guard<std::mutex> lock(mutex);
          b = next;
          next = std::min(end, next + chunk);
        }
        if (b >= end)
        {
          return;
        }
        f(b, std::min(end, b + chunk));
      }
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < this->Threads; ++t)
    {
      pool.emplace_back(worker);
    }
    for (std::thread& thread : pool)
    {
      thread.join();
    }
  }

  template <typename T>
  class ThreadLocal
  {
  public:
    T& Local()
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      auto found = this->Slots.find(std::this_thread::get_id());
      if (found != this->Slots.end())
      {
        return *found->second;
      }
      this->Values.emplace_back();
      this->Slots[std::this_thread::get_id()] = &this->Values.back();
      return this->Values.back();
    }
    typename std::list<T>::iterator begin() { return this->Values.begin(); }
    typename std::list<T>::iterator end() { return this->Values.end(); }

  private:
    std::mutex Mutex;
    std::list<T> Values;
    std::map<std::thread::id, T*> Slots;
  };
};

#ifdef __SIZEOF_INT128__
using Native = unsigned __int128;

Native ToNative(const mcx::PortableUInt128& value)
{
  return (static_cast<Native>(value.HighHalf()) << 64) | value.LowHalf();
}
#endif

// The ids 0 .. level.size() - 1 sorted by level (-1: not indexed), as the
// density index lists them; offsets (levels + 1 entries) bounds each level.
std::vector<std::uint32_t> SortByLevel(
  const std::vector<int>& level, std::int64_t levels, std::vector<std::int64_t>& offsets)
{
  std::vector<std::uint32_t> sorted(level.size());
  mcx::CountingSortByBin<std::uint32_t>(
    mcx::SerialExecutor(), static_cast<std::int64_t>(level.size()), levels,
    [&](std::int64_t id) { return static_cast<std::int64_t>(level[static_cast<std::size_t>(id)]); },
    offsets, sorted.data());
  return sorted;
}
}

TEST(WideInteger, PortableMatchesTheCompilersType)
{
#ifndef __SIZEOF_INT128__
  GTEST_SKIP() << "this compiler has no 128-bit integer to compare with";
#else
  std::mt19937_64 random(12345);
  for (int trial = 0; trial < 20000; ++trial)
  {
    const std::uint64_t a = random(), b = random(), c = random() >> (random() % 64);
    const unsigned shift = static_cast<unsigned>(random() % 128);
    mcx::PortableUInt128 x(a, b);
    const Native nx = ToNative(x);
    ASSERT_TRUE(ToNative(x << shift) == (nx << shift));
    mcx::PortableUInt128 y(c);
    y += x;
    ASSERT_TRUE(ToNative(y) == nx + c);
    ASSERT_EQ(nx < static_cast<Native>(c), x < mcx::PortableUInt128(c));
    // Conversions to double round to nearest, as the compiler's do; values
    // of every magnitude, including those just off a rounding tie.
    const mcx::PortableUInt128 z = mcx::PortableUInt128(a >> (random() % 64), b) << (random() % 64);
    ASSERT_EQ(static_cast<double>(ToNative(z)), static_cast<double>(z));
    const double d = std::ldexp(static_cast<double>(a >> 11), static_cast<int>(random() % 74));
    ASSERT_TRUE(ToNative(mcx::PortableUInt128::FromDouble(d)) == static_cast<Native>(d));
    std::uint64_t high, low;
    mcx::PortableMultiply64(a, c, high, low);
    const Native product = static_cast<Native>(a) * c;
    ASSERT_EQ(static_cast<std::uint64_t>(product >> 64), high);
    ASSERT_EQ(static_cast<std::uint64_t>(product), low);
  }
  // Ties round to even, with and without a sticky bit below.
  const mcx::PortableUInt128 tie(1, 0x400); // 2^64 + 2^10: halfway at 2^64 precision 2^11
  EXPECT_EQ(static_cast<double>(ToNative(tie)), static_cast<double>(tie));
  const mcx::PortableUInt128 aboveTie(1, 0x401);
  EXPECT_EQ(static_cast<double>(ToNative(aboveTie)), static_cast<double>(aboveTie));
  const mcx::PortableUInt128 top(~std::uint64_t(0), ~std::uint64_t(0));
  EXPECT_EQ(std::ldexp(1.0, 128), static_cast<double>(top));
  EXPECT_TRUE(mcx::PortableUInt128::FromDouble(-1.0) == mcx::PortableUInt128());
#endif
}

TEST(WideInteger, FixedPointIncrementsAboveSixtyFourBits)
{
  // A perspective weight near the largest allowed (1e12) gives an increment
  // above 2^64, which the fixed point keeps.
  const mcx::FixedSum increment = mcx::FixedIncrement(1e12);
  EXPECT_EQ(1e12 * 4294967296.0, mcx::ToDouble(increment));
  EXPECT_TRUE(mcx::FixedIncrement(1.0) == mcx::FixedOneInteger);
  EXPECT_TRUE(mcx::FixedIncrement(0.0) == mcx::FixedSum(0));
}

TEST(Executor, CountingSortIsTheSameOnOneThreadAndOnSeveral)
{
  const std::int64_t n = 300000, bins = 37;
  std::vector<int> bin(static_cast<std::size_t>(n));
  std::mt19937 random(7);
  for (int& b : bin)
  {
    b = static_cast<int>(random() % (bins + 1)) - 1; // -1: left out
  }
  auto binOf = [&](std::int64_t id)
  { return static_cast<std::int64_t>(bin[static_cast<std::size_t>(id)]); };
  std::vector<std::uint32_t> serial(static_cast<std::size_t>(n)),
    threaded(static_cast<std::size_t>(n));
  std::vector<std::int64_t> serialOffsets, threadedOffsets;
  const std::int64_t leftSerial = mcx::CountingSortByBin<std::uint32_t>(
    mcx::SerialExecutor(), n, bins, binOf, serialOffsets, serial.data());
  const std::int64_t leftThreaded = mcx::CountingSortByBin<std::uint32_t>(
    ThreadExecutor(), n, bins, binOf, threadedOffsets, threaded.data());
  EXPECT_EQ(leftSerial, leftThreaded);
  EXPECT_EQ(serialOffsets, threadedOffsets);
  EXPECT_EQ(serial, threaded);
  EXPECT_GT(leftSerial, 0);
}

TEST(EveryVoxelSource, EachKeptVoxelOnceByItsIdOnTheWholeAndOnAnyPieces)
{
  // A 7 x 5 x 6 volume of random levels (some voxels not indexed), two
  // levels of zero weight: the source emits each voxel of a kept level
  // once, numbered by its id, at its point (centre plus the kernel offset
  // of stream id) with its level's weight, for any split of [0, Size()).
  // z-slab pieces, one of them empty, emit together exactly what the whole
  // volume does.
  const std::uint64_t nx = 7, ny = 5, nz = 6, layer = nx * ny;
  const std::int64_t levels = 6;
  std::mt19937 random(11);
  std::vector<int> level(static_cast<std::size_t>(layer * nz));
  for (int& l : level)
  {
    l = static_cast<int>(random() % (levels + 1)) - 1; // -1: not indexed
  }
  const std::vector<double> weights = { 0.5, 0.0, 2.0, 1.25, 0.0, 3.0 };
  struct Emitted
  {
    double P[3];
    double Weight;
  };
  // What the source of z-slab [z0, z1) emits, by voxel number, in chunks
  // of random length.
  auto emit = [&](std::uint64_t z0, std::uint64_t z1, std::map<std::uint64_t, Emitted>& out)
  {
    const std::int64_t count = static_cast<std::int64_t>((z1 - z0) * layer);
    std::vector<std::int64_t> offsets;
    std::vector<std::uint32_t> sorted(static_cast<std::size_t>(count));
    mcx::CountingSortByBin<std::uint32_t>(
      mcx::SerialExecutor(), count, levels,
      [&](std::int64_t id)
      { return static_cast<std::int64_t>(level[static_cast<std::size_t>(z0 * layer) + id]); },
      offsets, sorted.data());
    mcx::EveryVoxelSource<std::uint32_t> source;
    source.SortedIds = sorted.data();
    source.LevelOffsets = offsets.data();
    source.NumberOfLevels = levels;
    source.LevelWeights = weights.data();
    source.Decoder = mcx::VoxelDecoder<std::uint32_t>(nx, ny);
    source.PieceStart[2] = z0;
    source.WholeDimensions[0] = nx;
    source.WholeDimensions[1] = ny;
    source.Centres = false;
    source.Seed = 3;
    source.Prepare();
    for (std::uint64_t b = 0; b < source.Size();)
    {
      const std::uint64_t e = std::min(source.Size(), b + 1 + random() % 40);
      source.Generate(b, e,
        [&](std::uint64_t k, const double p[3], double weight)
        {
          EXPECT_EQ(0u, out.count(k)) << "voxel " << k << " twice";
          out[k] = Emitted{ { p[0], p[1], p[2] }, weight };
        });
      b = e;
    }
  };
  std::map<std::uint64_t, Emitted> whole, pieces;
  emit(0, nz, whole);
  for (const auto& slab :
    { std::make_pair(0, 2), std::make_pair(2, 3), std::make_pair(3, 3), std::make_pair(3, 6) })
  {
    emit(slab.first, slab.second, pieces);
  }
  std::size_t expected = 0;
  for (std::uint64_t id = 0; id < layer * nz; ++id)
  {
    const int l = level[static_cast<std::size_t>(id)];
    const bool kept = l >= 0 && weights[static_cast<std::size_t>(l)] > 0;
    expected += kept ? 1 : 0;
    ASSERT_EQ(kept ? 1u : 0u, whole.count(id)) << "voxel " << id;
    if (!kept)
    {
      continue;
    }
    const Emitted& w = whole[id];
    EXPECT_EQ(weights[static_cast<std::size_t>(l)], w.Weight) << "voxel " << id;
    const double centre[3] = { static_cast<double>(id % nx), static_cast<double>((id / nx) % ny),
      static_cast<double>(id / layer) };
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_LT(std::abs(w.P[a] - centre[a]), 1.0) << "voxel " << id; // the tent's support
      EXPECT_EQ(w.P[a], pieces[id].P[a]) << "voxel " << id;
    }
    EXPECT_EQ(w.Weight, pieces[id].Weight) << "voxel " << id;
  }
  EXPECT_EQ(expected, whole.size());
  EXPECT_EQ(expected, pieces.size());
  EXPECT_GT(expected, 60u);
}

TEST(ViewOrder, LevelsGroupIntoBinsOfEqualWidthAndAtMostTwoTo16Levels)
{
  // Values 0, 1, ..., 99 in 4 bins of width 99 / 4: 0-24, 25-49, 50-74 and
  // 75-99 (the top value in the last bin); empty bins are left out.
  std::vector<double> values(100);
  std::iota(values.begin(), values.end(), 0.0);
  EXPECT_EQ((std::vector<std::int64_t>{ 0, 25, 50, 75, 100 }),
    mcx::GroupLevelsIntoBins(values.data(), 100, 4));
  const std::vector<double> gap = { 0, 1, 10 };
  EXPECT_EQ((std::vector<std::int64_t>{ 0, 2, 3 }), mcx::GroupLevelsIntoBins(gap.data(), 3, 4));
  EXPECT_EQ((std::vector<std::int64_t>{ 0, 1 }), mcx::GroupLevelsIntoBins(gap.data(), 1, 16));
  EXPECT_EQ((std::vector<std::int64_t>{ 0 }), mcx::GroupLevelsIntoBins(gap.data(), 0, 16));
  // One bin's worth of 2^16 + 5 levels opens a second bin after 2^16.
  std::vector<double> many((std::size_t(1) << 16) + 5);
  std::iota(many.begin(), many.end(), 0.0);
  EXPECT_EQ((std::vector<std::int64_t>{ 0, std::int64_t(1) << 16, std::int64_t(many.size()) }),
    mcx::GroupLevelsIntoBins(many.data(), static_cast<std::int64_t>(many.size()), 1));
}

TEST(ControlImage, SystematicPicksExpectEachVoxelOnceOverTheirStarts)
{
  // Runs of 1 to 299 voxels, strides of 1.01 to 100: an even count, at
  // least 2, of about n / stride picks (each voxel twice, Interval 1/2,
  // where that many picks would take every voxel) that lie in the run and
  // rise, those of one parity never on one voxel twice; averaged over the
  // starts (a midpoint rule of G of them, within 2 (1 / Interval + 2) / G of
  // the integral for each voxel) each voxel is picked 1 / Interval times.
  const int G = 10000;
  for (std::int64_t n : { 1, 2, 3, 5, 17, 64, 299 })
  {
    for (double stride : { 1.01, 1.5, 2.0, 7.3, 100.0 })
    {
      const std::string what = "n " + std::to_string(n) + " stride " + std::to_string(stride);
      const mcx::SystematicPicks shape(n, stride, 0.0);
      ASSERT_GE(shape.Count, 2) << what;
      ASSERT_EQ(0, shape.Count % 2) << what;
      const double sampled = 2.0 * std::ceil(static_cast<double>(n) / (2.0 * stride));
      if (sampled >= static_cast<double>(n))
      {
        EXPECT_EQ(2 * n, shape.Count) << what;
        EXPECT_EQ(0.5, shape.Interval) << what;
      }
      else
      {
        EXPECT_EQ(sampled, static_cast<double>(shape.Count)) << what;
        EXPECT_GE(static_cast<double>(shape.Count), static_cast<double>(n) / stride) << what;
      }
      EXPECT_DOUBLE_EQ(static_cast<double>(n), shape.Interval * static_cast<double>(shape.Count));
      std::vector<double> picked(static_cast<std::size_t>(n), 0.0);
      for (int g = 0; g < G; ++g)
      {
        const mcx::SystematicPicks picks(n, stride, (g + 0.5) / G);
        ASSERT_EQ(shape.Count, picks.Count);
        for (std::int64_t j = 0; j < picks.Count; ++j)
        {
          const std::int64_t i = picks[j];
          ASSERT_TRUE(i >= 0 && i < n) << what;
          ASSERT_TRUE(j == 0 || picks[j - 1] <= i) << what;
          ASSERT_TRUE(j < 2 || picks[j - 2] < i) << what;
          picked[static_cast<std::size_t>(i)] += 1.0 / G;
        }
      }
      const double expected = 1.0 / shape.Interval;
      for (std::int64_t i = 0; i < n; ++i)
      {
        EXPECT_NEAR(expected, picked[static_cast<std::size_t>(i)], 2.0 * (expected + 2.0) / G)
          << what << " voxel " << i;
      }
    }
  }
}

TEST(ControlImage, ABinsPicksInAnyRangesAreThoseOfTheWholeBin)
{
  // A bin of 500 runs of 0 to 40 entries after another bin's 7: its picks
  // visited in ranges of any size (a thread's share) are those visited at
  // once, in the same order with the same weights and halves; each run's
  // picks carry its entries exactly (Count x Interval) and alternate
  // between the halves; another seed moves them.
  const std::int64_t cells = 500;
  std::vector<std::int64_t> keyStarts(static_cast<std::size_t>(2 * cells + 1), 0);
  std::mt19937_64 random(5);
  for (std::size_t k = 1; k < keyStarts.size(); ++k)
  {
    keyStarts[k] = keyStarts[k - 1] + (k <= static_cast<std::size_t>(cells) ? 7 : random() % 41);
  }
  struct Pick
  {
    std::int64_t Entry;
    double Weight;
    bool FirstHalf;
    bool operator==(const Pick& o) const
    {
      return this->Entry == o.Entry && this->Weight == o.Weight && this->FirstHalf == o.FirstHalf;
    }
  };
  const std::int64_t* second = keyStarts.data() + cells;
  for (double stride : { 2.5, 9.0 })
  {
    const mcx::ControlPicks picks(second, 1, cells, stride, mcx::SeedKey(3));
    std::vector<Pick> whole;
    picks.Visit(0, picks.Count(),
      [&](std::int64_t entry, double weight, bool firstHalf) {
        whole.push_back(Pick{ entry, weight, firstHalf });
      });
    ASSERT_EQ(static_cast<std::size_t>(picks.Count()), whole.size());
    for (std::int64_t grain : { 1, 3, 64, 1000 })
    {
      std::vector<Pick> ranges;
      for (std::int64_t begin = 0; begin < picks.Count(); begin += grain)
      {
        picks.Visit(begin, std::min(picks.Count(), begin + grain),
          [&](std::int64_t entry, double weight, bool firstHalf) {
            ranges.push_back(Pick{ entry, weight, firstHalf });
          });
      }
      EXPECT_TRUE(ranges == whole) << "stride " << stride << " grain " << grain;
    }
    // Run by run: the entries in the run, the weights summing to its size.
    std::size_t i = 0;
    for (std::int64_t c = 0; c < cells; ++c)
    {
      const std::int64_t n = second[c + 1] - second[c];
      double carried = 0.0;
      for (std::int64_t j = 0; i < whole.size() && whole[i].Entry < second[c + 1] && j < 2 * n;
           ++i, ++j)
      {
        ASSERT_GE(whole[i].Entry, second[c]);
        EXPECT_EQ(j % 2 == 0, whole[i].FirstHalf);
        carried += whole[i].Weight;
      }
      EXPECT_DOUBLE_EQ(static_cast<double>(n), carried) << "stride " << stride << " run " << c;
    }
    EXPECT_EQ(whole.size(), i);
    const mcx::ControlPicks other(second, 1, cells, stride, mcx::SeedKey(4));
    std::vector<Pick> moved;
    other.Visit(0, other.Count(),
      [&](std::int64_t entry, double weight, bool firstHalf) {
        moved.push_back(Pick{ entry, weight, firstHalf });
      });
    EXPECT_FALSE(moved == whole) << "stride " << stride;
  }
}

TEST(HugePageAllocator, LargeArraysAlignToHugePagesAndAllHoldTheirValues)
{
  using Allocator = mcx::HugePageAllocator<std::uint32_t>;
  for (const std::size_t n : { std::size_t(0), std::size_t(1000), Allocator::HugeFrom / 4 + 3 })
  {
    std::vector<std::uint32_t, Allocator> values(n);
    std::iota(values.begin(), values.end(), 7u);
    EXPECT_TRUE(std::all_of(values.begin(), values.end(),
      [&](const std::uint32_t& v)
      { return v == 7u + static_cast<std::uint32_t>(&v - values.data()); }));
#if defined(__linux__)
    if (n * sizeof(std::uint32_t) >= Allocator::HugeFrom)
    {
      EXPECT_EQ(0u, reinterpret_cast<std::uintptr_t>(values.data()) % Allocator::HugePage);
    }
#endif
    values.resize(n / 2); // shrinks in place; the large block is freed with the vector
    EXPECT_EQ(n / 2, values.size());
  }
  EXPECT_THROW(
    Allocator().allocate(std::numeric_limits<std::size_t>::max() / 2), std::bad_array_new_length);
}

TEST(ViewOrder, PositionInPixelIsTheMortonRankOfSixteenthPixelSquares)
{
  EXPECT_EQ(0, mcx::PositionInPixel(0.0, 0.0));
  EXPECT_EQ(0, mcx::PositionInPixel(7.01, -3.0)); // only the fraction counts
  EXPECT_EQ(255, mcx::PositionInPixel(0.999, 2.9999));
  EXPECT_EQ(128, mcx::PositionInPixel(0.5, 0.0)); // the column's high bit first
  EXPECT_EQ(64, mcx::PositionInPixel(0.0, 0.5));
  // Column 1010, row 0101: the pairs 10 01 10 01.
  EXPECT_EQ(0b10011001, mcx::PositionInPixel(10.0 / 16 + 0.01, 5.0 / 16 + 0.01));
  EXPECT_EQ(0b10100000, mcx::PositionInPixel(-0.25, 0.0)); // column 12 (1100), row 0
  // Each aligned quarter of the pixel is one run of 64 ranks.
  for (int column = 0; column < 16; ++column)
  {
    for (int row = 0; row < 16; ++row)
    {
      const int quarter = 2 * (column / 8) + row / 8;
      EXPECT_EQ(quarter, mcx::PositionInPixel((column + 0.5) / 16, (row + 0.5) / 16) / 64);
    }
  }
}

TEST(ViewOrder, GridPixelPositionsArePixelPositionBitForBit)
{
  // A grid in an oblique view whose voxels fall in the image, off it and
  // (perspective) behind the near plane: the tables' positions and
  // refusals are PixelPosition's.
  const double origin[3] = { -7.0, -4.0, -90.0 };
  const double matrix[9] = { 0.6, 0.02, 0.0, -0.01, 0.5, 0.03, 0.015, 0.0, 4.0 };
  const std::int64_t nx = 23, ny = 17, nz = 29;
  for (const bool perspective : { false, true })
  {
    const mcx::ProjectionGeometry g = ObliqueTestGeometry(perspective);
    const mcx::PixelBinner binner(g, origin, matrix);
    const mcx::GridPixelPositions positions(binner, nx, ny, nz);
    int inImage = 0, refused = 0;
    for (std::int64_t k = 0; k < nz; ++k)
    {
      for (std::int64_t j = 0; j < ny; ++j)
      {
        for (std::int64_t i = 0; i < nx; ++i)
        {
          const double p[3] = { double(i), double(j), double(k) };
          double ex = 0, ey = 0, fx = 0, fy = 0;
          const bool expected = binner.PixelPosition(p, ex, ey);
          ASSERT_EQ(expected,
            positions.PixelPosition(std::uint64_t(i), std::uint64_t(j), std::uint64_t(k), fx, fy))
            << i << " " << j << " " << k;
          if (expected)
          {
            ASSERT_EQ(0, std::memcmp(&ex, &fx, sizeof(double))) << ex << " against " << fx;
            ASSERT_EQ(0, std::memcmp(&ey, &fy, sizeof(double))) << ey << " against " << fy;
            inImage += ex >= 0 && ex < g.Size[0] && ey >= 0 && ey < g.Size[1] ? 1 : 0;
          }
          else
          {
            ++refused;
          }
        }
      }
    }
    // Both kinds of voxel were compared.
    EXPECT_GT(inImage, 500) << perspective;
    // Off the grid (an id past the volume): not located, nothing read.
    double fx = 0, fy = 0;
    EXPECT_FALSE(positions.PixelPosition(std::uint64_t(nx), 0, 0, fx, fy));
    EXPECT_FALSE(positions.PixelPosition(0, std::uint64_t(ny), 0, fx, fy));
    EXPECT_FALSE(positions.PixelPosition(0, 0, std::uint64_t(nz), fx, fy));
    if (perspective)
    {
      EXPECT_GT(refused, 500);
    }
  }
}

TEST(ViewOrder, EachVoxelOnceByBinCellPositionLevelAndId)
{
  // Voxels of random levels in a random cell and position each: the order
  // holds each indexed voxel once, with its level, sorted by (bin, cell,
  // position, level, id), whatever the executor. 37 cells: one counting
  // pass by (bin, cell); 3001: by the key's high digit, then its low digit.
  for (const std::int64_t cells : { std::int64_t(37), std::int64_t(3001) })
  {
    for (const std::int64_t n : { std::int64_t(0), std::int64_t(1), std::int64_t(200003) })
    {
      const std::int64_t levels = 9;
      ASSERT_EQ(cells == 37 ? 0 : 3, mcx::ViewOrderDigits(4, cells).LowBits);
      std::mt19937 random(static_cast<unsigned>(n) + 11);
      std::vector<int> level(static_cast<std::size_t>(n)), cell(static_cast<std::size_t>(n)),
        position(static_cast<std::size_t>(n));
      for (std::size_t id = 0; id < level.size(); ++id)
      {
        level[id] = static_cast<int>(random() % (levels + 1)) - 1; // -1: not indexed
        cell[id] = static_cast<int>(random() % cells);
        // Few positions in the last cell (the off-image cell: 0), all in others.
        position[id] = cell[id] == cells - 1 ? 0 : static_cast<int>(random() % 256);
      }
      std::vector<std::int64_t> offsets;
      const std::vector<std::uint32_t> sorted = SortByLevel(level, levels, offsets);
      const std::vector<std::int64_t> bins = { 0, 2, 3, 7, 9 };
      auto cellOf = [&](std::uint32_t id)
      {
        mcx::ViewCell where;
        where.Cell = cell[id];
        where.Position = static_cast<std::uint8_t>(position[id]);
        return where;
      };
      auto keepGoing = [](double) { return true; };
      mcx::ViewOrder<std::uint32_t> serial, threaded;
      ASSERT_TRUE(serial.Build(mcx::SerialExecutor(), sorted.data(), offsets.data(), levels, bins,
        cells, cellOf, keepGoing));
      ASSERT_TRUE(threaded.Build(
        ThreadExecutor(), sorted.data(), offsets.data(), levels, bins, cells, cellOf, keepGoing));
      EXPECT_EQ(serial.Ids, threaded.Ids) << n;
      EXPECT_EQ(serial.LevelInBin, threaded.LevelInBin) << n;
      EXPECT_EQ(serial.BinOffsets, threaded.BinOffsets) << n;
      // Each voxel's cell and position kept in 64 bits (views of more than
      // 2^24 cells) instead of 32: the same order, then 32 bits again into
      // the recycled arrays.
      ASSERT_EQ(4, mcx::ViewOrderDigits::SlotKeyBytes(cells));
      mcx::ViewOrder<std::uint32_t> wide;
      ASSERT_TRUE(wide.BuildWithSlotKeys<std::uint64_t>(
        ThreadExecutor(), sorted.data(), offsets.data(), levels, bins, cells, cellOf, keepGoing));
      EXPECT_EQ(serial.Ids, wide.Ids) << n;
      EXPECT_EQ(serial.LevelInBin, wide.LevelInBin) << n;
      EXPECT_EQ(serial.KeyStarts, wide.KeyStarts) << n;
      EXPECT_EQ(static_cast<std::size_t>(offsets[levels]), wide.WideSlotKeys.size());
      mcx::ViewOrder<std::uint32_t> narrowAgain;
      narrowAgain.Recycle(std::move(wide));
      ASSERT_TRUE(narrowAgain.Build(
        ThreadExecutor(), sorted.data(), offsets.data(), levels, bins, cells, cellOf, keepGoing));
      EXPECT_EQ(serial.Ids, narrowAgain.Ids) << n;
      // Let go, not kept beside the narrow keys.
      EXPECT_EQ(0u, narrowAgain.WideSlotKeys.capacity());
      // What a next Build writes again: ids, levels, digits and keys of
      // the width its cells take (a view of more than 2^24 cells: wide).
      const double voxels = static_cast<double>(offsets[levels]);
      EXPECT_EQ(voxels * (4 + 2 + 4 + 4), narrowAgain.RecyclableBytes(offsets[levels], cells));
      EXPECT_EQ(voxels * (4 + 2 + 4), narrowAgain.RecyclableBytes(offsets[levels], (1 << 24) + 1));
      EXPECT_EQ(0.0, narrowAgain.RecyclableBytes(offsets[levels] + 1, cells));
      // Built into the arrays of an order of other cells (Recycle), or of
      // fewer voxels: the same order.
      for (const std::int64_t first : { n, n / 2 })
      {
        mcx::ViewOrder<std::uint32_t> previous, recycled;
        std::vector<std::int64_t> fewer(offsets);
        for (std::int64_t& o : fewer)
        {
          o = std::min(o, first);
        }
        auto shifted = [&](std::uint32_t id)
        {
          mcx::ViewCell where = cellOf(id);
          where.Cell = (where.Cell + 5) % cells;
          where.Position = static_cast<std::uint8_t>(where.Position ^ 0x5a);
          return where;
        };
        ASSERT_TRUE(previous.Build(
          ThreadExecutor(), sorted.data(), fewer.data(), levels, bins, cells, shifted, keepGoing));
        recycled.Recycle(std::move(previous));
        ASSERT_TRUE(recycled.Build(
          ThreadExecutor(), sorted.data(), offsets.data(), levels, bins, cells, cellOf, keepGoing));
        EXPECT_EQ(serial.Ids, recycled.Ids) << n << " after " << first;
        EXPECT_EQ(serial.LevelInBin, recycled.LevelInBin) << n << " after " << first;
        EXPECT_EQ(serial.BinOffsets, recycled.BinOffsets) << n << " after " << first;
      }
      ASSERT_EQ(4, serial.NumberOfBins());
      ASSERT_EQ(static_cast<std::size_t>(offsets[levels]), serial.Ids.size());

      std::vector<int> seen(static_cast<std::size_t>(n), 0);
      std::array<std::int64_t, 5> key{}, previous{ -1, -1, -1, -1, -1 };
      for (std::int64_t b = 0; b < 4; ++b)
      {
        EXPECT_EQ(offsets[bins[static_cast<std::size_t>(b)]],
          serial.BinOffsets[static_cast<std::size_t>(b)]);
        for (std::int64_t k = serial.BinOffsets[static_cast<std::size_t>(b)];
             k < serial.BinOffsets[static_cast<std::size_t>(b + 1)]; ++k)
        {
          const std::uint32_t id = serial.Ids[static_cast<std::size_t>(k)];
          ++seen[id];
          const std::int64_t l =
            bins[static_cast<std::size_t>(b)] + serial.LevelInBin[static_cast<std::size_t>(k)];
          ASSERT_EQ(level[id], l) << "entry " << k;
          key = { b, cell[id], position[id], l, id };
          ASSERT_LT(previous, key) << "entry " << k;
          previous = key;
        }
      }
      for (std::int64_t id = 0; id < n; ++id)
      {
        ASSERT_EQ(
          level[static_cast<std::size_t>(id)] >= 0 ? 1 : 0, seen[static_cast<std::size_t>(id)]);
      }
      // Stopped after the first or the second pass: no order.
      for (const double last : { 0.3, 0.6 })
      {
        mcx::ViewOrder<std::uint32_t> stopped;
        EXPECT_FALSE(stopped.Build(mcx::SerialExecutor(), sorted.data(), offsets.data(), levels,
          bins, cells, cellOf, [last](double fraction) { return fraction < last; }));
        EXPECT_TRUE(stopped.BinOffsets.empty());
      }
    }
  }
}

TEST(ViewOrder, KeysAtTheWidthsBoundaryKeepTheHighestCells)
{
  // The most cells each key width holds: 2^24 (a view of 2^24 - 1 pixels)
  // in 32 bits, 2^24 + 1 (a 4096 x 4096 view) in 64, whose last cell, 2^24,
  // a key cut to 32 bits would sort as cell 0. Voxels in the top cells and
  // in low ones, in an order of one bin.
  for (const std::int64_t cells : { std::int64_t(1) << 24, (std::int64_t(1) << 24) + 1 })
  {
    ASSERT_EQ(cells == (std::int64_t(1) << 24) ? 4 : 8, mcx::ViewOrderDigits::SlotKeyBytes(cells));
    const std::vector<std::int64_t> cellOfId = { cells - 1, cells - 2, 3, cells - 1, 0, 1,
      cells - 3, 5 };
    const std::vector<int> level(cellOfId.size(), 0);
    std::vector<std::int64_t> offsets;
    const std::vector<std::uint32_t> sorted = SortByLevel(level, 1, offsets);
    auto cellOf = [&](std::uint32_t id)
    {
      mcx::ViewCell where;
      where.Cell = cellOfId[id];
      // Positions against the ids' order; none off the image (the last cell).
      where.Position = static_cast<std::uint8_t>(where.Cell == cells - 1 ? 0 : 255 - id);
      return where;
    };
    mcx::ViewOrder<std::uint32_t> order;
    ASSERT_TRUE(order.Build(mcx::SerialExecutor(), sorted.data(), offsets.data(), 1, { 0, 1 },
      cells, cellOf, [](double) { return true; }));
    // By cell: ids 4, 5, 2, 7, 6, 1, then 0 and 3 off the image (the same
    // position, so as the index lists them).
    EXPECT_EQ((std::vector<std::uint32_t>{ 4, 5, 2, 7, 6, 1, 0, 3 }),
      std::vector<std::uint32_t>(order.Ids.begin(), order.Ids.end()))
      << cells << " cells";
    EXPECT_EQ(6, order.KeyStarts[static_cast<std::size_t>(cells - 1)]);
    EXPECT_EQ(5, order.KeyStarts[static_cast<std::size_t>(cells - 2)]);
  }
}

namespace
{
// The view order's Halton samples of a toy volume: Cells cells of PerCell
// voxels, each voxel's cell, position in its cell and level (0 to 3) random
// (so the index's own order, by level, stratifies neither the cells nor
// the positions), levels {0, 1} and {2, 3} in two bins. Returns each cell's
// estimate of its mass (sample k carries W / M times its weight, W the
// total mass) and keeps each quarter's of its cell (the four aligned runs
// of 64 positions); the order's bin means and ratios go to the caller.
struct ToyViewOrder
{
  static constexpr std::int64_t Cells = 4, PerCell = std::int64_t(1) << 14;
  std::vector<int> Level = std::vector<int>(static_cast<std::size_t>(Cells * PerCell));
  std::vector<std::uint8_t> Position =
    std::vector<std::uint8_t>(static_cast<std::size_t>(Cells * PerCell));
  std::vector<std::int64_t> Cell =
    std::vector<std::int64_t>(static_cast<std::size_t>(Cells * PerCell));
  std::vector<std::int64_t> Offsets;
  std::vector<double> Exact = std::vector<double>(static_cast<std::size_t>(Cells), 0.0);
  std::vector<double> ExactQuarters = std::vector<double>(static_cast<std::size_t>(4 * Cells));
  std::vector<double> EstimatedQuarters = std::vector<double>(static_cast<std::size_t>(4 * Cells));
  double Total = 0;

  ToyViewOrder()
  {
    std::mt19937 random(3);
    for (int& l : this->Level)
    {
      l = static_cast<int>(random() % 4);
    }
    for (std::uint8_t& p : this->Position)
    {
      p = static_cast<std::uint8_t>(random() % 256);
    }
    for (std::size_t id = 0; id < this->Cell.size(); ++id)
    {
      this->Cell[id] = static_cast<std::int64_t>(id) / PerCell;
    }
    std::shuffle(this->Cell.begin(), this->Cell.end(), random);
  }

  // Each cell's estimate and the sum of the sample weights for `weight`;
  // means and ratios are the order's.
  std::vector<double> Estimate(const double weight[4], unsigned exponent,
    std::vector<double>& means, std::vector<double>& ratios, double& weightSum)
  {
    const std::int64_t n = Cells * PerCell;
    const std::vector<std::uint32_t> sorted = SortByLevel(this->Level, 4, this->Offsets);
    mcx::ViewOrder<std::uint32_t> order;
    auto cellOf = [&](std::uint32_t id)
    {
      mcx::ViewCell where;
      where.Cell = this->Cell[id];
      where.Position = this->Position[id];
      return where;
    };
    EXPECT_TRUE(order.Build(mcx::SerialExecutor(), sorted.data(), this->Offsets.data(), 4,
      { 0, 2, 4 }, Cells, cellOf, [](double) { return true; }));
    order.Weights(weight, this->Offsets.data(), means, ratios);
    std::fill(this->Exact.begin(), this->Exact.end(), 0.0);
    std::fill(this->ExactQuarters.begin(), this->ExactQuarters.end(), 0.0);
    std::fill(this->EstimatedQuarters.begin(), this->EstimatedQuarters.end(), 0.0);
    this->Total = 0;
    for (std::size_t id = 0; id < static_cast<std::size_t>(n); ++id)
    {
      const double w = weight[this->Level[id]];
      this->Exact[static_cast<std::size_t>(this->Cell[id])] += w;
      this->ExactQuarters[this->QuarterOf(id)] += w;
      this->Total += w;
    }
    const mcx::TransferTable table =
      mcx::BuildTransferTable(means.data(), order.BinOffsets.data(), 2);
    mcx::SampleSource<std::uint32_t> source;
    source.SortedIds = order.Ids.data();
    source.LevelOffsets = order.BinOffsets.data();
    source.NumberOfLevels = 2;
    source.SetTable(table);
    source.Decoder = mcx::VoxelDecoder<std::uint32_t>(static_cast<std::uint64_t>(n), 1);
    source.LevelInBin = order.LevelInBin.data();
    source.BinFirstLevel = order.BinFirstLevel.data();
    source.LevelRatio = ratios.data();
    source.Centres = true;
    source.Exponent = exponent;
    const double m = static_cast<double>(source.NumberOfSamples());
    std::vector<double> estimate(static_cast<std::size_t>(Cells), 0.0);
    weightSum = 0;
    auto sink = [&](std::uint64_t, const double p[3], double w)
    {
      const std::size_t id = static_cast<std::size_t>(p[0]);
      estimate[static_cast<std::size_t>(this->Cell[id])] += w * this->Total / m;
      this->EstimatedQuarters[this->QuarterOf(id)] += w * this->Total / m;
      weightSum += w;
    };
    source.Generate(0, source.NumberOfSamples(), sink);
    return estimate;
  }

  std::size_t QuarterOf(std::size_t id) const
  {
    return static_cast<std::size_t>(4 * this->Cell[id] + this->Position[id] / 64);
  }

  double Count(int level) const
  {
    return static_cast<double>(this->Offsets[level + 1] - this->Offsets[level]);
  }
};
}

TEST(ViewOrder, HaltonSamplesStratifyEachCellAndItsQuartersToWithinOneCountPerBin)
{
  // Equal weights inside each bin (ratio 1): in the view order (bin, cell,
  // position) each cell's count in each bin, and each quarter's of the cell
  // (a run of 64 positions), is its expected count rounded up or down, so
  // each estimate is exact to within W / M per bin, where Monte Carlo's
  // error is sqrt(W_c W / M), 60 times more for a cell here, 30 for a
  // quarter.
  ToyViewOrder toy;
  const double weight[4] = { 1, 1, 2, 2 };
  std::vector<double> means, ratios;
  double weightSum = 0;
  const std::vector<double> estimate = toy.Estimate(weight, 16, means, ratios, weightSum);
  EXPECT_EQ((std::vector<double>{ 1, 1 }), std::vector<double>(ratios.begin(), ratios.begin() + 2));
  EXPECT_EQ((std::vector<double>{ 1, 1 }), std::vector<double>(ratios.begin() + 2, ratios.end()));
  const double m = std::ldexp(1.0, 16) - 1;
  for (std::int64_t c = 0; c < ToyViewOrder::Cells; ++c)
  {
    const double exact = toy.Exact[static_cast<std::size_t>(c)];
    EXPECT_NEAR(exact, estimate[static_cast<std::size_t>(c)], 2 * toy.Total / m) << "cell " << c;
  }
  for (std::size_t q = 0; q < toy.ExactQuarters.size(); ++q)
  {
    EXPECT_NEAR(toy.ExactQuarters[q], toy.EstimatedQuarters[q], 2 * toy.Total / m)
      << "quarter " << q;
  }
  EXPECT_DOUBLE_EQ(m, weightSum);
}

TEST(ViewOrder, HaltonSamplesWeightedByTheBinMeanAreUnbiased)
{
  // Weights 1, 3 | 0, 2: a voxel drawn uniformly in its bin carries w / (the
  // bin's mean w), so each cell's estimate is unbiased, and its error is the
  // spread of those ratios over the cell's samples: with n_b samples of bin
  // b in the cell and var_b the ratios' variance over the bin's voxels,
  // sigma = (W / M) sqrt(sum_b n_b var_b). Each cell within 2 W / M
  // (rounding) + 4 sigma; the weights sum to M within 4 sigma of the whole.
  ToyViewOrder toy;
  const double weight[4] = { 1, 3, 0, 2 };
  std::vector<double> means, ratios;
  double weightSum = 0;
  const unsigned exponent = 16;
  const std::vector<double> estimate = toy.Estimate(weight, exponent, means, ratios, weightSum);
  const double count[4] = { toy.Count(0), toy.Count(1), toy.Count(2), toy.Count(3) };
  ASSERT_EQ(2u, means.size());
  EXPECT_DOUBLE_EQ((1 * count[0] + 3 * count[1]) / (count[0] + count[1]), means[0]);
  EXPECT_DOUBLE_EQ(2 * count[3] / (count[2] + count[3]), means[1]);
  EXPECT_DOUBLE_EQ(3 / means[0], ratios[1]);
  EXPECT_EQ(0.0, ratios[2]);
  double variance[2];
  for (int b = 0; b < 2; ++b)
  {
    const int l0 = 2 * b;
    const double n = count[l0] + count[l0 + 1];
    variance[b] = (count[l0] * (ratios[l0] - 1) * (ratios[l0] - 1) +
                    count[l0 + 1] * (ratios[l0 + 1] - 1) * (ratios[l0 + 1] - 1)) /
      n;
  }
  const double m = std::ldexp(1.0, exponent) - 1;
  const double unit = toy.Total / m;
  double wholeVariance = 0;
  for (std::int64_t c = 0; c < ToyViewOrder::Cells; ++c)
  {
    // The cell's voxels of each bin: its exact mass per bin over the mean.
    double massOfBin[2] = { 0, 0 };
    for (std::size_t id = 0; id < toy.Level.size(); ++id)
    {
      const int l = toy.Level[id];
      massOfBin[l / 2] += toy.Cell[id] == c ? means[static_cast<std::size_t>(l / 2)] : 0.0;
    }
    double cellVariance = 0;
    for (int b = 0; b < 2; ++b)
    {
      cellVariance += massOfBin[b] / unit * variance[b];
    }
    wholeVariance += cellVariance;
    const double exact = toy.Exact[static_cast<std::size_t>(c)];
    const double sigma = unit * std::sqrt(cellVariance);
    EXPECT_NEAR(exact, estimate[static_cast<std::size_t>(c)], 2 * unit + 4 * sigma) << "cell " << c;
  }
  EXPECT_NEAR(m, weightSum, 2 + 4 * std::sqrt(wholeVariance));
}

TEST(EveryVoxelOrder, EachKeptVoxelOnceInSpreadRunsOfNeighbours)
{
  // Voxels of random levels, some levels dropped: the order holds each
  // voxel of a kept level exactly once with its level, in runs of up to
  // RunLength voxels ascending in id order, whatever the executor; any
  // prefix of whole runs is spread over the volume (van der Corput order:
  // each eighth of the kept voxels holds an eighth of the prefix within 3
  // runs; measured: at most 2).
  for (const std::int64_t n :
    { std::int64_t(0), std::int64_t(1), std::int64_t(130), std::int64_t(200003) })
  {
    const std::int64_t levels = 9;
    std::mt19937 random(static_cast<unsigned>(n) + 5);
    std::vector<int> level(static_cast<std::size_t>(n));
    for (int& l : level)
    {
      l = static_cast<int>(random() % (levels + 1)) - 1; // -1: not indexed
    }
    std::vector<std::int64_t> offsets;
    const std::vector<std::uint32_t> sorted = SortByLevel(level, levels, offsets);
    const std::vector<char> kept = { 1, 0, 1, 1, 0, 1, 1, 1, 1 };
    mcx::EveryVoxelOrder<std::uint32_t> serial, threaded;
    serial.Build(mcx::SerialExecutor(), sorted.data(), offsets.data(), levels, kept, n);
    threaded.Build(ThreadExecutor(), sorted.data(), offsets.data(), levels, kept, n);
    EXPECT_EQ(serial.Ids, threaded.Ids) << n;
    EXPECT_EQ(serial.Levels, threaded.Levels) << n;

    std::vector<int> seen(static_cast<std::size_t>(n), 0);
    for (std::uint64_t k = 0; k < serial.Size(); ++k)
    {
      const std::uint32_t id = serial.Ids[k];
      ASSERT_LT(id, static_cast<std::uint64_t>(n));
      ++seen[id];
      ASSERT_EQ(level[id], static_cast<int>(serial.Levels[k])) << "point " << k;
    }
    std::uint64_t expected = 0;
    for (std::int64_t id = 0; id < n; ++id)
    {
      const int l = level[static_cast<std::size_t>(id)];
      const bool wanted = l >= 0 && kept[static_cast<std::size_t>(l)];
      expected += wanted ? 1 : 0;
      ASSERT_EQ(wanted ? 1 : 0, seen[static_cast<std::size_t>(id)]) << "voxel " << id;
    }
    ASSERT_EQ(expected, serial.Size());

    // Runs: ascending ids within each run of RunLength points (the short
    // last run may sit anywhere, so runs are told apart by their breaks).
    const std::uint64_t run = mcx::EveryVoxelOrder<std::uint32_t>::RunLength;
    std::uint64_t breaks = 0;
    for (std::uint64_t k = 1; k < serial.Size(); ++k)
    {
      breaks += serial.Ids[k] < serial.Ids[k - 1] ? 1 : 0;
    }
    const std::uint64_t runs = (serial.Size() + run - 1) / run;
    EXPECT_LE(breaks, runs > 0 ? runs - 1 : 0) << n;
    if (runs >= 1000)
    {
      EXPECT_GE(breaks, runs / 2) << n; // the runs are permuted, not left in id order
      // Each point's rank among the kept voxels in id order.
      std::vector<std::uint64_t> rank(static_cast<std::size_t>(n), 0);
      for (std::uint64_t r = 0, id = 0; id < static_cast<std::uint64_t>(n); ++id)
      {
        rank[id] = r;
        r += seen[id];
      }
      const std::uint64_t size = serial.Size();
      for (const std::uint64_t prefixRuns : { std::uint64_t(64), std::uint64_t(200), runs / 3 })
      {
        const std::uint64_t prefix = prefixRuns * run;
        std::vector<double> eighths(8, 0.0);
        for (std::uint64_t k = 0; k < prefix; ++k)
        {
          eighths[static_cast<std::size_t>(8 * rank[serial.Ids[k]] / size)] += 1;
        }
        for (double count : eighths)
        {
          EXPECT_NEAR(static_cast<double>(prefix) / 8, count, 3.0 * run) << prefixRuns << " runs";
        }
      }
    }
  }
}

namespace
{
mcx::ProjectionGeometry SmallPerspectiveView()
{
  mcx::ProjectionGeometry g;
  g.Perspective = true;
  g.Eye[2] = -50;
  g.FocalDistance = 50;
  g.NearDistance = 1;
  g.Size[0] = 24;
  g.Size[1] = 16;
  g.Spacing[0] = g.Spacing[1] = 0.5;
  g.Origin[0] = -5.75;
  g.Origin[1] = -3.75;
  return g;
}

// The point deposit, or the footprint deposit tabulated over RandomCloud's
// depths in SmallPerspectiveView.
mcx::DepositSettings RandomCloudDeposit(bool footprint)
{
  mcx::DepositSettings settings;
  if (footprint)
  {
    settings.Mode = mcx::Deposit::Footprint;
    settings.Depths[0] = 40; // the cloud lies at depths 50 +- 9 (points beyond: points)
    settings.Depths[1] = 60;
  }
  return settings;
}

// The point and the footprint deposit (RandomCloudDeposit), each in a
// parallel view and in SmallPerspectiveView, and their names.
struct DepositCase
{
  mcx::ProjectionGeometry View;
  mcx::DepositSettings Settings;
  std::string What;
};

std::vector<DepositCase> DepositCases()
{
  mcx::ProjectionGeometry perspective = SmallPerspectiveView();
  mcx::ProjectionGeometry parallel = perspective;
  parallel.Perspective = false;
  std::vector<DepositCase> cases;
  for (const bool footprint : { false, true })
  {
    for (const mcx::ProjectionGeometry& g : { parallel, perspective })
    {
      cases.push_back({ g, RandomCloudDeposit(footprint),
        std::string(footprint ? "footprint" : "point") +
          (g.Perspective ? ", perspective" : ", parallel") });
    }
  }
  return cases;
}

std::vector<float> RandomCloud(std::size_t points)
{
  std::mt19937 random(99);
  std::normal_distribution<float> position(0.0f, 3.0f);
  std::vector<float> cloud(3 * points);
  for (float& x : cloud)
  {
    x = position(random);
  }
  return cloud;
}
}

TEST(SampleAccumulator, SplitSumsAndThreadIndependence)
{
  const mcx::ProjectionGeometry g = SmallPerspectiveView();
  ASSERT_EQ("", g.Validate());
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const std::uint64_t count = 4095, split = 2047;
  const std::vector<float> cloud = RandomCloud(count);
  const std::size_t pixels = 24 * 16;

  // Each sample by hand, through the binner.
  const mcx::PixelBinner binner(g, origin, identity);
  std::vector<mcx::FixedSum> all(pixels, 0), first(pixels, 0);
  std::uint64_t deposited = 0;
  for (std::uint64_t k = 0; k < count; ++k)
  {
    const double p[3] = { cloud[3 * k], cloud[3 * k + 1], cloud[3 * k + 2] };
    std::int64_t pixel;
    mcx::FixedSum increment;
    if (binner.Bin(p, pixel, increment))
    {
      all[static_cast<std::size_t>(pixel)] += increment;
      first[static_cast<std::size_t>(pixel)] += k < split ? increment : mcx::FixedSum(0);
      ++deposited;
    }
  }
  ASSERT_GT(deposited, count / 2);

  mcx::SampleAccumulator<ThreadExecutor> accumulator;
  accumulator.Reset(g, origin, identity);
  accumulator.SetSplit(split);
  accumulator.DepositPoints(ThreadExecutor(), cloud.data(), 0, count);
  std::vector<mcx::FixedSum> threadedAll(pixels, 0), threadedFirst(pixels, 0);
  accumulator.Collect(threadedAll.data(), threadedFirst.data());
  EXPECT_TRUE(all == threadedAll);
  EXPECT_TRUE(first == threadedFirst);

  // Collect leaves the threads' images zeroed: a second round adds nothing
  // of the first.
  accumulator.DepositPoints(ThreadExecutor(), cloud.data(), 0, 0);
  std::vector<mcx::FixedSum> again(pixels, 0), againFirst(pixels, 0);
  accumulator.Collect(again.data(), againFirst.data());
  EXPECT_TRUE(std::all_of(
    again.begin(), again.end(), [](const mcx::FixedSum& v) { return v == mcx::FixedSum(0); }));

  // A depth limit drops what lies behind it: a limit of 0 everywhere hides all.
  accumulator.Reset(g, origin, identity, std::vector<double>(pixels, 0.0));
  accumulator.DepositPoints(ThreadExecutor(), cloud.data(), 0, count);
  std::vector<mcx::FixedSum> hidden(pixels, 0), hiddenFirst(pixels, 0);
  accumulator.Collect(hidden.data(), hiddenFirst.data());
  EXPECT_TRUE(std::all_of(
    hidden.begin(), hidden.end(), [](const mcx::FixedSum& v) { return v == mcx::FixedSum(0); }));
}

TEST(SampleAccumulator, ThreadSumsCarryPastSixtyFourBits)
{
  // A thread keeps 64-bit words and adds the high words at the first carry:
  // perspective weights up to 1e12 give increments above 2^64, and sums of
  // many below it carry too. The collected sums are the exact 128-bit ones.
  mcx::ThreadSums sums;
  sums.Allocate(3);
  const mcx::FixedSum big = mcx::FixedIncrement(1e12); // above 2^64
  const mcx::FixedSum near = mcx::FixedSum(std::uint64_t(3) << 62);
  mcx::FixedSum expectedAll[3] = { 0, 0, 0 }, expectedFirst[3] = { 0, 0, 0 };
  for (int i = 0; i < 3; ++i)
  {
    sums.Add(0, 1, near); // carries on the second addition
    expectedAll[1] += near;
    expectedFirst[1] += near;
  }
  sums.Add(1, 1, big);
  expectedAll[1] += big;
  std::uint64_t* low = sums.LowWords(1);
  for (int i = 0; i < 5; ++i)
  {
    sums.AddWord(1, low, 2, ~std::uint64_t(0)); // 2^64 - 1, carrying from the second on
    expectedAll[2] += mcx::FixedSum(~std::uint64_t(0));
  }
  sums.Add(1, 0, mcx::FixedOneInteger);
  expectedAll[0] += mcx::FixedOneInteger;
  ASSERT_TRUE(mcx::HighHalf(expectedAll[2]) == 4);

  std::vector<mcx::FixedSum> all(3, 0), first(3, 0);
  sums.CollectInto(3, all.data(), first.data());
  for (int p = 0; p < 3; ++p)
  {
    EXPECT_TRUE(all[p] == expectedAll[p]) << "pixel " << p;
    EXPECT_TRUE(first[p] == expectedFirst[p]) << "pixel " << p;
  }
  // Collected sums start over from zero, high words included.
  sums.Add(0, 1, mcx::FixedOneInteger);
  std::vector<mcx::FixedSum> again(3, 0), againFirst(3, 0);
  sums.CollectInto(3, again.data(), againFirst.data());
  EXPECT_TRUE(again[1] == mcx::FixedOneInteger);
  EXPECT_TRUE(againFirst[1] == mcx::FixedOneInteger);
  EXPECT_TRUE(again[2] == mcx::FixedSum(0));

  // Another image size after a carry: high words of the new size.
  sums.Add(1, 2, near);
  sums.Add(1, 2, near);
  sums.Allocate(5);
  sums.Add(1, 4, near);
  sums.Add(1, 4, near);
  std::vector<mcx::FixedSum> larger(5, 0), largerFirst(5, 0);
  sums.CollectInto(5, larger.data(), largerFirst.data());
  EXPECT_TRUE(larger[4] == near + near);
  EXPECT_TRUE(larger[2] == mcx::FixedSum(0));
}

TEST(FootprintTable, EachPhasesSupportHoldsEveryShareAndIsTight)
{
  // A voxel about one pixel wide, seen obliquely, and one much smaller: a
  // phase's shares are stored and visited over its support only, so the
  // support must hold every non-zero share (the stored shares sum to one,
  // the stored increments to exactly 2^32, shares being non-negative) and
  // each of its edges one of them.
  const double oblique[3][2] = { { 0.8, 0.3 }, { -0.2, 0.9 }, { 0.5, -0.4 } };
  const double tiny[3][2] = { { 0.1, 0 }, { 0, 0.1 }, { 0, 0 } };
  for (const auto* axes : { oblique, tiny })
  {
    mcx::FootprintTable table;
    table.Build(axes, mcx::FootprintPlan::For(mcx::Kernel::Tent, axes, 16.0));
    ASSERT_EQ(table.Phases(), 1 << table.PhaseShift());
    for (int b = 0; b < table.Phases(); ++b)
    {
      for (int a = 0; a < table.Phases(); ++a)
      {
        const mcx::FootprintTable::Support& support = table.SupportOf(a, b);
        ASSERT_TRUE(support.Columns[0] >= 0 && support.Columns[1] < table.Columns() &&
          support.Rows[0] >= 0 && support.Rows[1] < table.Rows() && support.Width() > 0 &&
          support.Height() > 0)
          << "phase " << a << ", " << b;
        const double* shares = table.Shares(a, b);
        const std::uint64_t* increments = table.Increments(a, b);
        bool edges[4] = { false, false, false, false };
        double inside = 0;
        std::uint64_t given = 0;
        for (int j = 0; j < support.Height(); ++j)
        {
          for (int i = 0; i < support.Width(); ++i)
          {
            const double share = shares[j * support.Width() + i];
            ASSERT_GE(share, 0.0);
            inside += share;
            given += increments[j * support.Width() + i];
            const bool nonZero = share > 0;
            edges[0] |= nonZero && i == 0;
            edges[1] |= nonZero && i == support.Width() - 1;
            edges[2] |= nonZero && j == 0;
            edges[3] |= nonZero && j == support.Height() - 1;
          }
        }
        EXPECT_NEAR(1.0, inside, 1e-12);
        EXPECT_EQ(std::uint64_t(1) << 32, given) << "phase " << a << ", " << b;
        EXPECT_TRUE(edges[0] && edges[1] && edges[2] && edges[3]) << "phase " << a << ", " << b;
      }
    }
  }
}

TEST(FootprintTable, CentresLeftOfTheImageFallInTheirPixel)
{
  // A voxel centre left of the image (negative pixel coordinate) deposits
  // what the same centre 8 pixels further right does, shifted back by 8:
  // its cell is rounded down, not towards zero. Dyadic positions keep the
  // sub-pixel phase exact; the same k draws the same random numbers.
  mcx::ProjectionGeometry g;
  g.Size[0] = 24;
  g.Size[1] = 8;
  g.Origin[0] = g.Origin[1] = 0.5; // pixel i covers [i, i + 1)
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  mcx::DepositSettings settings;
  settings.Mode = mcx::Deposit::Footprint;
  std::vector<mcx::FixedSum> images[2];
  const double x[2] = { -0.375, 7.625 };
  for (int n = 0; n < 2; ++n)
  {
    mcx::SampleAccumulator<mcx::SerialExecutor> accumulator;
    accumulator.Reset(g, origin, identity, std::vector<double>(), settings);
    const double centre[3] = { x[n], 3.5, 0.0 };
    accumulator.Local().Deposit(5, centre);
    images[n].assign(24 * 8, 0);
    std::vector<mcx::FixedSum> first(24 * 8, 0);
    accumulator.Collect(images[n].data(), first.data());
  }
  mcx::FixedSum seen = 0;
  for (int row = 0; row < 8; ++row)
  {
    for (int column = 0; column < 16; ++column)
    {
      EXPECT_TRUE(images[0][row * 24 + column] == images[1][row * 24 + column + 8])
        << "pixel " << column << ", " << row;
      seen += images[0][row * 24 + column];
    }
  }
  // A tent of one pixel reaches 1.5 pixels right of the centre.
  EXPECT_TRUE(mcx::FixedSum(0) < seen && seen < mcx::FixedOneInteger);
}

namespace
{
// The exact pixel-averaged footprint of one axis: the unit pixel convolved
// with a tent of half-width a (two uniform segments of length a) or a box of
// width a, i.e. the kernel's CDF differenced across the pixel.
double ExactAxisFootprint(double x, double a, bool tent)
{
  const auto cdf = [&](double t)
  {
    if (!tent)
    {
      return std::min(1.0, std::max(0.0, t / a + 0.5));
    }
    if (t <= -a || t >= a)
    {
      return t <= -a ? 0.0 : 1.0;
    }
    return t < 0 ? (t + a) * (t + a) / (2 * a * a) : 1 - (a - t) * (a - t) / (2 * a * a);
  };
  return cdf(x + 0.5) - cdf(x - 0.5);
}
}

TEST(FootprintDensity, AxisAlignedTentsMatchTheExactFootprint)
{
  // Voxels seen along an axis: G(x, y) = Gx(x) Gy(y) exactly. The grid's
  // interpolation errs by O(Q^-2): 4-6e-4 of the peak for these voxels (Q =
  // 125, 69 and 23 steps per pixel). A segment half a step too long or out
  // of place errs by about 4e-3 on the widest: the bar lies between.
  for (const double a : { 0.3, 0.96, 4.0 })
  {
    const double axes[3][2] = { { a, 0 }, { 0, 0.7 * a }, { 0, 0 } };
    mcx::FootprintDensity density;
    density.Build(axes, mcx::FootprintPlan::For(mcx::Kernel::Tent, axes, 16.0));
    double worst = 0, peak = 0;
    for (double x = -a - 1; x <= a + 1; x += 0.0137)
    {
      for (double y = -a - 1; y <= a + 1; y += 0.0151)
      {
        const double exact = ExactAxisFootprint(x, a, true) * ExactAxisFootprint(y, 0.7 * a, true);
        peak = std::max(peak, exact);
        worst = std::max(worst, std::fabs(density.Evaluate(x, y) - exact));
      }
    }
    EXPECT_LT(worst, 1.5e-3 * peak) << "voxel of " << a << " pixels";
  }
}

TEST(FootprintDensity, ObliqueFootprintsHaveTheBoxSplinesMoments)
{
  // Seen obliquely, G is the unit pixel convolved with uniform segments (two
  // per axis for the tent, one for the box): mass 1, mean 0, and covariance
  // the pixel's 1/12 plus each segment's s s^T / 12. Both shears and the
  // convolutions must keep them (a shear of the wrong sign flips a segment's
  // covariance); the grid's interpolations blur them by 0.3-0.4 % (a
  // 1 % bar; a segment 10 % short takes 2 % or more off its share).
  const double axes[3][2] = { { 0.8, 0.3 }, { -0.2, 0.9 }, { 0.5, -0.4 } };
  for (const mcx::Kernel kernel : { mcx::Kernel::Tent, mcx::Kernel::Box })
  {
    mcx::FootprintDensity density;
    density.Build(axes, mcx::FootprintPlan::For(kernel, axes, 16.0));
    const double copies = kernel == mcx::Kernel::Tent ? 2 : 1;
    double exact[3] = { 1.0 / 12, 0, 1.0 / 12 }; // xx, xy, yy
    for (const auto& s : axes)
    {
      exact[0] += copies * s[0] * s[0] / 12;
      exact[1] += copies * s[0] * s[1] / 12;
      exact[2] += copies * s[1] * s[1] / 12;
    }
    const double step = 0.01;
    double mass = 0, mean[2] = { 0, 0 }, moment[3] = { 0, 0, 0 };
    for (double x = -3; x <= 3; x += step)
    {
      for (double y = -3; y <= 3; y += step)
      {
        const double g = density.Evaluate(x, y) * step * step;
        mass += g;
        mean[0] += g * x;
        mean[1] += g * y;
        moment[0] += g * x * x;
        moment[1] += g * x * y;
        moment[2] += g * y * y;
      }
    }
    EXPECT_NEAR(1.0, mass, 1e-4);
    EXPECT_NEAR(0.0, mean[0], 1e-4);
    EXPECT_NEAR(0.0, mean[1], 1e-4);
    for (int m = 0; m < 3; ++m)
    {
      EXPECT_NEAR(exact[m], moment[m], 0.01 * std::fabs(exact[m])) << "moment " << m;
    }
  }
}

TEST(FootprintDensity, AVoxelAxisNearlyAlongTheViewChangesNothing)
{
  // An axis projected to 1e-11 pixel (above the 1e-12 cut for segments) is
  // a convolution over a tiny fraction of a grid step: it must leave G as
  // it is, not add the rounding of a difference of large antiderivative
  // sums divided by the tiny length (4e-5 of the peak here).
  const double flat[3][2] = { { 0.8, 0.3 }, { -0.2, 0.9 }, { 0, 0 } };
  const double tilted[3][2] = { { 0.8, 0.3 }, { -0.2, 0.9 }, { 1e-11, 0 } };
  mcx::FootprintDensity a, b;
  a.Build(flat, mcx::FootprintPlan::For(mcx::Kernel::Tent, flat, 16.0));
  b.Build(tilted, mcx::FootprintPlan::For(mcx::Kernel::Tent, tilted, 16.0));
  double worst = 0, peak = 0;
  for (double x = -2.5; x <= 2.5; x += 0.0137)
  {
    for (double y = -2.5; y <= 2.5; y += 0.0151)
    {
      peak = std::max(peak, a.Evaluate(x, y));
      worst = std::max(worst, std::fabs(a.Evaluate(x, y) - b.Evaluate(x, y)));
    }
  }
  EXPECT_LT(worst, 1e-6 * peak);
}

TEST(FootprintLadder, ScalesAreChosenWithTheMeanInverseDepth)
{
  // The ladder's tables lie at inverse depths w_j = w_0 r^j from the
  // farthest depth; a sample at w between two of them takes the nearer
  // scale with the probability that makes its mean scale w.
  const mcx::ProjectionGeometry g = SmallPerspectiveView();
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const mcx::PixelBinner binner(g, origin, identity);
  mcx::DepositSettings settings;
  settings.Mode = mcx::Deposit::Footprint;
  settings.Depths[0] = 40;
  settings.Depths[1] = 60;
  mcx::FootprintLadder ladder;
  ladder.Build(mcx::SerialExecutor(), binner, settings);
  const double r = mcx::FootprintLadder::Ratio, w0 = 1.0 / 60;
  const mcx::FootprintTable* first = ladder.Select(w0, 0.5);
  ASSERT_NE(nullptr, first);
  EXPECT_EQ(nullptr, ladder.Select(w0 * 0.999, 0.5)); // beyond the farthest
  EXPECT_EQ(nullptr, ladder.Select(1.0 / 10, 0.5));   // far beyond the nearest
  // On a ladder value: that table; on the last, the last (no table beyond).
  EXPECT_EQ(first + 3, ladder.Select(w0 * std::pow(r, 3.0), 0.0));
  const int last = 2 + static_cast<int>(std::ceil(std::log(60.0 / 40.0) / std::log(r))) - 1;
  EXPECT_EQ(first + last, ladder.Select(w0 * std::pow(r, static_cast<double>(last)), 1 - 1e-16));
  for (const double w : { w0 * 1.01, w0 * 1.2, 1.0 / 50, 1.0 / 41 })
  {
    const int j = static_cast<int>(std::floor(std::log(w / w0) / std::log(r)));
    const double below = w0 * std::pow(r, j), above = below * r;
    const double fraction = (w - below) / (above - below);
    double mean = 0;
    const int draws = 1000;
    for (int i = 0; i < draws; ++i)
    {
      const long chosen = ladder.Select(w, (i + 0.5) / draws) - first;
      ASSERT_TRUE(chosen == j || chosen == j + 1) << "w " << w;
      mean += (chosen == j ? below : above) / draws;
    }
    EXPECT_NEAR(w, mean, 1e-3 * (above - below)) << "fraction " << fraction;
  }
  EXPECT_EQ(nullptr, ladder.Select(std::nan(""), 0.5));

  // The shortest ladder: one depth, two scales (the guide's fewest buckets).
  settings.Depths[0] = settings.Depths[1] = 50;
  mcx::FootprintLadder shortest;
  shortest.Build(mcx::SerialExecutor(), binner, settings);
  const mcx::FootprintTable* near = shortest.Select(1.0 / 50, 0.5);
  ASSERT_NE(nullptr, near);
  EXPECT_EQ(near + 1, shortest.Select(1.0 / 50 * r, 1 - 1e-16)); // the last scale, as built
  EXPECT_EQ(near, shortest.Select(1.0 / 50 * (1 + 0.25 * (r - 1)), 0.5)); // fraction 1/4
  EXPECT_EQ(near + 1, shortest.Select(1.0 / 50 * (1 + 0.25 * (r - 1)), 0.2));
  EXPECT_EQ(nullptr, shortest.Select(1.0 / 50 * r * 1.001, 0.5));
}

TEST(FootprintLadder, TablesAreBoundedByTheReachAndCheckedBeforeTheyAreBuilt)
{
  // Voxels of a million pixels (a pixel spacing of 1e-6 voxel, as
  // --pixel-spacing 1e-9 makes of a CT) grew the tables without end; now
  // each is split until its deposited part is within the reach, and the
  // tables' bytes are known before any is built.
  const mcx::ProjectionGeometry g = SmallPerspectiveView();
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const mcx::PixelBinner binner(g, origin, identity);
  mcx::DepositSettings settings;
  settings.Mode = mcx::Deposit::Footprint;
  settings.Depths[0] = 1;
  settings.Depths[1] = 100; // the ladder's most tables
  for (double scale : { 1.0, 1e6 })
  {
    for (int k = 0; k < 9; k += 4)
    {
      settings.VoxelMatrix[k] = scale;
    }
    for (double reach : { 0.5, 16.0, 32.0 })
    {
      settings.Reach = reach;
      settings.TableMemory = mcx::FootprintLadder::MaximumBytes(reach);
      mcx::FootprintLadder ladder;
      EXPECT_NO_THROW(ladder.Build(mcx::SerialExecutor(), binner, settings)) << scale;
      EXPECT_FALSE(ladder.IsEmpty()) << scale << " " << reach;
      settings.TableMemory = 1024.0;
      mcx::FootprintLadder refused;
      try
      {
        refused.Build(mcx::SerialExecutor(), binner, settings);
        ADD_FAILURE() << "no error for tables beyond 1 KiB";
      }
      catch (const std::runtime_error& error)
      {
        EXPECT_EQ(0u, std::string(error.what()).find("the footprint tables of this view need"));
      }
      EXPECT_TRUE(refused.IsEmpty());
    }
  }
  // The bound itself: 251 MiB at the default reach, 764 MiB at the largest.
  EXPECT_NEAR(251.4, mcx::FootprintLadder::MaximumBytes(16) / 1048576.0, 0.1);
  EXPECT_NEAR(764.1, mcx::FootprintLadder::MaximumBytes(32) / 1048576.0, 0.1);
  // Every table of a plan within the reach is within the bound's share.
  for (double length : { 0.01, 1.0, 40.0, 1e3, 1e9, 1e11 })
  {
    const double axes[3][2] = { { length, 0.3 * length }, { -0.2 * length, length },
      { 0.5 * length, 0.5 * length } };
    for (double reach : { 0.5, 16.0, 32.0 })
    {
      const mcx::FootprintPlan plan = mcx::FootprintPlan::For(mcx::Kernel::Tent, axes, reach);
      ASSERT_TRUE(plan.Within(axes, reach)) << length;
      EXPECT_LE(mcx::FootprintTable::PlannedBytes(axes, plan),
        mcx::FootprintLadder::MaximumBytes(reach) / mcx::FootprintLadder::MaximumTables)
        << length << " " << reach;
    }
  }
  // Voxels beyond 2^40 times the reach are not split that far: no table
  // (point deposits), nothing to allocate.
  const double huge[3][2] = { { 1e20, 0 }, { 0, 1e20 }, { 0, 0 } };
  EXPECT_FALSE(mcx::FootprintPlan::For(mcx::Kernel::Tent, huge, 16).Within(huge, 16));
  for (int k = 0; k < 9; k += 4)
  {
    settings.VoxelMatrix[k] = 1e20;
  }
  mcx::FootprintLadder points;
  EXPECT_NO_THROW(points.Build(mcx::SerialExecutor(), binner, settings));
  EXPECT_TRUE(points.IsEmpty());
}

namespace
{
// The sums of points [begin, end) of `cloud`, with `weights` or none.
template <typename Executor>
std::vector<mcx::FixedSum> WeightedSums(const mcx::ProjectionGeometry& g,
  const mcx::DepositSettings& settings, const std::vector<float>& cloud, std::uint64_t begin,
  std::uint64_t end, const float* weights)
{
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  mcx::SampleAccumulator<Executor> accumulator;
  accumulator.Reset(g, origin, identity, std::vector<double>(), settings);
  accumulator.SetSplit(mcx::FirstHalfSize(cloud.size() / 3));
  accumulator.DepositPoints(Executor(), cloud.data(), begin, end, weights);
  const std::size_t pixels = accumulator.NumberOfPixels();
  std::vector<mcx::FixedSum> sums(2 * pixels, 0);
  accumulator.Collect(sums.data(), sums.data() + pixels);
  return sums;
}
}

TEST(SampleAccumulator, WeightedPointsAddTheirWeightTimesTheirDeposit)
{
  // Point i of a weighted cloud adds weights[i] times what it adds alone
  // (the same footprint phase and scale: they come from its index), up to
  // the rounding of each pixel's increment; weight 1 is the unweighted
  // deposit bit for bit and weight 0 adds nothing; any number of threads
  // gives the same sums.
  const std::uint64_t count = 1500;
  const std::vector<float> cloud = RandomCloud(count);
  std::vector<float> weights(count), ones(count, 1.0f), zeros(count, 0.0f);
  for (std::uint64_t i = 0; i < count; ++i)
  {
    weights[i] = 0.75f * static_cast<float>(i % 4) + (i % 7 == 0 ? 1e-3f : 0.0f);
  }
  for (const DepositCase& deposit : DepositCases())
  {
    const mcx::ProjectionGeometry& g = deposit.View;
    ASSERT_EQ("", g.Validate());
    const mcx::DepositSettings& settings = deposit.Settings;
    const std::string& what = deposit.What;
    using Serial = mcx::SerialExecutor;
    const auto plain = WeightedSums<Serial>(g, settings, cloud, 0, count, nullptr);
    EXPECT_TRUE(plain == WeightedSums<Serial>(g, settings, cloud, 0, count, ones.data())) << what;
    const auto none = WeightedSums<Serial>(g, settings, cloud, 0, count, zeros.data());
    EXPECT_TRUE(std::all_of(
      none.begin(), none.end(), [](const mcx::FixedSum& v) { return v == mcx::FixedSum(0); }))
      << what;

    const auto weighted = WeightedSums<Serial>(g, settings, cloud, 0, count, weights.data());
    EXPECT_TRUE(
      weighted == WeightedSums<ThreadExecutor>(g, settings, cloud, 0, count, weights.data()))
      << what;
    const std::size_t entries = weighted.size(); // both halves
    std::vector<double> expected(entries, 0.0), slack(entries, 0.0);
    double mass = 0.0;
    for (std::uint64_t i = 0; i < count; ++i)
    {
      const auto alone = WeightedSums<Serial>(g, settings, cloud, i, i + 1, nullptr);
      for (std::size_t e = 0; e < entries; ++e)
      {
        if (alone[e] != mcx::FixedSum(0))
        {
          expected[e] += weights[i] * mcx::ToDouble(alone[e]);
          slack[e] += 0.5 * weights[i] + 0.5; // w round(x) against round(w x)
        }
      }
      mass += weights[i] > 0 ? 1.0 : 0.0;
    }
    ASSERT_GT(mass, count / 2.0);
    std::size_t outside = 0, reached = 0;
    for (std::size_t e = 0; e < entries; ++e)
    {
      outside +=
        std::fabs(mcx::ToDouble(weighted[e]) - expected[e]) > slack[e] + 1e-6 * expected[e] ? 1 : 0;
      reached += expected[e] > 0 ? 1 : 0;
    }
    EXPECT_EQ(0u, outside) << what;
    EXPECT_GT(reached, entries / 4) << what;
  }
}

TEST(ChannelSplit, SplitsAreFloorsOfTheProductAndFractionsSumToOne)
{
  std::mt19937_64 random(7);
  for (int i = 0; i < 2000; ++i)
  {
    const std::uint64_t increment = random() >> (i % 40);
    const std::uint64_t fraction = random() % (mcx::FractionOne + 1);
    // floor(increment x fraction / 2^32), from the two 32-bit halves of the increment.
    const std::uint64_t high = increment >> 32, low = increment & 0xFFFFFFFFu;
    const std::uint64_t expected = high * fraction + ((low * fraction) >> 32);
    ASSERT_EQ(expected, mcx::SplitWord(increment, fraction)) << increment << " " << fraction;
    // A 128-bit increment 2^64 h + l splits into 2^32 h f + (l's split).
    const std::uint64_t h = random() >> 40;
    const mcx::FixedSum wide = (mcx::FixedSum(h) << 64) + mcx::FixedSum(increment);
    const mcx::FixedSum part = mcx::SplitSum(wide, fraction);
    EXPECT_TRUE(part == (mcx::FixedSum(h * fraction) << 32) + mcx::FixedSum(expected));
  }
  EXPECT_EQ(12345u, mcx::SplitWord(12345, mcx::FractionOne));
  EXPECT_EQ(0u, mcx::SplitWord(~std::uint64_t(0), 0));

  const double weights[4] = { 0.2, 0.0, 1.0 / 3.0, 0.7 };
  std::uint64_t fractions[4];
  ASSERT_TRUE(mcx::FixedFractions(weights, 4, fractions));
  EXPECT_EQ(mcx::FractionOne, fractions[0] + fractions[1] + fractions[2] + fractions[3]);
  EXPECT_EQ(0u, fractions[1]);
  EXPECT_NEAR(0.2 / (0.2 + 1.0 / 3.0 + 0.7), fractions[0] / mcx::FixedOne, 1e-9);
  // A channel of no weight gets nothing, the last one included (the rest
  // goes to the last positive weight); weights near the largest double
  // do not overflow their sum.
  const double lastZero[3] = { 1.0, 1.0 / 3.0, 0.0 };
  ASSERT_TRUE(mcx::FixedFractions(lastZero, 3, fractions));
  EXPECT_EQ(0u, fractions[2]);
  EXPECT_EQ(mcx::FractionOne, fractions[0] + fractions[1]);
  const double huge[2] = { 1e308, 1e308 };
  ASSERT_TRUE(mcx::FixedFractions(huge, 2, fractions));
  EXPECT_EQ(mcx::FractionOne / 2, fractions[0]);
  EXPECT_FALSE(mcx::FixedFractions(huge, 0, fractions));
  const double none[2] = { 0.0, 0.0 }, negative[2] = { 1.0, -0.1 }, nan[2] = { 1.0, std::nan("") };
  EXPECT_FALSE(mcx::FixedFractions(none, 2, fractions));
  EXPECT_FALSE(mcx::FixedFractions(negative, 2, fractions));
  EXPECT_FALSE(mcx::FixedFractions(nan, 2, fractions));
}

namespace
{
// The total's sums and each channel's (all, then the first half) of the
// cloud's points deposited once each, point i split by fractions[i] (of
// FixedFractions).
template <typename Executor>
std::vector<std::vector<mcx::FixedSum>> ChannelSums(const mcx::ProjectionGeometry& g,
  const mcx::DepositSettings& settings, const std::vector<float>& cloud,
  const std::vector<std::array<std::uint64_t, 3>>& fractions)
{
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  mcx::SampleAccumulator<Executor> accumulator;
  accumulator.Reset(g, origin, identity, std::vector<double>(), settings);
  const std::uint64_t count = cloud.size() / 3;
  accumulator.SetSplit(mcx::FirstHalfSize(count));
  accumulator.SetChannels(3);
  mcx::ChannelShareTable table; // a level per point
  std::vector<std::uint64_t> flat;
  for (const auto& point : fractions)
  {
    flat.insert(flat.end(), point.begin(), point.end());
  }
  table.Build(flat, 3);
  Executor().For(0, static_cast<std::int64_t>(count), 64,
    [&](std::int64_t b, std::int64_t e)
    {
      const auto image = accumulator.Local();
      for (std::int64_t i = b; i < e; ++i)
      {
        const double p[3] = { cloud[3 * i], cloud[3 * i + 1], cloud[3 * i + 2] };
        image.Deposit(static_cast<std::uint64_t>(i), p, 1.0, table.Of(i));
      }
    });
  const std::size_t pixels = accumulator.NumberOfPixels();
  std::vector<std::vector<mcx::FixedSum>> sums(4, std::vector<mcx::FixedSum>(2 * pixels, 0));
  mcx::FixedSum* channels[3] = { sums[1].data(), sums[2].data(), sums[3].data() };
  accumulator.Collect(sums[0].data(), sums[0].data() + pixels, nullptr, nullptr, channels);
  return sums;
}
}

TEST(ChannelSplit, ChannelsAddUpToTheTotalAndAWholeChannelIsItsSamplesAlone)
{
  // One deposit split into three channels: the total is the unsplit
  // deposit's, bit for bit; the channels add up to it exactly in every
  // pixel and half; a sample given wholly to a channel adds there what it
  // adds alone; any number of threads gives the same sums.
  const std::uint64_t count = 1500;
  const std::vector<float> cloud = RandomCloud(count);
  std::vector<std::array<std::uint64_t, 3>> whole(count), mixed(count);
  std::vector<float> ofChannel[3];
  for (auto& weights : ofChannel)
  {
    weights.assign(count, 0.0f);
  }
  for (std::uint64_t i = 0; i < count; ++i)
  {
    whole[i] = { 0, 0, 0 };
    whole[i][i % 3] = mcx::FractionOne;
    ofChannel[i % 3][i] = 1.0f;
    const double weights[3] = { 0.1 + (i % 5), 0.25 * (i % 2), 1.0 / (1 + i % 7) };
    ASSERT_TRUE(mcx::FixedFractions(weights, 3, mixed[i].data()));
  }
  for (const DepositCase& deposit : DepositCases())
  {
    const mcx::ProjectionGeometry& g = deposit.View;
    const mcx::DepositSettings& settings = deposit.Settings;
    const std::string& what = deposit.What;
    using Serial = mcx::SerialExecutor;
    const auto unsplit = WeightedSums<Serial>(g, settings, cloud, 0, count, nullptr);
    for (const auto* fractions : { &whole, &mixed })
    {
      const auto sums = ChannelSums<Serial>(g, settings, cloud, *fractions);
      EXPECT_TRUE(sums[0] == unsplit) << what;
      EXPECT_TRUE(sums == ChannelSums<ThreadExecutor>(g, settings, cloud, *fractions)) << what;
      std::size_t reached = 0;
      for (std::size_t e = 0; e < unsplit.size(); ++e)
      {
        ASSERT_TRUE(sums[1][e] + sums[2][e] + sums[3][e] == sums[0][e]) << what << " " << e;
        reached += sums[3][e] != mcx::FixedSum(0) ? 1 : 0;
      }
      EXPECT_GT(reached, unsplit.size() / 4) << what;
    }
    const auto split = ChannelSums<Serial>(g, settings, cloud, whole);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_TRUE(
        split[1 + c] == WeightedSums<Serial>(g, settings, cloud, 0, count, ofChannel[c].data()))
        << what << ", channel " << c;
    }
  }
}

namespace
{
// The serial executor with thread-local values made as vtkSMPThreadLocal
// makes them: default-initialised over storage that is not zero.
struct PoisonedExecutor : mcx::SerialExecutor
{
  template <typename T>
  class ThreadLocal
  {
  public:
    ThreadLocal() { std::memset(this->Storage, 0xA5, sizeof(T)); }
    ~ThreadLocal()
    {
      if (this->Made)
      {
        this->Value()->~T();
      }
    }
    T& Local()
    {
      if (!this->Made)
      {
        new (this->Storage) T;
        this->Made = true;
      }
      return *this->Value();
    }
    T* begin() { return this->Made ? this->Value() : nullptr; }
    T* end() { return this->Made ? this->Value() + 1 : nullptr; }

  private:
    T* Value() { return reinterpret_cast<T*>(this->Storage); }
    alignas(T) unsigned char Storage[sizeof(T)];
    bool Made = false;
  };
};
}

TEST(SampleAccumulator, PointWeightSumIsExactForAnySplit)
{
  // The fixed-point sum of weights: the same for any executor (also one
  // whose thread-local values start as garbage), and the sums of two
  // consecutive ranges add up to that of their union.
  std::mt19937 random(3);
  std::uniform_real_distribution<float> weight(0.0f, 5.0f);
  std::vector<float> weights(300001);
  double reference = 0;
  for (float& w : weights)
  {
    w = weight(random);
    reference += w;
  }
  const std::uint64_t n = weights.size();
  const mcx::FixedSum serial = mcx::PointWeightSum(mcx::SerialExecutor(), weights.data(), 0, n);
  EXPECT_TRUE(serial == mcx::PointWeightSum(ThreadExecutor(), weights.data(), 0, n));
  EXPECT_TRUE(serial == mcx::PointWeightSum(PoisonedExecutor(), weights.data(), 0, n));
  EXPECT_TRUE(serial ==
    mcx::PointWeightSum(ThreadExecutor(), weights.data(), 0, 1234) +
      mcx::PointWeightSum(ThreadExecutor(), weights.data(), 1234, n));
  EXPECT_NEAR(reference, mcx::ToDouble(serial) / mcx::FixedOne, 1e-9 * reference);
}

TEST(SampleAccumulator, PointWeightProblemNamesTheFirstBadWeight)
{
  const double fine[] = { 0.0, 1.0, 0.25, mcx::MaximumPointWeight };
  EXPECT_EQ("", mcx::PointWeightProblem(fine, 4));
  for (const double bad :
    { -1e-30, std::nan(""), HUGE_VAL, -HUGE_VAL, 2 * mcx::MaximumPointWeight })
  {
    const double weights[] = { 1.0, 2.0, bad, -5.0 };
    const std::string problem = mcx::PointWeightProblem(weights, 4);
    EXPECT_NE(std::string::npos, problem.find("point 2 has the weight")) << problem;
  }
  const float negative[] = { 3.0f, -0.5f };
  EXPECT_NE(
    std::string::npos, mcx::PointWeightProblem(negative, 2).find("point 1 has the weight -0.5"));
}

TEST(ProgressiveImage, PrefixesAddUpToTheOneShotImageAndItsHalves)
{
  const mcx::ProjectionGeometry g = SmallPerspectiveView();
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const std::uint64_t count = 8191;
  const std::vector<float> cloud = RandomCloud(count);

  mcx::SampleAccumulator<mcx::SerialExecutor> oneShot;
  oneShot.Reset(g, origin, identity);
  oneShot.SetSplit(mcx::FirstHalfSize(count));
  oneShot.DepositPoints(mcx::SerialExecutor(), cloud.data(), 0, count);
  const std::size_t pixels = oneShot.NumberOfPixels();
  std::vector<mcx::FixedSum> sums(2 * pixels, 0);
  oneShot.Collect(sums.data(), sums.data() + pixels);

  mcx::ProgressiveImage<ThreadExecutor> image;
  image.Reset(g, origin, identity);
  for (std::uint64_t target = 1; target <= count; target = 2 * target + 1)
  {
    image.Advance(ThreadExecutor(), cloud.data(), target);
    EXPECT_EQ(target, image.Count());
  }
  EXPECT_TRUE(std::equal(
    sums.begin(), sums.begin() + static_cast<std::ptrdiff_t>(pixels), image.Sums().begin()));
  EXPECT_EQ(mcx::EstimateRelativeError(sums, count), image.EstimateRelativeError());
  EXPECT_GT(image.EstimateRelativeError(), 0.0);
}

TEST(ProgressiveImage, ControlledImageIsTheWeightedMinusTheOnceCountedPlusTheControl)
{
  // mcxControlImage.h: (I / W) S_w + H - (I / n) S_1, every point counted
  // once in S_1 whatever its weight (0 too), point and footprint deposits,
  // parallel and perspective. Weights all 1: S_w = S_1, so the image is H
  // exactly and the halves differ nowhere.
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const std::uint64_t count = 8191;
  const std::vector<float> cloud = RandomCloud(count);
  const double integral = 3.5;
  std::vector<float> ones(count, 1.0f), weights(count);
  for (std::uint64_t i = 0; i < count; ++i)
  {
    weights[i] = 0.5f * static_cast<float>(i % 5);
  }
  for (const DepositCase& deposit : DepositCases())
  {
    const mcx::ProjectionGeometry& g = deposit.View;
    const mcx::DepositSettings& settings = deposit.Settings;
    const std::string& what = deposit.What;
    auto image =
      [&](const float* pointWeights, const std::vector<double>& control, double variance = 0.0)
    {
      mcx::ProgressiveImage<ThreadExecutor> progressive;
      progressive.Reset(g, origin, identity, std::vector<double>(), settings);
      if (!control.empty())
      {
        progressive.SetControl(control, integral, variance);
      }
      for (std::uint64_t target = 1; target <= count; target = 2 * target + 1)
      {
        progressive.Advance(ThreadExecutor(), cloud.data(), target, pointWeights);
      }
      EXPECT_EQ(!control.empty(), progressive.IsControlled()) << what;
      std::vector<double> values(progressive.NumberOfPixels());
      progressive.ToValues(integral / progressive.CountedWeight(), values.data());
      return std::make_pair(values, progressive.EstimateRelativeError());
    };
    const std::vector<double> once = image(nullptr, {}).first;
    const std::size_t pixels = once.size();
    std::vector<double> control(pixels);
    for (std::size_t p = 0; p < pixels; ++p)
    {
      control[p] = 0.01 * static_cast<double>(p % 37);
    }
    const auto equal = image(ones.data(), control);
    EXPECT_EQ(control, equal.first) << what;
    EXPECT_LT(equal.second, 1e-12) << what; // 0 but for the rounding of W / W_A against n / a
    // The control's own variance joins the estimate: sqrt(variance / the
    // image's squares), the points' part 0 here.
    double squares = 0.0;
    for (double v : control)
    {
      squares += v * v;
    }
    EXPECT_NEAR(0.5, image(ones.data(), control, 0.25 * squares).second, 1e-9) << what;

    const auto controlled = image(weights.data(), control);
    const std::vector<double> weighted = image(weights.data(), {}).first;
    double peak = 0.0;
    for (double v : weighted)
    {
      peak = std::max(peak, std::fabs(v));
    }
    ASSERT_GT(peak, 0.0) << what;
    for (std::size_t p = 0; p < pixels; ++p)
    {
      ASSERT_NEAR(weighted[p] + control[p] - once[p], controlled.first[p], 1e-12 * peak)
        << what << ", pixel " << p;
    }
    EXPECT_GT(controlled.second, 0.0) << what;
  }
}

TEST(RadiographEffects, AppliedToAnImageAsPerPixel)
{
  const mcx::RadiographEffects effects =
    mcx::RadiographEffects::FromProperties(false, 2.0, 500.0, 9, true);
  EXPECT_TRUE(effects.BeerLambert); // implied by the noise and the log
  const std::int64_t pixels = 10000;
  std::vector<double> lineIntegrals(static_cast<std::size_t>(pixels));
  for (std::int64_t p = 0; p < pixels; ++p)
  {
    lineIntegrals[static_cast<std::size_t>(p)] = 0.001 * static_cast<double>(p % 5000);
  }
  std::vector<float> values(static_cast<std::size_t>(pixels));
  effects.ApplyToImage(
    ThreadExecutor(), pixels,
    [&](std::int64_t p) { return lineIntegrals[static_cast<std::size_t>(p)]; }, values.data());
  const std::uint64_t key = mcx::SeedKey(9);
  for (std::int64_t p = 0; p < pixels; ++p)
  {
    ASSERT_EQ(static_cast<float>(effects.Apply(
                lineIntegrals[static_cast<std::size_t>(p)], static_cast<std::uint64_t>(p), key)),
      values[static_cast<std::size_t>(p)]);
  }
  EXPECT_FALSE(mcx::RadiographEffects::FromProperties(false, 1.0, 0.0, 0, false).Any());
}
