// A control variate for a view-ordered cloud (beyond the paper).
//
// A view-ordered cloud (mcxViewOrder.h) draws a bin of levels in proportion
// to its mass and a voxel uniformly inside it, weighted w / (the bin's mean
// w). Counted once each instead, the same samples estimate the image H of
// the TF that is constant on each bin (its mean w), which the sampler
// projects for the view it sorted for: each bin's voxels projected (the
// bins' images), then one weighted sum per TF edit. The controlled estimate
//
//   image = (I / W) S_w + H - (I / n) S_1
//
// (I the cloud's integral, W the weight of its n points so far, S_w their
// weighted sums, S_1 their sums counted once) is unbiased like the cloud's
// own (I / W) S_w as far as H's expectation is the image of every voxel's
// footprint, which S_1 estimates, and mass-conserving like it (H and
// (I / n) S_1 carry the same integral). Where the samples fall in their
// pixel, at which depth, and how many land in each (bin, pixel) cell moves
// S_w and S_1 alike and cancels; what is left is the spread of w / (the
// bin's mean w) inside each bin. On the CT chest upsampled to 50 M voxels
// (256^2 cone beam, 2^21 - 1 points) the error falls from 1.7 to 0.65 %.
//
// H is every voxel projected once (the footprints' random rounding one
// fixed draw) or, where the voxels far outnumber the points, an estimate
// from a few voxels of each (bin, pixel) run drawn systematically
// (SystematicPicks, ControlPicks): its own error, a fraction of the cloud's
// at a fraction of the cost, adds to the cloud's. The difference of the
// picks' two interleaved halves estimates H's variance, which the error
// estimate then adds (ControlledSums::ControlVariance).
#ifndef mcxControlImage_h
#define mcxControlImage_h

#include "mcxErrorEstimate.h"
#include "mcxFixedPoint.h"
#include "mcxRandom.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mcx
{

/// The sums of a controlled image and what its points carry.
struct ControlledSums
{
  const FixedSum* Weighted = nullptr; ///< S_w of all points
  const FixedSum* Once = nullptr;     ///< S_1 of all points
  const double* Control = nullptr;    ///< H, line integrals
  std::size_t Pixels = 0;
  std::uint64_t Count = 0;    ///< n
  double CarriedWeight = 0.0; ///< W (n for an unweighted cloud)
  double Integral = 0.0;      ///< I
  double PixelArea = 1.0;     ///< the beam cross-section of a pixel
  /// H's own variance summed over the pixels (line integrals squared): 0
  /// for an H of every voxel.
  double ControlVariance = 0.0;
};

/// The voxels of a run of `n` (a view order's (bin, pixel) run) that a
/// control image projects to project about one in `stride` (> 1): Count
/// picks, an even number and at least 2, at floor(Start + j Interval) (j <
/// Count), Interval = n / Count, Start = uniform Interval (uniform in [0,
/// 1)), each carrying Interval. A pick falls in [i, i + 1) for a share 1 /
/// Interval of the starts, so each voxel is picked 1 / Interval times on
/// average: the picks' images are an unbiased estimate of the run's
/// every-voxel image, and in the run's order (by position in the pixel) they
/// spread over the pixel evenly. The even and the odd picks are two
/// interleaved halves whose images' difference estimates the variance of
/// their sum: conservatively where the footprints change smoothly along the
/// run (the halves then move together). A run that would get as many picks
/// as voxels or more takes each voxel twice instead, once in each half,
/// with weight 1/2 (Start 0, Interval 1/2): exact, and its halves differ by
/// their random rounding only.
struct SystematicPicks
{
  std::int64_t Count = 0;
  double Interval = 1.0;
  double Start = 0.0;

  SystematicPicks(std::int64_t n, double stride, double uniform)
  {
    if (n <= 0)
    {
      return;
    }
    const double pairs = std::ceil(static_cast<double>(n) / (2.0 * std::max(stride, 1.0)));
    this->Count = 2 * static_cast<std::int64_t>(pairs);
    if (this->Count >= n)
    {
      this->Count = 2 * n;
      this->Interval = 0.5;
    }
    else
    {
      this->Interval = static_cast<double>(n) / static_cast<double>(this->Count);
      this->Start = this->Interval * uniform;
    }
    this->Last = n - 1;
  }

  /// Pick j's place in the run, in [0, n).
  std::int64_t operator[](std::int64_t j) const
  {
    return std::min(
      this->Last, static_cast<std::int64_t>(this->Start + static_cast<double>(j) * this->Interval));
  }

private:
  std::int64_t Last = 0; // a rounding up to n stays in the run
};

/// The picks (SystematicPicks) of one bin of a view order: its runs are
/// cells [0, cells) of the bin, run c holding the order's entries
/// [keyStarts[c], keyStarts[c + 1]); run c's start is drawn from stream
/// (seedKey, bin x cells + c). The picks are counted run after run, so that
/// any range of them can be visited on its own (a thread's share).
class ControlPicks
{
public:
  ControlPicks(const std::int64_t* keyStarts, std::int64_t bin, std::int64_t cells, double stride,
    std::uint64_t seedKey)
    : KeyStarts(keyStarts)
    , Bin(bin)
    , Stride(stride)
    , SeedKey(seedKey)
    , FirstPicks(static_cast<std::size_t>(cells + 1), 0)
  {
    for (std::int64_t c = 0; c < cells; ++c)
    {
      this->FirstPicks[static_cast<std::size_t>(c + 1)] =
        this->FirstPicks[static_cast<std::size_t>(c)] + this->Run(c, 0.0).Count;
    }
  }

  /// The bin's picks.
  std::int64_t Count() const { return this->FirstPicks.back(); }

  /// Picks [begin, end) of the bin in order: visit(entry, weight,
  /// firstHalf), entry the view order's (an index into its ids).
  template <typename Visitor>
  void Visit(std::int64_t begin, std::int64_t end, const Visitor& visit) const
  {
    std::int64_t cell = std::upper_bound(this->FirstPicks.begin(), this->FirstPicks.end(), begin) -
      this->FirstPicks.begin() - 1;
    std::int64_t j = begin - this->FirstPicks[static_cast<std::size_t>(cell)];
    for (std::int64_t pick = begin; pick < end; ++cell, j = 0)
    {
      CounterRandom random(this->SeedKey, static_cast<std::uint64_t>(this->Key(cell)));
      const SystematicPicks picks = this->Run(cell, 1.0 - random.NextOpenClosed());
      const std::int64_t first = this->KeyStarts[static_cast<std::size_t>(cell)];
      for (; j < picks.Count && pick < end; ++j, ++pick)
      {
        visit(first + picks[j], picks.Interval, j % 2 == 0);
      }
    }
  }

private:
  std::int64_t Key(std::int64_t cell) const
  {
    return this->Bin * (static_cast<std::int64_t>(this->FirstPicks.size()) - 1) + cell;
  }
  SystematicPicks Run(std::int64_t cell, double uniform) const
  {
    const std::size_t c = static_cast<std::size_t>(cell);
    return SystematicPicks(this->KeyStarts[c + 1] - this->KeyStarts[c], this->Stride, uniform);
  }

  const std::int64_t* KeyStarts; // the bin's first run's
  std::int64_t Bin;
  double Stride;
  std::uint64_t SeedKey;
  std::vector<std::int64_t> FirstPicks; // each run's first pick, and the count last
};

/// Line integrals of the controlled estimate (see the file comment); the
/// control image alone when there are no points.
template <typename Value>
void ControlledSumsToValues(const ControlledSums& sums, Value* values)
{
  const double unit = 1.0 / (FixedOne * sums.PixelArea);
  const double weighted = sums.CarriedWeight > 0 ? sums.Integral / sums.CarriedWeight * unit : 0.0;
  const double once = sums.Count > 0 ? sums.Integral / static_cast<double>(sums.Count) * unit : 0.0;
  for (std::size_t p = 0; p < sums.Pixels; ++p)
  {
    // The difference first: it is exactly 0 where every point weighs 1.
    values[p] = static_cast<Value>(
      (ToDouble(sums.Weighted[p]) * weighted - ToDouble(sums.Once[p]) * once) + sums.Control[p]);
  }
}

/// Relative RMS error of the controlled estimate of all points, from the
/// controlled estimates of its two Halton halves (the first
/// FirstHalfSize(Count) points: sums weightedFirst and onceFirst, carrying
/// firstWeight), as EstimateRelativeError: Var = E[(x_A - x_B)^2] / (n (1/a
/// + 1/b)). H cancels in the halves' difference; its own variance
/// (ControlVariance) is added. NaN below 3 points; 0 for an image that is 0
/// everywhere.
inline double EstimateControlledRelativeError(const ControlledSums& sums,
  const FixedSum* weightedFirst, const FixedSum* onceFirst, double firstWeight)
{
  const std::uint64_t first = FirstHalfSize(sums.Count);
  if (first == 0)
  {
    return sums.Count == 0 ? 0.0 : std::nan("");
  }
  const double a = static_cast<double>(first);
  const double b = static_cast<double>(sums.Count - first);
  const double n = static_cast<double>(sums.Count);
  const double secondWeight = sums.CarriedWeight - firstWeight;
  const double unit = sums.Integral / (FixedOne * sums.PixelArea);
  const double wa = firstWeight > 0 ? unit / firstWeight : 0.0;
  const double wb = secondWeight > 0 ? unit / secondWeight : 0.0;
  const double w = sums.CarriedWeight > 0 ? unit / sums.CarriedWeight : 0.0;
  double difference = 0.0, norm = 0.0;
  for (std::size_t p = 0; p < sums.Pixels; ++p)
  {
    const double weighted = ToDouble(sums.Weighted[p]), once = ToDouble(sums.Once[p]);
    const double weightedA = ToDouble(weightedFirst[p]), onceA = ToDouble(onceFirst[p]);
    const double d =
      weightedA * wa - (weighted - weightedA) * wb - (onceA / a - (once - onceA) / b) * unit;
    difference += d * d;
    const double value = (weighted * w - once / n * unit) + sums.Control[p];
    norm += value * value;
  }
  if (!(norm > 0))
  {
    return 0.0;
  }
  return std::sqrt((difference / (n * (1.0 / a + 1.0 / b)) + sums.ControlVariance) / norm);
}

} // namespace mcx

#endif
