#include "mcxPlastimatchView.h"

#include <cmath>

namespace mcx
{

namespace
{
bool Finite3(const double v[3])
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

void Cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

bool Normalize(double v[3])
{
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(length > 0) || !std::isfinite(length))
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    v[a] /= length;
  }
  return true;
}

const double Pi = 3.14159265358979323846;
}

std::string PlastimatchView::Camera(PinholeCamera& camera) const
{
  const double sad = this->SourceToAxis;
  const double sid = this->SourceToImage;
  if (!(sad > 0) || !std::isfinite(sad) || !(sid > 0) || !std::isfinite(sid))
  {
    return "the source-to-axis and source-to-image distances must be positive and finite";
  }
  if (this->Pixels[0] < 1 || this->Pixels[1] < 1)
  {
    return "the detector needs at least 1 x 1 pixels";
  }
  for (int k = 0; k < 2; ++k)
  {
    if (!(this->DetectorSize[k] > 0) || !std::isfinite(this->DetectorSize[k]))
    {
      return "the detector size must be positive and finite";
    }
  }
  if (!Finite3(this->Isocenter) || !std::isfinite(this->GantryDegrees) ||
    (this->HasImageCenter &&
      (!std::isfinite(this->ImageCenter[0]) || !std::isfinite(this->ImageCenter[1]))))
  {
    return "the isocentre, the gantry angle and the image centre must be finite";
  }
  double normal[3];
  if (this->HasNormal)
  {
    for (int a = 0; a < 3; ++a)
    {
      normal[a] = this->Normal[a];
    }
    if (!Normalize(normal))
    {
      return "the detector normal (--nrm) must be a finite, nonzero vector";
    }
  }
  else
  {
    const double a = this->GantryDegrees * Pi / 180.0;
    normal[0] = std::cos(a);
    normal[1] = -std::sin(a);
    normal[2] = 0.0;
  }
  // Camera axes: z from the source to the isocentre, x along vup x normal,
  // y = z x x (downwards, away from vup).
  double x[3], y[3];
  const double z[3] = { -normal[0], -normal[1], -normal[2] };
  Cross(this->Up, normal, x);
  if (!Finite3(this->Up) || !Normalize(x))
  {
    return "the view-up vector (--vup) must be finite and not along the detector normal";
  }
  Cross(z, x, y);
  PinholeCamera c;
  c.Fx = sid * this->Pixels[0] / this->DetectorSize[0];
  c.Fy = sid * this->Pixels[1] / this->DetectorSize[1];
  c.Cx = this->HasImageCenter ? this->ImageCenter[0] : 0.5 * (this->Pixels[0] - 1);
  c.Cy = this->HasImageCenter ? this->ImageCenter[1] : 0.5 * (this->Pixels[1] - 1);
  double source[3];
  for (int a = 0; a < 3; ++a)
  {
    source[a] = this->Isocenter[a] + sad * normal[a];
    c.R[a] = x[a];
    c.R[3 + a] = y[a];
    c.R[6 + a] = z[a];
  }
  for (int r = 0; r < 3; ++r)
  {
    c.T[r] = -(c.R[3 * r] * source[0] + c.R[3 * r + 1] * source[1] + c.R[3 * r + 2] * source[2]);
  }
  camera = c;
  return std::string();
}

} // namespace mcx
