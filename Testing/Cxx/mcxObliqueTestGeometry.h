// An oblique view for the core's tests (no VTK): 37 x 29 pixels, not a
// multiple of any vector width, U and V turned about two axes, the eye 60
// units back along W; parallel views sheared (obliquity 0.125).
#ifndef mcxObliqueTestGeometry_h
#define mcxObliqueTestGeometry_h

#include "mcxProjectionGeometry.h"

#include <cmath>

inline mcx::ProjectionGeometry ObliqueTestGeometry(bool perspective)
{
  mcx::ProjectionGeometry g;
  g.Perspective = perspective;
  g.Size[0] = 37;
  g.Size[1] = 29;
  g.Spacing[0] = 0.75;
  g.Spacing[1] = 0.5;
  g.Origin[0] = -13.0;
  g.Origin[1] = -7.0;
  // U, V, W orthonormal.
  const double a = 0.3, b = -0.7;
  const double u[3] = { std::cos(a), std::sin(a), 0 };
  const double v[3] = { -std::sin(a) * std::cos(b), std::cos(a) * std::cos(b), std::sin(b) };
  for (int r = 0; r < 3; ++r)
  {
    g.U[r] = u[r];
    g.V[r] = v[r];
  }
  g.W[0] = u[1] * v[2] - u[2] * v[1];
  g.W[1] = u[2] * v[0] - u[0] * v[2];
  g.W[2] = u[0] * v[1] - u[1] * v[0];
  for (int r = 0; r < 3; ++r)
  {
    g.Eye[r] = -60.0 * g.W[r] + 1.5 * r;
  }
  g.FocalDistance = 90.0;
  g.NearDistance = perspective ? 6.0 : 0.0;
  if (!perspective)
  {
    g.Obliquity[0] = 0.125;
  }
  return g;
}

#endif
