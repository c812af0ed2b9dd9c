// The weights of a weighted cloud's points (an every-voxel or view-ordered
// cloud's PointWeight): the range a deposit takes, and their exact sum in
// fixed point. Apart from the accumulator because the filters check and sum
// weights without depositing anything.
#ifndef mcxPointWeights_h
#define mcxPointWeights_h

#include "mcxFixedPoint.h"

#include <cstdint>
#include <sstream>
#include <string>

namespace mcx
{

/// The largest weight of a point of a weighted cloud: a point adds at most
/// 2^40 counts of 2^32 each, so no pixel's 128-bit sum comes near overflow.
constexpr double MaximumPointWeight = 1099511627776.0; // 2^40

/// Empty when each of the `count` weights is finite and in [0,
/// MaximumPointWeight] (what the deposits take); else why not, naming the
/// first point that is not.
template <typename Weight>
std::string PointWeightProblem(const Weight* weights, std::uint64_t count)
{
  for (std::uint64_t i = 0; i < count; ++i)
  {
    const double w = static_cast<double>(weights[i]);
    if (!(w >= 0.0 && w <= MaximumPointWeight)) // NaN too
    {
      std::ostringstream message;
      message << "point " << i << " has the weight " << w
              << " (weights must be finite and in [0, 2^40])";
      return message.str();
    }
  }
  return std::string();
}

/// The sum of weights [begin, end) in fixed point (each rounded to 2^-32, as
/// FixedIncrement): exact, so the same for any split of the work, and the
/// sums of consecutive ranges add up to the sum of their union.
template <typename Executor, typename Weight>
FixedSum PointWeightSum(
  const Executor& executor, const Weight* weights, std::uint64_t begin, std::uint64_t end)
{
  // A class with a zero default: a thread-local built-in integer would be
  // default-initialised (vtkSMPThreadLocal copies such an exemplar).
  struct Sum
  {
    FixedSum Value = 0;
  };
  typename Executor::template ThreadLocal<Sum> sums;
  executor.For(static_cast<std::int64_t>(begin), static_cast<std::int64_t>(end),
    std::int64_t(1) << 16,
    [&](std::int64_t b, std::int64_t e)
    {
      FixedSum& sum = sums.Local().Value;
      for (std::int64_t i = b; i < e; ++i)
      {
        sum += FixedIncrement(static_cast<double>(weights[i]));
      }
    });
  FixedSum total = 0;
  for (const Sum& sum : sums)
  {
    total += sum.Value;
  }
  return total;
}

} // namespace mcx

#endif
