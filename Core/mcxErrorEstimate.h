// What an image's two Halton halves say about its error, and the paper's
// sample count for a given number of grey levels.
#ifndef mcxErrorEstimate_h
#define mcxErrorEstimate_h

#include "mcxFixedPoint.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace mcx
{

/// Size of the first half of a run of `count` samples, the part the error
/// estimate compares with the rest: for count = 2^m - 1 the coarser Halton
/// run of 2^(m-1) - 1 samples (every other point of the u-grid, so both
/// halves are stratified alike); else count / 2.
inline std::uint64_t FirstHalfSize(std::uint64_t count)
{
  if (count < 3)
  {
    return 0;
  }
  return ((count + 1) & count) == 0 ? (count - 1) / 2 : count / 2;
}

/// Relative RMS error of the image of all `count` samples (sums `whole`),
/// estimated from the image of its first FirstHalfSize(count) samples
/// (`firstHalf`) and that of the rest. With x_A, x_B the half images per
/// sample and x the full one, Var(x) = E[(x_A - x_B)^2] / (M (1/|A| + 1/|B|)).
/// 0 for an empty image (no samples, or all outside it: exactly known);
/// NaN for 1 or 2 samples (no halves to compare).
inline double EstimateRelativeError(
  const FixedSum* whole, const FixedSum* firstHalf, std::size_t pixels, std::uint64_t count)
{
  if (count == 0)
  {
    return 0.0;
  }
  const std::uint64_t first = FirstHalfSize(count);
  if (first == 0)
  {
    return std::nan("");
  }
  const double a = static_cast<double>(first);
  const double b = static_cast<double>(count - first);
  const double m = static_cast<double>(count);
  double difference = 0.0, norm = 0.0;
  for (std::size_t p = 0; p < pixels; ++p)
  {
    const double all = ToDouble(whole[p]);
    const double partA = ToDouble(firstHalf[p]);
    const double d = partA / a - (all - partA) / b;
    difference += d * d;
    norm += (all / m) * (all / m);
  }
  if (!(norm > 0))
  {
    return 0.0;
  }
  return std::sqrt(difference / (m * (1.0 / a + 1.0 / b)) / norm);
}

/// The same, for sums holding the image of all samples in its first half and
/// that of the first FirstHalfSize(count) samples in its second.
inline double EstimateRelativeError(const std::vector<FixedSum>& sums, std::uint64_t count)
{
  const std::size_t pixels = sums.size() / 2;
  return EstimateRelativeError(sums.data(), sums.data() + pixels, pixels, count);
}

/// The halves' estimate assumes an error falling as M^-1/2, as the point
/// deposit's does. The footprint deposit's error falls about as M^-1 (its
/// voxel choice is stratified and nothing else is random), so each half errs
/// about twice as much as the whole and their difference overstates the
/// whole's error by sqrt(2): this factor calibrates it (checked against the
/// exact reference in TestFootprint).
constexpr double FootprintErrorCalibration = 0.70710678118654752;

/// The exponent a of error ~ M^-a by which the target controls extrapolate.
inline double ErrorDecayExponent(bool footprint)
{
  return footprint ? 1.0 : 0.5;
}

/// The paper's equation 1: the sample count above which the average pixel
/// deviation stays below one of `levels` grey levels for an image displayed
/// from 0 to its maximum, (W H - 1) B^2 L^2, B = mean / maximum of the image
/// in the first half of sums.
inline double QuantizationSampleCount(const std::vector<FixedSum>& sums, int levels)
{
  const std::size_t pixels = sums.size() / 2;
  double total = 0.0, largest = 0.0;
  for (std::size_t p = 0; p < pixels; ++p)
  {
    const double v = ToDouble(sums[p]);
    total += v;
    largest = std::max(largest, v);
  }
  if (!(largest > 0) || pixels == 0)
  {
    return 0.0;
  }
  const double brightness = total / static_cast<double>(pixels) / largest;
  const double l = static_cast<double>(levels);
  return (static_cast<double>(pixels) - 1.0) * brightness * brightness * l * l;
}

} // namespace mcx

#endif
