// The mapper's exact accumulation buffer, free of any graphics API so that the
// tests can check it directly.
//
// It holds the fixed-point image of the first Count() points of a cloud in
// Halton order and grows it by whole prefixes without ever starting over, so
// a refined image only ever adds samples to the one on screen. When it grows
// to 2^m - 1 points it first stops at 2^(m-1) - 1 and keeps that image, which
// the error estimate compares with the rest (the same halves as the off-line
// projector's). Sums are integers, so the image is the same for any number of
// threads and equals vtkMCXProjector's for the same camera and points.
#ifndef mcxProgressiveImage_h
#define mcxProgressiveImage_h

#include "mcxAccumulator.h"
#include "mcxProjectionGeometry.h"

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace mcx
{

class ProgressiveImage
{
public:
  /// Starts over for a view: the geometry, the map from point coordinates to
  /// world (origin, row-major 3x3), and, when opaque geometry hides part of
  /// the scene, the depth (along the view direction, from the eye) beyond
  /// which each pixel's samples are hidden; empty when nothing is hidden.
  void Reset(const ProjectionGeometry& geometry, const double origin[3], const double matrix[9],
    std::vector<double> depthLimits = std::vector<double>())
  {
    this->Geometry = geometry;
    this->Binner.reset(new PixelBinner(geometry, origin, matrix));
    const std::size_t pixels = static_cast<std::size_t>(geometry.Size[0]) * geometry.Size[1];
    this->Total.assign(pixels, 0);
    this->FirstHalf.assign(pixels, 0);
    this->DepthLimits = std::move(depthLimits);
    this->Counted = 0;
    this->FirstHalfCount = 0;
  }

  /// Adds points [Count(), target) of `points` (x, y, z each) to the image.
  template <typename Real>
  void Advance(const Real* points, std::uint64_t target)
  {
    const std::uint64_t half = FirstHalfSize(target);
    if (half > this->Counted)
    {
      this->Project(points, this->Counted, half);
    }
    if (half == this->Counted && half > this->FirstHalfCount)
    {
      this->FirstHalf = this->Total;
      this->FirstHalfCount = half;
    }
    if (target > this->Counted)
    {
      this->Project(points, this->Counted, target);
    }
  }

  std::uint64_t Count() const { return this->Counted; }
  std::size_t NumberOfPixels() const { return this->Total.size(); }
  const ProjectionGeometry& GetGeometry() const { return this->Geometry; }
  bool IsOccluded() const { return !this->DepthLimits.empty(); }

  /// The fixed-point sums of the image of all Count() points.
  const std::vector<FixedSum>& Sums() const { return this->Total; }

  /// Relative RMS error of the current image, from its two halves; NaN when
  /// the halves are not known (fewer than 3 points).
  double EstimateRelativeError() const
  {
    if (this->FirstHalfCount != FirstHalfSize(this->Counted))
    {
      return std::nan("");
    }
    return mcx::EstimateRelativeError(
      this->Total.data(), this->FirstHalf.data(), this->Total.size(), this->Counted);
  }

  /// Pixel values in physical units: the line integral, each point carrying
  /// `sampleWeight` (the cloud's integral over Count()).
  template <typename Value>
  void ToValues(double sampleWeight, Value* values) const
  {
    FixedSumsToValues(this->Total.data(), this->Total.size(), sampleWeight, this->Geometry.PixelArea(), values);
  }

private:
  template <typename Real>
  void Project(const Real* points, std::uint64_t begin, std::uint64_t end)
  {
    const std::size_t pixels = this->Total.size();
    const PixelBinner& binner = *this->Binner;
    const double* limits = this->DepthLimits.empty() ? nullptr : this->DepthLimits.data();
    vtkSMPTools::For(static_cast<vtkIdType>(begin), static_cast<vtkIdType>(end), vtkIdType(1) << 15,
      [&](vtkIdType b, vtkIdType e) {
        std::vector<FixedSum>& local = this->Local.Local();
        if (local.size() != pixels)
        {
          local.assign(pixels, 0);
        }
        FixedSum* image = local.data();
        for (vtkIdType i = b; i < e; ++i)
        {
          const double p[3] = { static_cast<double>(points[3 * i]),
            static_cast<double>(points[3 * i + 1]), static_cast<double>(points[3 * i + 2]) };
          std::int64_t pixel;
          FixedSum increment;
          if (binner.Bin(p, pixel, increment) && (!limits || binner.Depth(p) < limits[pixel]))
          {
            image[pixel] += increment;
          }
        }
      });
    // Integer sums: the order in which the threads' images add up is irrelevant.
    for (std::vector<FixedSum>& local : this->Local)
    {
      if (local.size() == pixels)
      {
        for (std::size_t p = 0; p < pixels; ++p)
        {
          this->Total[p] += local[p];
        }
        std::fill(local.begin(), local.end(), FixedSum(0));
      }
    }
    this->Counted = end;
  }

  ProjectionGeometry Geometry;
  std::unique_ptr<PixelBinner> Binner;
  std::vector<FixedSum> Total;
  std::vector<FixedSum> FirstHalf;
  std::vector<double> DepthLimits;
  std::uint64_t Counted = 0;
  std::uint64_t FirstHalfCount = 0;
  vtkSMPThreadLocal<std::vector<FixedSum>> Local;
};

} // namespace mcx

#endif
