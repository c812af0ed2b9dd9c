// Exact, order-independent accumulation of projected samples.
//
// Every sample adds an integer to its pixel: 2^32 in a parallel view (so the
// sum is an exact count), round(2^32 * f) in a perspective view, where
// f = D^2 s / z^3 turns the sample's share of a pixel's frustum into its share
// of the pixel's line integral (s the distance from the eye, z the depth,
// D the focal distance; f = 1 at the focal point). Integer sums do not depend
// on the order of addition, so images are bit-identical for any thread count;
// 128-bit sums hold 2^96 parallel samples per pixel.
#ifndef mcxAccumulator_h
#define mcxAccumulator_h

#include "mcxProjectionGeometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace mcx
{

using FixedSum = unsigned __int128;
constexpr double FixedOne = 4294967296.0; // 2^32
constexpr FixedSum FixedOneInteger = FixedSum(1) << 32;

/// Maps points given in a source frame (world = Origin + Matrix * p) to
/// pixels and fixed-point increments for one ProjectionGeometry.
class PixelBinner
{
public:
  /// sourceOrigin and sourceMatrix (row-major 3x3) take source coordinates to world.
  PixelBinner(const ProjectionGeometry& g, const double sourceOrigin[3], const double sourceMatrix[9])
    : Perspective(g.Perspective)
    , Width(g.Size[0])
    , Height(g.Size[1])
    , WidthAsDouble(g.Size[0])
    , HeightAsDouble(g.Size[1])
    , Near(g.NearDistance)
    , FocalSquared(g.FocalDistance * g.FocalDistance)
  {
    const double* axes[3] = { g.U, g.V, g.W };
    // Rows k = 0, 1 give (x - E) . U, . V (perspective) or x . U, x . V
    // (parallel), row 2 the depth (x - E) . W, as affine functions of the
    // source coordinates p.
    for (int k = 0; k < 3; ++k)
    {
      this->Offset[k] = 0.0;
      for (int r = 0; r < 3; ++r)
      {
        const double base = sourceOrigin[r] - (this->Perspective || k == 2 ? g.Eye[r] : 0.0);
        this->Offset[k] += axes[k][r] * base;
      }
      for (int c = 0; c < 3; ++c)
      {
        double sum = 0.0;
        for (int r = 0; r < 3; ++r)
        {
          sum += axes[k][r] * sourceMatrix[3 * r + c];
        }
        this->Rows[3 * k + c] = sum;
      }
    }
    for (int k = 0; k < 2; ++k)
    {
      if (this->Perspective)
      {
        this->PixelScale[k] = g.FocalDistance / g.Spacing[k];
        this->PixelOffset[k] = -g.Origin[k] / g.Spacing[k] + 0.5;
      }
      else
      {
        // Fold the pixel scaling into the rows: one affine map to pixel units.
        for (int c = 0; c < 3; ++c)
        {
          this->Rows[3 * k + c] /= g.Spacing[k];
        }
        this->PixelOffset[k] = this->Offset[k] / g.Spacing[k] - g.Origin[k] / g.Spacing[k] + 0.5;
      }
    }
  }

  /// Pixel index (i + Width * j) and increment of a point, or false when it
  /// misses the image or lies nearer than the near plane (perspective).
  bool Bin(const double p[3], std::int64_t& pixel, FixedSum& increment) const
  {
    const double* m = this->Rows;
    double fx, fy;
    if (!this->Perspective)
    {
      fx = m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + this->PixelOffset[0];
      fy = m[3] * p[0] + m[4] * p[1] + m[5] * p[2] + this->PixelOffset[1];
      increment = FixedOneInteger;
    }
    else
    {
      const double u = m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + this->Offset[0];
      const double v = m[3] * p[0] + m[4] * p[1] + m[5] * p[2] + this->Offset[1];
      const double z = m[6] * p[0] + m[7] * p[1] + m[8] * p[2] + this->Offset[2];
      if (!(z >= this->Near))
      {
        return false;
      }
      const double inverseZ = 1.0 / z;
      fx = u * inverseZ * this->PixelScale[0] + this->PixelOffset[0];
      fy = v * inverseZ * this->PixelScale[1] + this->PixelOffset[1];
      if (!(fx >= 0 && fx < this->WidthAsDouble && fy >= 0 && fy < this->HeightAsDouble))
      {
        return false;
      }
      // U, V, W are orthonormal, so the distance from the eye is |(u, v, z)|.
      const double s = std::sqrt(u * u + v * v + z * z);
      const double f = this->FocalSquared * s * inverseZ * inverseZ * inverseZ;
      const double scaled = f * FixedOne + 0.5;
      increment = scaled < 1.8e19 ? static_cast<FixedSum>(static_cast<std::uint64_t>(scaled))
                                  : static_cast<FixedSum>(scaled);
    }
    if (!(fx >= 0 && fx < this->WidthAsDouble && fy >= 0 && fy < this->HeightAsDouble))
    {
      return false;
    }
    pixel = static_cast<std::int64_t>(fx) + static_cast<std::int64_t>(fy) * this->Width;
    return true;
  }

  /// Distance of a point from the eye along the viewing direction W.
  double Depth(const double p[3]) const
  {
    const double* m = this->Rows + 6;
    return m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + this->Offset[2];
  }

private:
  bool Perspective;
  int Width;
  int Height;
  double WidthAsDouble;
  double HeightAsDouble;
  double Near;
  double FocalSquared;
  double Offset[3] = { 0, 0, 0 };
  double Rows[9] = { 0 };
  double PixelScale[2] = { 0, 0 };
  double PixelOffset[2] = { 0, 0 };
};

/// Converts the first `pixels` fixed-point sums to pixel values:
/// sum / 2^32 * sampleWeight / pixelArea.
template <typename Value>
void FixedSumsToValues(const FixedSum* sums, std::size_t pixels, double sampleWeight,
  double pixelArea, Value* values)
{
  const double scale = sampleWeight / pixelArea / FixedOne;
  for (std::size_t i = 0; i < pixels; ++i)
  {
    values[i] = static_cast<Value>(static_cast<double>(sums[i]) * scale);
  }
}

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
/// NaN below 3 samples; 0 for an empty image.
inline double EstimateRelativeError(
  const FixedSum* whole, const FixedSum* firstHalf, std::size_t pixels, std::uint64_t count)
{
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
    const double all = static_cast<double>(whole[p]);
    const double partA = static_cast<double>(firstHalf[p]);
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
    const double v = static_cast<double>(sums[p]);
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
