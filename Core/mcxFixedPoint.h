// Exact, order-independent image sums.
//
// Every sample adds an integer to its pixel: 2^32 in a parallel view (so the
// sum is an exact count), round(2^32 * f) in a perspective view, where
// f = D^2 s / z^3 turns the sample's share of a pixel's frustum into its share
// of the pixel's line integral (s the distance from the eye, z the depth,
// D the focal distance; f = 1 at the focal point). Integer sums do not depend
// on the order of addition, so images are bit-identical for any thread count;
// 128-bit sums hold 2^96 parallel samples per pixel.
#ifndef mcxFixedPoint_h
#define mcxFixedPoint_h

#include "mcxWideInteger.h"

#include <cstddef>
#include <cstdint>

namespace mcx
{

using FixedSum = UInt128;
constexpr double FixedOne = 4294967296.0; // 2^32
constexpr FixedSum FixedOneInteger = FixedSum(1) << 32;

/// round(2^32 f) for a weight f >= 0.
inline FixedSum FixedIncrement(double f)
{
  const double scaled = f * FixedOne + 0.5;
  return scaled < 1.8e19 ? FixedSum(static_cast<std::uint64_t>(scaled)) : UInt128FromDouble(scaled);
}

/// Converts the first `pixels` fixed-point sums to pixel values:
/// sum / 2^32 * sampleWeight / area (the beam cross-section of a pixel).
template <typename Value>
void FixedSumsToValues(
  const FixedSum* sums, std::size_t pixels, double sampleWeight, double pixelArea, Value* values)
{
  const double scale = sampleWeight / pixelArea / FixedOne;
  for (std::size_t i = 0; i < pixels; ++i)
  {
    values[i] = static_cast<Value>(ToDouble(sums[i]) * scale);
  }
}

} // namespace mcx

#endif
