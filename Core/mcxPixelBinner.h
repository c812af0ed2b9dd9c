// Projection of points to pixels and fixed-point increments, the geometric
// half of every deposit (see mcxFixedPoint.h for the increments' meaning).
#ifndef mcxPixelBinner_h
#define mcxPixelBinner_h

#include "mcxFixedPoint.h"
#include "mcxProjectionGeometry.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace mcx
{

/// Maps points given in a source frame (world = Origin + Matrix * p) to
/// pixels and fixed-point increments for one ProjectionGeometry.
class PixelBinner
{
public:
  /// The affine map to the detector and the perspective constants.
  struct Map
  {
    bool Perspective = false;
    double Near = 0.0;
    double FocalSquared = 0.0;
    double Offset[3] = { 0, 0, 0 };
    double Rows[9] = { 0 };
    double PixelScale[2] = { 0, 0 };
    double PixelOffset[2] = { 0, 0 };
  };

  /// LocatePoints reads x, y and z up to n rounded up to a multiple of this
  /// (the widest SIMD vector of doubles: 8 on AVX-512, up to 32 on SVE).
  static constexpr std::size_t LanePadding = 32;
  /// sourceOrigin and sourceMatrix (row-major 3x3) take source coordinates to world.
  PixelBinner(
    const ProjectionGeometry& g, const double sourceOrigin[3], const double sourceMatrix[9])
    : Width(g.Size[0])
    , Height(g.Size[1])
    , WidthAsDouble(g.Size[0])
    , HeightAsDouble(g.Size[1])
  {
    this->Lanes.Perspective = g.Perspective;
    this->Lanes.Near = g.NearDistance;
    this->Lanes.FocalSquared = g.FocalDistance * g.FocalDistance;
    // Rows k = 0, 1 give (x - E) . U, . V (perspective) or the plane
    // coordinates x . U - o_0 x . W, x . V - o_1 x . W (parallel, obliquity
    // o), row 2 the depth (x - E) . W, as affine functions of the source
    // coordinates p.
    double planeAxes[2][3];
    for (int k = 0; k < 2; ++k)
    {
      const double o = this->Lanes.Perspective ? 0.0 : g.Obliquity[k];
      const double* axis = k == 0 ? g.U : g.V;
      for (int r = 0; r < 3; ++r)
      {
        planeAxes[k][r] = o != 0 ? axis[r] - o * g.W[r] : axis[r];
      }
    }
    const double* axes[3] = { planeAxes[0], planeAxes[1], g.W };
    for (int k = 0; k < 3; ++k)
    {
      this->Lanes.Offset[k] = 0.0;
      for (int r = 0; r < 3; ++r)
      {
        const double base = sourceOrigin[r] - (this->Lanes.Perspective || k == 2 ? g.Eye[r] : 0.0);
        this->Lanes.Offset[k] += axes[k][r] * base;
      }
      for (int c = 0; c < 3; ++c)
      {
        double sum = 0.0;
        for (int r = 0; r < 3; ++r)
        {
          sum += axes[k][r] * sourceMatrix[3 * r + c];
        }
        this->Lanes.Rows[3 * k + c] = sum;
      }
    }
    for (int k = 0; k < 2; ++k)
    {
      if (this->Lanes.Perspective)
      {
        this->Lanes.PixelScale[k] = g.FocalDistance / g.Spacing[k];
        this->Lanes.PixelOffset[k] = -g.Origin[k] / g.Spacing[k] + 0.5;
      }
      else
      {
        // Fold the pixel scaling into the rows: one affine map to pixel units.
        for (int c = 0; c < 3; ++c)
        {
          this->Lanes.Rows[3 * k + c] /= g.Spacing[k];
        }
        this->Lanes.PixelOffset[k] =
          this->Lanes.Offset[k] / g.Spacing[k] - g.Origin[k] / g.Spacing[k] + 0.5;
      }
    }
  }

  /// Pixel index (i + Width * j) and increment of a point of weight
  /// `weight` (one count times it), or false when it misses the image or
  /// lies nearer than the near plane (perspective).
  bool Bin(const double p[3], std::int64_t& pixel, FixedSum& increment, double weight = 1.0) const
  {
    double fx, fy, f, inverseDepth;
    return this->Locate(p, fx, fy, f, inverseDepth) &&
      this->PixelOf(fx, fy, f, pixel, increment, weight);
  }

  /// Bin's second half, for a point Locate (or LocatePoints) placed at
  /// (fx, fy) with perspective weight f: its pixel and increment, or false
  /// when it misses the image.
  bool PixelOf(double fx, double fy, double f, std::int64_t& pixel, FixedSum& increment,
    double weight = 1.0) const
  {
    if (!(fx >= 0 && fx < this->WidthAsDouble && fy >= 0 && fy < this->HeightAsDouble))
    {
      return false;
    }
    increment =
      this->Lanes.Perspective || weight != 1.0 ? FixedIncrement(f * weight) : FixedOneInteger;
    pixel = static_cast<std::int64_t>(fx) + static_cast<std::int64_t>(fy) * this->Width;
    return true;
  }

  /// Continuous pixel coordinates (pixel i covers [i, i + 1)) of a point,
  /// its perspective weight f (1 in parallel views) and its inverse depth
  /// 1 / z (0 in parallel views), whether or not it falls in the image;
  /// false when it lies nearer than the near plane (perspective) or its
  /// pixel coordinates are not finite.
  bool Locate(const double p[3], double& fx, double& fy, double& f, double& inverseDepth) const
  {
    double eye[3];
    if (!this->Project(p, fx, fy, eye, inverseDepth))
    {
      return false;
    }
    if (!this->Lanes.Perspective)
    {
      f = 1.0;
      return true;
    }
    // U, V, W are orthonormal, so the distance from the eye is |(u, v, z)|.
    const double s = std::sqrt(eye[0] * eye[0] + eye[1] * eye[1] + eye[2] * eye[2]);
    f = this->Lanes.FocalSquared * s * inverseDepth * inverseDepth * inverseDepth;
    return true;
  }

  /// Locate's fx and fy alone, the same bits, and its result: without the
  /// perspective weight's square root, for a pass that only bins.
  bool PixelPosition(const double p[3], double& fx, double& fy) const
  {
    double eye[3], inverseDepth;
    return this->Project(p, fx, fy, eye, inverseDepth);
  }

  /// Locate for n points (x, y, z readable up to n rounded up to a
  /// multiple of LanePadding) on the CPU's widest SIMD lanes, bit for bit
  /// the same: fx, fy, f of point i, located[i] = Locate's result, and
  /// its inverse depth when inverseDepth is given (mcxPixelBinnerLanes.cxx).
  void LocatePoints(const double* x, const double* y, const double* z, std::size_t n, double* fx,
    double* fy, double* f, std::uint8_t* located, double* inverseDepth = nullptr) const;

  /// The affine map and perspective constants that Locate computes with.
  const Map& Mapping() const { return this->Lanes; }

  /// The instruction set LocatePoints runs on (Highway's name: AVX3, AVX2, SSE4, EMU128...).
  static const char* LanesInstructionSet();

  /// A voxel's edges (given in the source frame: row-major, column k is edge
  /// k) in pixels on the detector: exact in parallel views; in perspective
  /// views at depth 1, to be scaled by 1 / z (the central direction's
  /// projection).
  void PixelAxes(const double voxel[9], double axes[3][2]) const
  {
    for (int k = 0; k < 3; ++k)
    {
      for (int a = 0; a < 2; ++a)
      {
        const double* row = this->Lanes.Rows + 3 * a;
        const double step = row[0] * voxel[k] + row[1] * voxel[3 + k] + row[2] * voxel[6 + k];
        axes[k][a] = step * (this->Lanes.Perspective ? this->Lanes.PixelScale[a] : 1.0);
      }
    }
  }

  bool IsPerspective() const { return this->Lanes.Perspective; }
  int GetWidth() const { return this->Width; }
  int GetHeight() const { return this->Height; }

  /// Distance of a point from the eye along the viewing direction W.
  double Depth(const double p[3]) const
  {
    const double* m = this->Lanes.Rows + 6;
    return m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + this->Lanes.Offset[2];
  }

private:
  // Locate's first part: the pixel coordinates (finite, else false) and,
  // in perspective views, the point in the eye's frame (u, v, depth) and
  // its inverse depth (0 in parallel views); false nearer than the near
  // plane.
  bool Project(const double p[3], double& fx, double& fy, double eye[3], double& inverseDepth) const
  {
    const double* m = this->Lanes.Rows;
    if (!this->Lanes.Perspective)
    {
      fx = m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + this->Lanes.PixelOffset[0];
      fy = m[3] * p[0] + m[4] * p[1] + m[5] * p[2] + this->Lanes.PixelOffset[1];
      inverseDepth = 0.0;
      return std::isfinite(fx) && std::isfinite(fy);
    }
    eye[0] = m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + this->Lanes.Offset[0];
    eye[1] = m[3] * p[0] + m[4] * p[1] + m[5] * p[2] + this->Lanes.Offset[1];
    eye[2] = m[6] * p[0] + m[7] * p[1] + m[8] * p[2] + this->Lanes.Offset[2];
    if (!(eye[2] >= this->Lanes.Near))
    {
      return false;
    }
    inverseDepth = 1.0 / eye[2];
    fx = eye[0] * inverseDepth * this->Lanes.PixelScale[0] + this->Lanes.PixelOffset[0];
    fy = eye[1] * inverseDepth * this->Lanes.PixelScale[1] + this->Lanes.PixelOffset[1];
    return std::isfinite(fx) && std::isfinite(fy);
  }

  Map Lanes; // what Locate computes with, also on SIMD lanes
  int Width;
  int Height;
  double WidthAsDouble;
  double HeightAsDouble;
};

} // namespace mcx

#endif
