#include "mcxRTKView.h"

#include <cmath>

namespace mcx
{

namespace
{
// 3x3 row-major products of ITK's Euler3DTransform rotations.
void Multiply(const double a[9], const double b[9], double c[9])
{
  for (int r = 0; r < 3; ++r)
  {
    for (int k = 0; k < 3; ++k)
    {
      c[3 * r + k] = a[3 * r] * b[k] + a[3 * r + 1] * b[3 + k] + a[3 * r + 2] * b[6 + k];
    }
  }
}
}

void RTKMatrix(const RTKProjection& p, double M[12])
{
  // Degrees to radians as RTK converts them.
  const double toRadians = std::atan(1.0) / 45.0;
  const double x = -toRadians * p.OutOfPlaneAngle;
  const double y = -toRadians * p.GantryAngle;
  const double z = -toRadians * p.InPlaneAngle;
  const double rx[9] = { 1, 0, 0, 0, std::cos(x), -std::sin(x), 0, std::sin(x), std::cos(x) };
  const double ry[9] = { std::cos(y), 0, std::sin(y), 0, 1, 0, -std::sin(y), 0, std::cos(y) };
  const double rz[9] = { std::cos(z), -std::sin(z), 0, std::sin(z), std::cos(z), 0, 0, 0, 1 };
  double zx[9], r[9];
  Multiply(rz, rx, zx);
  Multiply(zx, ry, r);
  const double sid = p.SourceToIsocenterDistance, sdd = p.SourceToDetectorDistance;
  const double shift[2] = { p.SourceOffsetX - p.ProjectionOffsetX,
    p.SourceOffsetY - p.ProjectionOffsetY };
  const double source[2] = { p.SourceOffsetX, p.SourceOffsetY };
  for (int row = 0; row < 2; ++row)
  {
    for (int k = 0; k < 3; ++k)
    {
      M[4 * row + k] = -sdd * r[3 * row + k] + shift[row] * r[6 + k];
    }
    M[4 * row + 3] = sdd * source[row] - shift[row] * sid;
  }
  for (int k = 0; k < 3; ++k)
  {
    M[8 + k] = r[6 + k];
  }
  M[11] = -sid;
}

std::string RTKPixelMatrix(const RTKProjection& p, const int pixels[2], const double origin[2],
  const double spacing[2], double P[12])
{
  const double values[] = { p.SourceToIsocenterDistance, p.SourceToDetectorDistance, p.GantryAngle,
    p.ProjectionOffsetX, p.ProjectionOffsetY, p.OutOfPlaneAngle, p.InPlaneAngle, p.SourceOffsetX,
    p.SourceOffsetY, origin[0], origin[1], spacing[0], spacing[1] };
  for (double value : values)
  {
    if (!std::isfinite(value))
    {
      return "every parameter must be finite";
    }
  }
  if (!(p.SourceToIsocenterDistance > 0) || !(p.SourceToDetectorDistance > 0))
  {
    return "SourceToIsocenterDistance and SourceToDetectorDistance must be positive (RTK's "
           "parallel geometry, SourceToDetectorDistance 0, is not supported)";
  }
  if (!(spacing[0] > 0) || !(spacing[1] > 0) || pixels[0] < 1 || pixels[1] < 1)
  {
    return "the detector's pixels and spacing must be positive";
  }
  double M[12];
  RTKMatrix(p, M);
  // Pixels: column (u - ox) / su, row from the top rows - 1 - (v - oy) / sv;
  // negated so that w > 0 in front of the source.
  for (int k = 0; k < 4; ++k)
  {
    const double u = M[k], v = M[4 + k], w = M[8 + k];
    P[k] = -(u - origin[0] * w) / spacing[0];
    P[4 + k] = -((pixels[1] - 1) * w - (v - origin[1] * w) / spacing[1]);
    P[8 + k] = -w;
  }
  return std::string();
}

} // namespace mcx
