#include "mcxIECBeamView.h"

#include <cmath>

namespace mcx
{

namespace
{
const double Pi = 3.14159265358979323846;

// Right-handed rotations by a degrees (row-major), as IEC 61217 turns its
// systems: about Y for the gantry, Z for the collimator and the couch.
void RotationY(double a, double r[9])
{
  const double c = std::cos(a * Pi / 180), s = std::sin(a * Pi / 180);
  const double m[9] = { c, 0, s, 0, 1, 0, -s, 0, c };
  for (int k = 0; k < 9; ++k)
  {
    r[k] = m[k];
  }
}

void RotationZ(double a, double r[9])
{
  const double c = std::cos(a * Pi / 180), s = std::sin(a * Pi / 180);
  const double m[9] = { c, -s, 0, s, c, 0, 0, 0, 1 };
  for (int k = 0; k < 9; ++k)
  {
    r[k] = m[k];
  }
}

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

std::string IECBeamView::Camera(PinholeCamera& camera) const
{
  const double sad = this->SourceToAxis, sid = this->SourceToImage;
  if (!(sad > 0) || !std::isfinite(sad) || !(sid > 0) || !std::isfinite(sid))
  {
    return "the source-axis and source-to-image distances must be positive and finite";
  }
  if (this->Pixels[0] < 1 || this->Pixels[1] < 1 || !(this->Pitch[0] > 0) ||
    !(this->Pitch[1] > 0) || !std::isfinite(this->Pitch[0]) || !std::isfinite(this->Pitch[1]))
  {
    return "the detector's pixels and pitch must be positive";
  }
  const double values[] = { this->GantryDegrees, this->CollimatorDegrees, this->CouchDegrees,
    this->Isocenter[0], this->Isocenter[1], this->Isocenter[2] };
  for (double value : values)
  {
    if (!std::isfinite(value))
    {
      return "the angles and the isocentre must be finite";
    }
  }
  // The collimator's axes in the couch's (the patient's) system: the couch
  // turns the patient by +couch, so the beam turns by -couch about Z.
  double couch[9], gantry[9], collimator[9], cg[9], b[9];
  RotationZ(-this->CouchDegrees, couch);
  RotationY(this->GantryDegrees, gantry);
  RotationZ(this->CollimatorDegrees, collimator);
  Multiply(couch, gantry, cg);
  Multiply(cg, collimator, b);
  // Head first supine: (X, Y, Z) of the couch are (x, z, -y) of LPS.
  double axes[3][3]; // the collimator's X, Y, Z in LPS
  for (int k = 0; k < 3; ++k)
  {
    axes[k][0] = b[k];
    axes[k][1] = -b[6 + k];
    axes[k][2] = b[3 + k];
  }
  PinholeCamera c;
  c.Fx = sid / this->Pitch[0];
  c.Fy = sid / this->Pitch[1];
  c.Cx = 0.5 * (this->Pixels[0] - 1);
  c.Cy = 0.5 * (this->Pixels[1] - 1);
  double source[3];
  for (int a = 0; a < 3; ++a)
  {
    c.R[a] = axes[0][a];      // columns along X
    c.R[3 + a] = -axes[1][a]; // rows down -Y
    c.R[6 + a] = -axes[2][a]; // forward, from the source to the isocentre
    source[a] = this->Isocenter[a] + sad * axes[2][a];
  }
  for (int r = 0; r < 3; ++r)
  {
    c.T[r] = -(c.R[3 * r] * source[0] + c.R[3 * r + 1] * source[1] + c.R[3 * r + 2] * source[2]);
  }
  camera = c;
  return std::string();
}

} // namespace mcx
