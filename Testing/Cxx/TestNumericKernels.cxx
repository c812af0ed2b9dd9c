// The plain C++ kernels, without any pipeline.
#include "mcxCountingSort.h"
#include "mcxExecutor.h"
#include "mcxFastDivide.h"
#include "mcxFixedPoint.h"
#include "mcxHalton.h"
#include "mcxPixelBinner.h"
#include "mcxRayIntegrator.h"
#include "mcxSampleGenerator.h"
#include "mcxTransferTable.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

TEST(Halton, PositionIsAPermutationForSmallExponents)
{
  for (unsigned m = 1; m <= 20; ++m)
  {
    const std::uint64_t count = mcx::SampleCount(m);
    std::vector<char> seen(count, 0);
    for (std::uint64_t i = 0; i < count; ++i)
    {
      const std::uint64_t k = mcx::HaltonPosition(i, m);
      ASSERT_LT(k, count);
      ASSERT_FALSE(seen[k]);
      seen[k] = 1;
      // u_i = (i + 1) / 2^m is the Halton point of position k.
      ASSERT_EQ(std::ldexp(static_cast<double>(i + 1), -static_cast<int>(m)),
        mcx::RadicalInverse(k + 1, 2));
    }
  }
}

TEST(Halton, PositionIsAnInvolutionInRangeUpTo63)
{
  std::mt19937_64 random(7);
  for (unsigned m = 1; m <= 63; ++m)
  {
    const std::uint64_t count = mcx::SampleCount(m);
    for (int t = 0; t < 2000; ++t)
    {
      const std::uint64_t i = t == 0 ? 0 : (t == 1 ? count - 1 : random() % count);
      const std::uint64_t k = mcx::HaltonPosition(i, m);
      ASSERT_LT(k, count);
      ASSERT_EQ(i, mcx::HaltonPosition(k, m));
    }
  }
}

TEST(Halton, FirstPositionsAreCoarseStrata)
{
  // The first 2^j - 1 positions hold exactly the multiples of 2^(m-j) - 1.
  const unsigned m = 12, j = 5;
  std::vector<std::uint64_t> ranks;
  for (std::uint64_t k = 0; k < mcx::SampleCount(j); ++k)
  {
    ranks.push_back(mcx::HaltonPosition(k, m));
  }
  std::sort(ranks.begin(), ranks.end());
  for (std::size_t q = 0; q < ranks.size(); ++q)
  {
    EXPECT_EQ((q + 1) << (m - j), ranks[q] + 1);
  }
}

TEST(Halton, ExponentForSampleCount)
{
  EXPECT_EQ(0u, mcx::ExponentForSampleCount(0));
  EXPECT_EQ(1u, mcx::ExponentForSampleCount(1));
  EXPECT_EQ(2u, mcx::ExponentForSampleCount(2));
  EXPECT_EQ(2u, mcx::ExponentForSampleCount(3));
  EXPECT_EQ(24u, mcx::ExponentForSampleCount(16000000));
  EXPECT_EQ(63u, mcx::ExponentForSampleCount(std::numeric_limits<long long>::max()));
}

TEST(FastDivide, ExactForAll32BitOperands)
{
  std::mt19937_64 random(3);
  const std::uint64_t divisors[] = { 1, 2, 3, 7, 64, 93, 255, 4096, 65535, 65536, 1u << 20,
    4294967295ull };
  for (std::uint64_t d : divisors)
  {
    const mcx::Divider32 divider(d);
    for (int t = 0; t < 20000; ++t)
    {
      const std::uint64_t n = t < 4 ? (t == 0 ? 0 : 4294967296ull - t) : (random() >> 32);
      ASSERT_EQ(n / d, divider.Quotient(n)) << n << " / " << d;
    }
  }
}

TEST(FastDivide, VoxelDecoderBothWidths)
{
  const std::uint64_t nx = 100003, ny = 40009; // nx * ny * nz > 2^32 for the wide decoder
  const mcx::VoxelDecoder<std::uint64_t> wide(nx, ny);
  const std::uint64_t id = (5ull * ny + 40000) * nx + 99999;
  std::uint64_t i, j, k;
  wide.Decode(id, i, j, k);
  EXPECT_EQ(99999u, i);
  EXPECT_EQ(40000u, j);
  EXPECT_EQ(5u, k);
  const mcx::VoxelDecoder<std::uint32_t> narrow(64, 64);
  narrow.Decode(static_cast<std::uint32_t>((92 * 64 + 63) * 64 + 17), i, j, k);
  EXPECT_EQ(17u, i);
  EXPECT_EQ(63u, j);
  EXPECT_EQ(92u, k);
}

TEST(CountingSort, MatchesStableSortForAnyLayout)
{
  std::mt19937 random(11);
  for (std::int64_t n : { 1, 5, 70000, 300001 })
  {
    for (std::int64_t bins : { 1, 3, 4096 })
    {
      std::vector<std::int64_t> bin(static_cast<std::size_t>(n));
      for (auto& b : bin)
      {
        b = static_cast<std::int64_t>(random() % (bins + 1)) - 1; // -1: left out
      }
      std::vector<std::uint32_t> expected;
      for (std::int64_t id = 0; id < n; ++id)
      {
        if (bin[id] >= 0)
        {
          expected.push_back(static_cast<std::uint32_t>(id));
        }
      }
      std::stable_sort(expected.begin(), expected.end(),
        [&](std::uint32_t a, std::uint32_t b) { return bin[a] < bin[b]; });
      std::vector<std::uint32_t> sorted(expected.size());
      std::vector<std::int64_t> offsets;
      const std::int64_t left = mcx::CountingSortByBin<std::uint32_t>(
        mcx::SerialExecutor(), n, bins, [&](std::int64_t id) { return bin[id]; }, offsets,
        sorted.data());
      EXPECT_EQ(n - static_cast<std::int64_t>(expected.size()), left);
      EXPECT_EQ(expected, sorted);
      ASSERT_EQ(static_cast<std::size_t>(bins + 1), offsets.size());
      for (std::int64_t b = 0; b < bins; ++b)
      {
        for (std::int64_t i = offsets[b]; i < offsets[b + 1]; ++i)
        {
          ASSERT_EQ(b, bin[sorted[i]]);
        }
      }
    }
  }
}

TEST(TransferTable, ScalesExactlyAndClampsBadWeights)
{
  const std::int64_t offsets[] = { 0, 2, 5, 6, 10 };
  const double weights[] = { 3.0, -1.0, std::nan(""), 1e300 };
  const mcx::TransferTable table = mcx::BuildTransferTable(weights, offsets, 4);
  EXPECT_EQ(1, table.NegativeLevels);
  EXPECT_EQ(1, table.NaNLevels);
  EXPECT_EQ(0, table.InfiniteLevels);
  EXPECT_DOUBLE_EQ(4e300 + 6.0, table.WeightSum());
  EXPECT_EQ(table.Cumulative[1], table.Cumulative[2]);
  EXPECT_EQ(table.Cumulative[2], table.Cumulative[3]);

  const double none[] = { 0.0, 0.0, 0.0, 0.0 };
  EXPECT_TRUE(mcx::BuildTransferTable(none, offsets, 4).IsEmpty());
  const double infinite[] = { 1.0, INFINITY, 0.0, 0.0 };
  EXPECT_EQ(1, mcx::BuildTransferTable(infinite, offsets, 4).InfiniteLevels);
}

TEST(SampleGenerator, HybridVisitsEveryLevelInProportion)
{
  // Two levels with masses 1:3: exactly a quarter of the u-grid falls in the first.
  const std::uint32_t ids[] = { 0, 1, 2, 3 };
  const std::int64_t offsets[] = { 0, 2, 4 };
  const double weights[] = { 1.0, 3.0 };
  const mcx::TransferTable table = mcx::BuildTransferTable(weights, offsets, 2);
  mcx::SampleSource<std::uint32_t> source;
  source.SortedIds = ids;
  source.LevelOffsets = offsets;
  source.SetTable(table);
  source.NumberOfLevels = 2;
  source.Decoder = mcx::VoxelDecoder<std::uint32_t>(4, 1);
  source.Exponent = 12;
  std::vector<char> seen(source.NumberOfSamples(), 0);
  auto sink = [&](std::uint64_t k, const double p[3])
  {
    seen[k] = 1; // every output index is written exactly once
    EXPECT_LT(std::fabs(p[1]), 1.0);
    EXPECT_LT(std::fabs(p[2]), 1.0);
  };
  source.Generate(0, source.NumberOfSamples(), sink);
  EXPECT_EQ(
    source.NumberOfSamples(), static_cast<std::uint64_t>(std::count(seen.begin(), seen.end(), 1)));
  // With the box kernel the voxel of a sample is floor(p + 0.5).
  source.Reconstruction = mcx::Kernel::Box;
  std::vector<std::int64_t> counts(4, 0);
  auto counter = [&](std::uint64_t, const double p[3])
  { ++counts[static_cast<int>(std::floor(p[0] + 0.5))]; };
  source.Generate(0, source.NumberOfSamples(), counter);
  // 4095 samples over voxel weights 1, 1, 3, 3 (total 8): 511.875 each for the
  // first two and 1535.625 for the others; stratification keeps each within 1.
  EXPECT_NEAR(511.875, counts[0], 1.0);
  EXPECT_NEAR(511.875, counts[1], 1.0);
  EXPECT_NEAR(1535.625, counts[2], 1.0);
  EXPECT_NEAR(1535.625, counts[3], 1.0);
}

TEST(RayIntegrator, TentAndBoxOfOneVoxel)
{
  // One voxel of value 2 in the middle of a 3^3 grid, unit spacing.
  std::vector<double> values(27, 0.0);
  values[13] = 2.0;
  const int dims[3] = { 3, 3, 3 };
  const mcx::RayIntegrator tent(values.data(), dims, mcx::Kernel::Tent);
  const mcx::RayIntegrator box(values.data(), dims, mcx::Kernel::Box);
  const double d[3] = { 0, 0, 1 };
  const double inf = INFINITY;
  // Through the centre: integral of 2 (1 - |t|) = 2; off by (0.5, 0.25): 2 * 0.5 * 0.75.
  const double centre[3] = { 1, 1, -5 };
  const double off[3] = { 1.5, 1.25, 7 };
  EXPECT_NEAR(2.0, tent.Integrate(centre, d, -inf, inf), 1e-14);
  EXPECT_NEAR(0.75, tent.Integrate(off, d, -inf, inf), 1e-14);
  EXPECT_NEAR(2.0, box.Integrate(centre, d, -inf, inf), 1e-14);
  EXPECT_NEAR(0.0, box.Integrate(off, d, -inf, inf), 1e-14);
  // A diagonal ray through the centre: the tent's integral along direction
  // (1,1,1)/sqrt(3) is 2 * sqrt(3) * integral of (1-|s|)^3 ds = sqrt(3).
  const double diagonal[3] = { 1 / std::sqrt(3.0), 1 / std::sqrt(3.0), 1 / std::sqrt(3.0) };
  const double start[3] = { 1 - 3 * diagonal[0], 1 - 3 * diagonal[1], 1 - 3 * diagonal[2] };
  EXPECT_NEAR(std::sqrt(3.0), tent.Integrate(start, diagonal, -inf, inf), 1e-13);
  // Half a ray: from the centre onwards, half the axial integral.
  EXPECT_NEAR(1.0, tent.Integrate(centre, d, 6.0, inf), 1e-14);
}

TEST(RayIntegrator, ConstantVolumeGivesLengthTimesValue)
{
  // A constant c over n voxels: the tent field is c inside and ramps to 0
  // within one spacing outside, so any axial ray through the interior sees c * n.
  const int dims[3] = { 4, 5, 6 };
  std::vector<double> values(4 * 5 * 6, 1.5);
  const mcx::RayIntegrator tent(values.data(), dims, mcx::Kernel::Tent);
  const double p[3] = { 1.3, 2.7, 0 };
  const double d[3] = { 0, 0, -1 };
  EXPECT_NEAR(1.5 * 6, tent.Integrate(p, d, -INFINITY, INFINITY), 1e-12);
}

TEST(SampleGenerator, EveryVisitingOrderGivesTheSameSamples)
{
  // Generate (rank order), GenerateInOutputOrder and GenerateForStorage must
  // produce bit-identical samples, each output index exactly once.
  std::vector<std::uint32_t> ids(60);
  std::iota(ids.begin(), ids.end(), 0u);
  const std::int64_t offsets[] = { 0, 7, 30, 31, 60 };
  const double weights[] = { 0.5, 2.0, 40.0, 1.0 };
  const mcx::TransferTable table = mcx::BuildTransferTable(weights, offsets, 4);
  for (auto method :
    { mcx::Strategy::Hybrid, mcx::Strategy::MonteCarlo, mcx::Strategy::QuasiMonteCarlo })
  {
    for (unsigned m : { 1u, 2u, 3u, 5u, 12u, 13u, 14u, 15u, 17u })
    {
      mcx::SampleSource<std::uint32_t> source;
      source.SortedIds = ids.data();
      source.LevelOffsets = offsets;
      source.SetTable(table);
      source.Decoder = mcx::VoxelDecoder<std::uint32_t>(5, 4);
      source.Method = method;
      source.Seed = 77;
      source.Exponent = m;
      const std::uint64_t count = source.NumberOfSamples();
      std::vector<std::array<double, 3>> orders[3];
      std::vector<int> hits[3];
      for (int o = 0; o < 3; ++o)
      {
        orders[o].assign(count, { NAN, NAN, NAN });
        hits[o].assign(count, 0);
        auto sink = [&](std::uint64_t k, const double p[3])
        {
          orders[o][k] = { p[0], p[1], p[2] };
          ++hits[o][k];
        };
        if (o == 0)
          source.Generate(0, count, sink);
        else if (o == 1)
          source.GenerateInOutputOrder(0, count, sink);
        else // item by item, last first: items are independent of how threads split them
          for (std::uint64_t t = source.NumberOfStorageItems(); t-- > 0;)
            source.GenerateForStorage(t, t + 1, sink);
      }
      for (int o = 0; o < 3; ++o)
      {
        EXPECT_EQ(std::vector<int>(count, 1), hits[o]) << "order " << o << " m " << m;
        for (std::uint64_t k = 0; k < count; ++k)
        {
          ASSERT_EQ(orders[0][k], orders[o][k]) << "order " << o << " m " << m << " k " << k;
        }
      }
    }
  }
}

TEST(SampleGenerator, RankArithmeticCannotOverflowForHugeLevels)
{
  // A level of 2^40 (and 2^62) voxels: the rank comes from a floating-point
  // product, never from a count times a count.
  for (int bits : { 40, 62 })
  {
    const std::int64_t count = std::int64_t(1) << bits;
    const std::int64_t offsets[] = { 0, count };
    const double cumulative[] = { 0.0, 1.0 };
    const double scale[] = { static_cast<double>(count) };
    mcx::SampleSource<std::uint64_t> source;
    source.LevelOffsets = offsets;
    source.Cumulative = cumulative;
    source.RankScale = scale;
    source.NumberOfLevels = 1;
    EXPECT_EQ(count / 2 - 1, source.VoxelRank(0.5, 1));
    EXPECT_EQ(count - 1, source.VoxelRank(1.0, 1));
    EXPECT_EQ(0, source.VoxelRank(1e-300, 1));
    // A denormal level mass makes the scale infinite: the rank still stays in range.
    const double infinite[] = { INFINITY };
    source.RankScale = infinite;
    EXPECT_EQ(count - 1, source.VoxelRank(0.25, 1));
  }
}

TEST(SampleGenerator, LargeExponentsOnASmallVolume)
{
  // m = 31, 32, 40 and 63: the first and last work items of the run are
  // valid samples (ranks, output indices and positions), without running
  // all 2^m - 1 of them.
  std::vector<std::uint32_t> ids(24);
  std::iota(ids.begin(), ids.end(), 0u);
  const std::int64_t offsets[] = { 0, 4, 24 };
  const double weights[] = { 3.0, 1.0 };
  const mcx::TransferTable table = mcx::BuildTransferTable(weights, offsets, 2);
  for (unsigned m : { 31u, 32u, 40u, 63u })
  {
    mcx::SampleSource<std::uint32_t> source;
    source.SortedIds = ids.data();
    source.LevelOffsets = offsets;
    source.SetTable(table);
    source.Decoder = mcx::VoxelDecoder<std::uint32_t>(4, 3); // 4 x 3 x 2 voxels
    source.Exponent = m;
    const std::uint64_t count = source.NumberOfSamples();
    int seen = 0;
    auto check = [&](std::uint64_t k, const double p[3])
    {
      ++seen;
      EXPECT_LT(k, count);
      EXPECT_TRUE(p[0] > -1 && p[0] < 4 && p[1] > -1 && p[1] < 3 && p[2] > -1 && p[2] < 2)
        << p[0] << " " << p[1] << " " << p[2];
    };
    source.Generate(0, 1000, check);
    source.Generate(count - 1000, count, check);
    source.GenerateInOutputOrder(count - 1000, count, check);
    EXPECT_EQ(3000, seen) << m;
    // The level masses 12 : 20 put the first 12/32 of the u-grid in level 0
    // (voxels 0..3, i.e. y = 0 and z = 0 rows of x = 0..3).
    int inFirstLevel = 0;
    auto level = [&](std::uint64_t, const double p[3])
    { inFirstLevel += (std::lround(p[1]) <= 0 && std::lround(p[2]) <= 0) ? 1 : 0; };
    source.Reconstruction = mcx::Kernel::Box;
    source.Generate(0, 1000, level);
    EXPECT_EQ(1000, inFirstLevel) << m; // the smallest u all fall in level 0
  }
}

TEST(CountingSort, LayoutForMoreThan2To32Voxels)
{
  const std::int64_t n = std::int64_t(1) << 34;
  for (std::int64_t bins :
    { std::int64_t(1), std::int64_t(4096), std::int64_t(65536), std::int64_t(1) << 24 })
  {
    const mcx::CountingSortLayout layout = mcx::MakeCountingSortLayout(n, bins);
    EXPECT_GE(layout.NumberOfChunks * layout.ChunkSize, n);
    EXPECT_LT((layout.NumberOfChunks - 1) * layout.ChunkSize, n);
    EXPECT_LE(layout.NumberOfChunks * bins, std::max<std::int64_t>(bins, std::int64_t(1) << 24));
  }
}

TEST(Accumulation, CountsAbove2To32StayExact)
{
  // 2^33 + 5 samples in one pixel (as 128-bit fixed point) convert exactly.
  std::vector<mcx::FixedSum> sums(2, 0);
  const std::uint64_t samples = (std::uint64_t(1) << 33) + 5;
  sums[0] = mcx::FixedSum(samples) << 32; // samples times 2^32
  for (int i = 0; i < 3; ++i)
  {
    sums[1] += mcx::FixedOneInteger; // the accumulator's own additions
  }
  double values[2];
  mcx::FixedSumsToValues(sums.data(), 2, 0.5, 0.25, values);
  EXPECT_EQ(static_cast<double>(samples) * 2.0, values[0]);
  EXPECT_EQ(6.0, values[1]);
}

TEST(Accumulation, PerspectivePointsBehindOnAndBeforeTheEye)
{
  mcx::ProjectionGeometry g;
  g.Perspective = true;
  g.FocalDistance = 10;
  g.NearDistance = 1;
  g.Size[0] = g.Size[1] = 8;
  g.Spacing[0] = g.Spacing[1] = 1;
  g.Origin[0] = g.Origin[1] = -3.5;
  ASSERT_EQ("", g.Validate());
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const mcx::PixelBinner binner(g, origin, identity);
  std::int64_t pixel = -1;
  mcx::FixedSum increment = 0;
  const double behind[3] = { 0, 0, -5 }, eye[3] = { 0, 0, 0 }, beforeNear[3] = { 0.1, 0.1, 0.5 };
  EXPECT_FALSE(binner.Bin(behind, pixel, increment));
  EXPECT_FALSE(binner.Bin(eye, pixel, increment));
  EXPECT_FALSE(binner.Bin(beforeNear, pixel, increment));
  // On the near plane, on the axis: seen, with weight D^2 / near^2 = 100.
  const double onNear[3] = { 0.0, 0.0, 1.0 };
  ASSERT_TRUE(binner.Bin(onNear, pixel, increment));
  EXPECT_TRUE(mcx::FixedSum(100) << 32 == increment);
  EXPECT_EQ(4 + 8 * 4, pixel);
  // Nearer than 1e-6 of the focal distance is refused as a geometry.
  g.NearDistance = 1e-6;
  EXPECT_NE("", g.Validate());
}

TEST(Accumulation, ObliqueParallelRaysBinAlongTheirDirection)
{
  // Rays along R = W + 0.75 U: a point at depth z lands 0.75 z to the left of
  // where its perpendicular projection would, and a pixel's value is its
  // mass over the beam's cross-section, the pixel area times cos = 1 / 1.25.
  mcx::ProjectionGeometry g;
  g.Obliquity[0] = 0.75;
  g.Size[0] = g.Size[1] = 8;
  g.Spacing[0] = g.Spacing[1] = 1;
  g.Origin[0] = g.Origin[1] = -3.5;
  ASSERT_EQ("", g.Validate());
  EXPECT_DOUBLE_EQ(1.25, g.RayLengthPerDepth());
  EXPECT_DOUBLE_EQ(0.8, g.BeamCrossSection());
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const mcx::PixelBinner binner(g, origin, identity);
  std::int64_t pixel = -1;
  mcx::FixedSum increment = 0;
  const double deep[3] = { 0.2, 0.2, 4.0 }; // plane coordinates (0.2 - 3, 0.2)
  ASSERT_TRUE(binner.Bin(deep, pixel, increment));
  EXPECT_EQ(1 + 8 * 4, pixel);
  double a = 0, b = 0;
  ASSERT_TRUE(mcx::ProjectToPlane(g, deep, a, b));
  EXPECT_DOUBLE_EQ(0.2 - 3.0, a);
  EXPECT_DOUBLE_EQ(0.2, b);
  // Obliquity is for parallel views, and bounded.
  g.Perspective = true;
  g.FocalDistance = 10;
  g.NearDistance = 1;
  EXPECT_NE("", g.Validate());
  g.Perspective = false;
  g.Obliquity[1] = std::nan("");
  EXPECT_NE("", g.Validate());
}

namespace
{
// A sample as a piece emits it: output index and position, bit for bit.
struct EmittedSample
{
  std::uint64_t K;
  double P[3];
  bool operator<(const EmittedSample& o) const { return this->K < o.K; }
  bool operator==(const EmittedSample& o) const
  {
    return this->K == o.K && std::memcmp(this->P, o.P, sizeof(this->P)) == 0;
  }
};
}

TEST(SampleGenerator, PiecesEmitExactlyTheWholeVolumesSamples)
{
  // A 5 x 4 x 9 volume of 12 levels cut into z-slabs, as processes hold it
  // (an empty slab, one whose voxels all have zero weight, uneven sizes):
  // each slab, knowing only the global table and its own sorted ids, emits
  // exactly the whole volume's samples whose voxels it holds, with the same
  // output indices and positions, for every strategy; under the Halton
  // choice its runs (PieceRanks) hold its samples and no other.
  const std::uint64_t nx = 5, ny = 4, nz = 9, slice = nx * ny;
  const std::int64_t levels = 12;
  std::vector<std::int64_t> level(nx * ny * nz);
  for (std::size_t id = 0; id < level.size(); ++id)
  {
    const std::uint64_t z = id / slice;
    // Slab z in [6, 8) holds level 11 alone, whose weight is 0.
    level[id] = z >= 6 && z < 8 ? 11 : static_cast<std::int64_t>((id * 7 + id / 3) % 11);
  }
  auto sortSlab = [&](std::uint64_t z0, std::uint64_t z1, std::vector<std::uint32_t>& ids,
                    std::vector<std::int64_t>& offsets)
  {
    offsets.assign(levels + 1, 0);
    ids.clear();
    for (std::int64_t l = 0; l < levels; ++l)
    {
      for (std::uint64_t id = z0 * slice; id < z1 * slice; ++id)
      {
        if (level[id] == l)
        {
          ids.push_back(static_cast<std::uint32_t>(id - z0 * slice));
        }
      }
      offsets[l + 1] = static_cast<std::int64_t>(ids.size());
    }
  };
  std::vector<std::uint32_t> wholeIds;
  std::vector<std::int64_t> wholeOffsets;
  sortSlab(0, nz, wholeIds, wholeOffsets);
  std::vector<double> weights(levels);
  for (std::int64_t l = 0; l < levels; ++l)
  {
    weights[l] = l == 11 ? 0.0 : 0.5 + 0.37 * static_cast<double>((l * 5) % 7);
  }
  const mcx::TransferTable table =
    mcx::BuildTransferTable(weights.data(), wholeOffsets.data(), levels);
  const std::uint64_t cuts[] = { 0, 2, 2, 3, 6, 8, 9 }; // slabs [cuts[r], cuts[r + 1])
  for (const mcx::Strategy method :
    { mcx::Strategy::Hybrid, mcx::Strategy::QuasiMonteCarlo, mcx::Strategy::MonteCarlo })
  {
    mcx::SampleSource<std::uint32_t> whole;
    whole.SortedIds = wholeIds.data();
    whole.LevelOffsets = wholeOffsets.data();
    whole.SetTable(table);
    whole.NumberOfLevels = levels;
    whole.Decoder = mcx::VoxelDecoder<std::uint32_t>(nx, ny);
    whole.Method = method;
    whole.Seed = 5;
    whole.Exponent = 11;
    std::vector<EmittedSample> expected, pieces;
    auto into = [](std::vector<EmittedSample>& list)
    {
      return [&list](std::uint64_t k, const double p[3])
      { list.push_back({ k, { p[0], p[1], p[2] } }); };
    };
    auto wholeSink = into(expected);
    whole.Generate(0, whole.NumberOfSamples(), wholeSink);
    ASSERT_EQ(whole.NumberOfSamples(), expected.size());
    std::vector<std::int64_t> firstRank(levels, 0); // running over the slabs
    for (std::size_t r = 0; r + 1 < sizeof(cuts) / sizeof(cuts[0]); ++r)
    {
      std::vector<std::uint32_t> ids;
      std::vector<std::int64_t> offsets;
      sortSlab(cuts[r], cuts[r + 1], ids, offsets);
      mcx::SampleSource<std::uint32_t> piece = whole;
      piece.SortedIds = ids.data();
      piece.PieceOffsets = offsets.data();
      piece.PieceFirstRank = firstRank.data();
      piece.PieceStart[2] = cuts[r];
      std::vector<EmittedSample> own;
      auto pieceSink = into(own);
      std::uint64_t generated = 0;
      for (const auto& run : piece.PieceRanks())
      {
        piece.Generate(run.first, run.second, pieceSink);
        generated += run.second - run.first;
      }
      if (method != mcx::Strategy::MonteCarlo)
      {
        EXPECT_EQ(generated, own.size()) << "slab " << r << ": runs of other slabs' samples";
      }
      if (cuts[r] >= 6 && cuts[r + 1] <= 8)
      {
        EXPECT_EQ(0u, own.size()) << "a slab of zero weight";
      }
      pieces.insert(pieces.end(), own.begin(), own.end());
      for (std::int64_t l = 0; l < levels; ++l)
      {
        firstRank[l] += offsets[l + 1] - offsets[l];
      }
    }
    std::sort(expected.begin(), expected.end());
    std::sort(pieces.begin(), pieces.end());
    ASSERT_EQ(expected.size(), pieces.size()) << static_cast<int>(method);
    EXPECT_TRUE(expected == pieces) << static_cast<int>(method);
  }
}
