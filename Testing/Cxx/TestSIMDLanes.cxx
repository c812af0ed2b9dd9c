// The SIMD kernels give the scalar code's results bit for bit on every
// instruction set Highway compiles them for (scalar to AVX-512 here): each
// is forced in turn (hwy::SetSupportedTargetsForTest) and compared with the
// scalar PixelBinner::Locate and ThreadImage::DepositPoint.
#include "mcxExecutor.h"
#include "mcxFootprintBatch.h"
#include "mcxObliqueTestGeometry.h"
#include "mcxPixelBinner.h"
#include "mcxSampleAccumulator.h"

#include <hwy/highway.h>
#include <hwy/targets.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace
{
// Points around the volume, and the awkward ones: behind the near plane,
// on it, not finite, overflowing to infinity in the products, subnormal.
std::vector<double> Points(std::size_t n)
{
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> around(-40.0, 40.0);
  std::vector<double> xyz(3 * n);
  for (double& c : xyz)
  {
    c = around(random);
  }
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double awkward[][3] = { { nan, 0, 0 }, { 0, inf, 0 }, { 0, 0, -inf }, { 1e300, 1e300, 0 },
    { 4.9e-324, -4.9e-324, 0 }, { 0, 0, 0 }, { -1e308, 1e308, 1e308 } };
  for (std::size_t i = 0; i < sizeof(awkward) / sizeof(awkward[0]); ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      xyz[3 * (5 * i + 3) + a] = awkward[i][a];
    }
  }
  return xyz;
}

bool SameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

// Every compiled target the CPU runs, one at a time (the mock is reset
// after each test).
std::vector<std::int64_t> Targets()
{
  return hwy::SupportedAndGeneratedTargets();
}

struct ResetTargets
{
  ~ResetTargets() { hwy::SetSupportedTargetsForTest(0); }
};
}

TEST(SIMDLanes, LocatePointsIsLocateBitForBitOnEveryInstructionSet)
{
  ResetTargets reset;
  const std::string dispatched = mcx::PixelBinner::LanesInstructionSet(); // before any mock
  const std::vector<std::int64_t> targets = Targets();
  // The portable one and the CPU's widest at least (one only where the
  // CPU's widest is the portable one).
  ASSERT_GE(targets.size(), 1u);
  std::vector<std::string> names;
  const std::size_t n = 1000; // not a multiple of any vector width
  const std::vector<double> xyz = Points(n);
  std::vector<double> x(n + mcx::PixelBinner::LanePadding), y(x.size()), z(x.size());
  for (std::size_t i = 0; i < n; ++i)
  {
    x[i] = xyz[3 * i];
    y[i] = xyz[3 * i + 1];
    z[i] = xyz[3 * i + 2];
  }
  const double origin[3] = { -3.0, 2.0, 1.0 };
  const double matrix[9] = { 0.8, 0.1, 0, 0, 1.1, 0.05, 0.02, 0, 1.3 };
  for (bool perspective : { false, true })
  {
    const mcx::PixelBinner binner(ObliqueTestGeometry(perspective), origin, matrix);
    for (std::int64_t target : targets)
    {
      hwy::SetSupportedTargetsForTest(target);
      names.push_back(hwy::TargetName(target));
      std::vector<double> fx(n), fy(n), f(n), inverseDepth(n);
      std::vector<std::uint8_t> located(n);
      binner.LocatePoints(x.data(), y.data(), z.data(), n, fx.data(), fy.data(), f.data(),
        located.data(), inverseDepth.data());
      int inImage = 0, refused = 0;
      for (std::size_t i = 0; i < n; ++i)
      {
        double ex = 0, ey = 0, ef = 0, depth = 0;
        const double p[3] = { x[i], y[i], z[i] };
        const bool expected = binner.Locate(p, ex, ey, ef, depth);
        ASSERT_EQ(expected, located[i] != 0)
          << hwy::TargetName(target) << " point " << i << (perspective ? " perspective" : "");
        if (expected)
        {
          EXPECT_TRUE(SameBits(ex, fx[i]) && SameBits(ey, fy[i]) && SameBits(ef, f[i]) &&
            SameBits(depth, inverseDepth[i]))
            << hwy::TargetName(target) << " point " << i << ": " << ex << " " << ey << " " << ef
            << " against " << fx[i] << " " << fy[i] << " " << f[i];
          inImage += ex >= 0 && ex < 37 && ey >= 0 && ey < 29 ? 1 : 0;
        }
        else
        {
          ++refused;
        }
      }
      // The comparison covers points in the image and refused ones alike.
      EXPECT_GT(inImage, 50) << hwy::TargetName(target);
      EXPECT_GT(refused, 2) << hwy::TargetName(target);
    }
  }
  std::string tested;
  for (const std::string& name : names)
  {
    tested += name + " ";
  }
  std::cout << "instruction sets compared: " << tested << "(dispatch picks " << dispatched << ")"
            << std::endl;
}

TEST(SIMDLanes, DepositPointsAddsWhatDepositPointAdds)
{
  // The batch's scalar half (image bounds, depth limits, the first Halton
  // half's split, the control images, a stored cloud's weights, 0 among
  // them) against one DepositPoint per sample, on every instruction set:
  // the collected sums must be equal.
  ResetTargets reset;
  const std::size_t n = 5000;
  const std::vector<double> xyz = Points(n);
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  auto weightOf = [](std::size_t i) { return i % 5 == 0 ? 0.0 : 0.25 + 0.375 * (i % 11); };
  for (bool perspective : { false, true })
  {
    for (bool weighted : { false, true })
    {
      const mcx::ProjectionGeometry g = ObliqueTestGeometry(perspective);
      const std::size_t pixels = static_cast<std::size_t>(g.Size[0]) * g.Size[1];
      std::vector<double> limits(pixels);
      for (std::size_t p = 0; p < pixels; ++p)
      {
        limits[p] = 40.0 + 50.0 * static_cast<double>(p % 7) / 7.0; // hides some samples
      }
      for (std::int64_t target : Targets())
      {
        hwy::SetSupportedTargetsForTest(target);
        std::vector<mcx::FixedSum> sums[2][4];
        for (int batched = 0; batched < 2; ++batched)
        {
          mcx::SampleAccumulator<mcx::SerialExecutor> accumulator;
          accumulator.Reset(g, origin, identity, limits);
          accumulator.SetControlled(true);
          accumulator.SetSplit(n / 3);
          const auto image = accumulator.Local();
          mcx::ThreadImage::PointBatch batch(image);
          for (std::size_t i = 0; i < n; ++i)
          {
            if (batched && weighted)
            {
              batch.AddWeighted(i, &xyz[3 * i], weightOf(i));
            }
            else if (batched)
            {
              batch.Add(i, &xyz[3 * i]);
            }
            else
            {
              image.DepositPoint(i, &xyz[3 * i], weighted ? weightOf(i) : 1.0);
            }
          }
          batch.Flush();
          for (auto& s : sums[batched])
          {
            s.assign(pixels, 0);
          }
          accumulator.Collect(sums[batched][0].data(), sums[batched][1].data(),
            sums[batched][2].data(), sums[batched][3].data());
        }
        mcx::FixedSum total = 0;
        for (int s = 0; s < 4; ++s)
        {
          for (std::size_t p = 0; p < pixels; ++p)
          {
            ASSERT_TRUE(sums[0][s][p] == sums[1][s][p])
              << hwy::TargetName(target) << (weighted ? " weighted" : "") << " image " << s
              << " pixel " << p;
            total += sums[0][s][p];
          }
        }
        EXPECT_TRUE(mcx::FixedSum(0) < total) << "no sample reached the image";
      }
  }
  }
}

TEST(SIMDLanes, AStoredCloudInBatchesAddsWhatOneAtATimeAdds)
{
  // A weighted, controlled stored cloud through DepositRange, chunk by
  // chunk, in a perspective and an oblique parallel view, unsplit and split
  // into three channels: its perspective points batched on lanes, its
  // footprints through FootprintBatch (located on lanes in perspective),
  // against Deposit's one Locate and one footprint at a time, on every
  // instruction set; the points nearer than the tables' depths go as
  // points either way.
  ResetTargets reset;
  const std::size_t n = 3000, chunk = 1000; // DepositRange chunk by chunk
  const std::vector<double> points = Points(n);
  std::vector<float> weights(n);
  std::vector<std::uint32_t> rows(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    weights[i] = i % 7 == 0 ? 0.0f : 0.5f + 0.25f * static_cast<float>(i % 5);
    rows[i] = static_cast<std::uint32_t>(i % 3);
  }
  // Three rows of fractions of 2^32: one channel, two, and all three.
  mcx::ChannelShareTable table;
  const std::uint64_t whole = std::uint64_t(1) << 32;
  table.Build({ whole, 0, 0, 0, whole / 4, whole - whole / 4, whole / 2, whole / 4, whole / 4 }, 3);
  const mcx::PointShares shares{ rows.data(), &table };
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  mcx::DepositSettings settings;
  settings.Depths[0] = 30.0;
  settings.Depths[1] = 110.0;
  for (const bool perspective : { true, false })
  {
    const mcx::ProjectionGeometry g = ObliqueTestGeometry(perspective);
    const std::size_t pixels = static_cast<std::size_t>(g.Size[0]) * g.Size[1];
    // Each chunk ends in points well inside the image, so that a footprint
    // left in the pipeline at a chunk's end would be missed.
    std::vector<double> xyz(points);
    const mcx::PixelBinner binner(g, origin, identity);
    std::vector<std::size_t> inside;
    for (std::size_t i = 0; i < n; ++i)
    {
      double fx, fy, f, w;
      // In the image, and in perspective within the tables' depths (nearer
      // or farther samples are deposited as points at once).
      if (binner.Locate(&points[3 * i], fx, fy, f, w) && fx > 4 && fy > 4 && fx < g.Size[0] - 4 &&
        fy < g.Size[1] - 4 && weights[i] > 0 &&
        (!perspective || (w > 1.0 / settings.Depths[1] && w < 1.0 / settings.Depths[0])))
      {
        inside.push_back(i);
      }
    }
    ASSERT_GE(inside.size(), 3 * mcx::FootprintBatch::Lookahead);
    for (std::size_t c = 0; c < n / chunk; ++c)
    {
      for (std::size_t j = 0; j < mcx::FootprintBatch::Lookahead; ++j)
      {
        const std::size_t from = inside[c * mcx::FootprintBatch::Lookahead + j];
        const std::size_t to = (c + 1) * chunk - 1 - j;
        std::copy(&points[3 * from], &points[3 * from] + 3, &xyz[3 * to]);
        weights[to] = weights[from];
      }
    }
    for (const int channels : { 0, 3 })
    {
      for (const mcx::Deposit mode : { mcx::Deposit::Point, mcx::Deposit::Footprint })
      {
        for (std::int64_t target : Targets())
        {
          settings.Mode = mode;
          hwy::SetSupportedTargetsForTest(target);
          // The total's four images, then each channel's (all, first half).
          std::vector<mcx::FixedSum> sums[2][7];
          for (int blocks = 0; blocks < 2; ++blocks)
          {
            mcx::SampleAccumulator<mcx::SerialExecutor> accumulator;
            accumulator.Reset(g, origin, identity, std::vector<double>(), settings);
            accumulator.SetControlled(true);
            accumulator.SetSplit(n / 3);
            accumulator.SetChannels(channels);
            const mcx::PointShares* split = channels ? &shares : nullptr;
            if (blocks)
            {
              for (std::size_t c = 0; c < n; c += chunk)
              {
                accumulator.DepositRange(xyz.data(), c, c + chunk, weights.data(), split);
              }
            }
            else
            {
              const auto image = accumulator.Local();
              for (std::size_t i = 0; i < n; ++i)
              {
                image.Deposit(i, &xyz[3 * i], weights[i], split ? split->Of(i) : nullptr);
              }
            }
            for (int s = 0; s < 7; ++s)
            {
              sums[blocks][s].assign(s < 4 ? pixels : 2 * pixels, 0);
            }
            mcx::FixedSum* channelSums[3] = { sums[blocks][4].data(), sums[blocks][5].data(),
              sums[blocks][6].data() };
            accumulator.Collect(sums[blocks][0].data(), sums[blocks][1].data(),
              sums[blocks][2].data(), sums[blocks][3].data(), channels ? channelSums : nullptr);
          }
          mcx::FixedSum total = 0, channelTotal = 0;
          for (int s = 0; s < 7; ++s)
          {
            for (std::size_t p = 0; p < sums[0][s].size(); ++p)
            {
              ASSERT_TRUE(sums[0][s][p] == sums[1][s][p])
                << hwy::TargetName(target) << (perspective ? " perspective" : " parallel")
                << (mode == mcx::Deposit::Point ? " points" : " footprints") << ", " << channels
                << " channels, image " << s << " pixel " << p;
              (s < 4 ? total : channelTotal) += sums[0][s][p];
            }
          }
          EXPECT_TRUE(mcx::FixedSum(0) < total) << "no sample reached the image";
          EXPECT_EQ(channels > 0, mcx::FixedSum(0) < channelTotal) << "the channels' sums";
        }
      }
    }
  }
}
