#include "mcxProjectionMatrix.h"

#include <algorithm>
#include <cmath>

namespace mcx
{

namespace
{
double Dot3(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double Norm3(const double* a)
{
  return std::sqrt(Dot3(a, a));
}

// K's skew, relative to fx, below which pixels count as rectangles: it
// moves no point of a 65536-pixel detector by more than 0.033 pixel, and it
// is far above the rounding of a matrix written with 9 digits.
const double SkewTolerance = 1e-6;
}

void PinholeCamera::Source(double source[3]) const
{
  for (int a = 0; a < 3; ++a)
  {
    source[a] =
      -(this->R[a] * this->T[0] + this->R[3 + a] * this->T[1] + this->R[6 + a] * this->T[2]);
  }
}

void MatrixFromPinhole(const PinholeCamera& c, double P[12])
{
  const double K[9] = { c.Fx, 0, c.Cx, 0, c.Fy, c.Cy, 0, 0, 1 };
  for (int r = 0; r < 3; ++r)
  {
    for (int col = 0; col < 3; ++col)
    {
      P[4 * r + col] =
        K[3 * r] * c.R[col] + K[3 * r + 1] * c.R[3 + col] + K[3 * r + 2] * c.R[6 + col];
    }
    P[4 * r + 3] = K[3 * r] * c.T[0] + K[3 * r + 1] * c.T[1] + K[3 * r + 2] * c.T[2];
  }
}

std::string PinholeFromMatrix(const double P[12], PinholeCamera& camera)
{
  for (int k = 0; k < 12; ++k)
  {
    if (!std::isfinite(P[k]))
    {
      return "the projection matrix has a value that is not a finite number";
    }
  }
  // A camera's matrix is defined up to scale: divided by its largest entry,
  // 1e300 and 1e-300 scales neither overflow nor underflow below.
  double largest = 0.0;
  for (int k = 0; k < 12; ++k)
  {
    largest = std::max(largest, std::fabs(P[k]));
  }
  const double unit = largest > 0.0 ? 1.0 / largest : 1.0;
  double m[3][3], p4[3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m[r][c] = P[4 * r + c] * unit;
    }
    p4[r] = P[4 * r + 3] * unit;
  }
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
    m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
    m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  const double scale = Norm3(m[0]) * Norm3(m[1]) * Norm3(m[2]);
  if (!(std::fabs(det) > 1e-12 * scale))
  {
    return "the projection matrix's left 3x3 block has rank below 3 (no source point: an affine "
           "or degenerate matrix)";
  }
  // The overall sign that makes det M > 0: then K's diagonal is positive
  // with a proper rotation, and w > 0 in front of the source.
  const double sign = det > 0 ? 1.0 : -1.0;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m[r][c] *= sign;
    }
    p4[r] *= sign;
  }
  // RQ decomposition by Gram-Schmidt on the rows, from the last.
  double R[3][3];
  const double k33 = Norm3(m[2]);
  for (int c = 0; c < 3; ++c)
  {
    R[2][c] = m[2][c] / k33;
  }
  const double k23 = Dot3(m[1], R[2]);
  double row[3];
  for (int c = 0; c < 3; ++c)
  {
    row[c] = m[1][c] - k23 * R[2][c];
  }
  const double k22 = Norm3(row);
  for (int c = 0; c < 3; ++c)
  {
    R[1][c] = row[c] / k22;
  }
  const double k13 = Dot3(m[0], R[2]);
  const double k12 = Dot3(m[0], R[1]);
  for (int c = 0; c < 3; ++c)
  {
    row[c] = m[0][c] - k13 * R[2][c] - k12 * R[1][c];
  }
  const double k11 = Norm3(row);
  for (int c = 0; c < 3; ++c)
  {
    R[0][c] = row[c] / k11;
  }
  if (!(std::fabs(k12) <= SkewTolerance * k11))
  {
    return "the projection matrix has skewed pixels (K's skew " + std::to_string(k12 / k33) +
      " of fx " + std::to_string(k11 / k33) + "): only rectangular pixels are supported";
  }
  PinholeCamera c;
  c.Fx = k11 / k33;
  c.Fy = k22 / k33;
  c.Cx = k13 / k33;
  c.Cy = k23 / k33;
  for (int r = 0; r < 3; ++r)
  {
    for (int col = 0; col < 3; ++col)
    {
      c.R[3 * r + col] = R[r][col];
    }
  }
  // t solves K t = p4 / k33 (K with its negligible skew, exact for P).
  const double skew = k12 / k33;
  c.T[2] = p4[2] / k33;
  c.T[1] = (p4[1] / k33 - c.Cy * c.T[2]) / c.Fy;
  c.T[0] = (p4[0] / k33 - skew * c.T[1] - c.Cx * c.T[2]) / c.Fx;
  camera = c;
  return std::string();
}

std::string GeometryFromPinhole(
  const PinholeCamera& c, const int size[2], double focalDistance, ProjectionGeometry& geometry)
{
  if (!(focalDistance > 0) || !std::isfinite(focalDistance))
  {
    return "the focal distance must be positive and finite";
  }
  if (!(c.Fx > 0 && c.Fy > 0) || !std::isfinite(c.Fx) || !std::isfinite(c.Fy) ||
    !std::isfinite(c.Cx) || !std::isfinite(c.Cy))
  {
    return "the focal lengths must be positive and finite, the principal point finite";
  }
  ProjectionGeometry g;
  g.Perspective = true;
  c.Source(g.Eye);
  for (int a = 0; a < 3; ++a)
  {
    g.U[a] = c.R[a];
    g.V[a] = -c.R[3 + a];
    g.W[a] = c.R[6 + a];
  }
  g.FocalDistance = focalDistance;
  // Nothing a radiograph sees is nearer than this; it bounds the weights.
  g.NearDistance = 1e-3 * focalDistance;
  g.Size[0] = size[0];
  g.Size[1] = size[1];
  g.Spacing[0] = focalDistance / c.Fx;
  g.Spacing[1] = focalDistance / c.Fy;
  g.Origin[0] = -c.Cx * g.Spacing[0];
  g.Origin[1] = (c.Cy - (size[1] - 1)) * g.Spacing[1];
  const std::string problem = g.Validate();
  if (!problem.empty())
  {
    return problem;
  }
  geometry = g;
  return std::string();
}

bool IsAffineMatrix(const double P[12])
{
  for (int k = 0; k < 12; ++k)
  {
    if (!std::isfinite(P[k]))
    {
      return false;
    }
  }
  return P[8] == 0.0 && P[9] == 0.0 && P[10] == 0.0 && P[11] != 0.0;
}

namespace
{
void Cross3(const double* a, const double* b, double* c)
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

// The detector plane's normal for an affine P's rows a and b (independent):
// the rays' direction n = a x b where a and b are perpendicular, else n
// tilted towards a bisector m of a and b by the angle whose sine squared is
// 2 |cos phi| / (1 + |cos phi|), phi the angle between a and b: then
// (a . W)(b . W) = a . b, so that a and b less their parts along W are
// perpendicular (rectangular pixels on the plane). Returns whether the
// rows are perpendicular (W then along the rays).
bool DetectorNormal(const double a[3], const double b[3], double W[3])
{
  double n[3];
  Cross3(a, b, n);
  const double nn = Norm3(n);
  const double na = Norm3(a), nb = Norm3(b);
  // Rows perpendicular but for rounding (a skew moving no pixel of a
  // 65536-pixel side by 1e-7 pixel) count as perpendicular: the square
  // root below would make 1e-16 a tilt of 1e-8.
  double c = Dot3(a, b) / (na * nb);
  c = std::fabs(c) <= 1e-12 ? 0.0 : c;
  const double sign = c < 0 ? -1.0 : 1.0;
  double m[3];
  for (int i = 0; i < 3; ++i)
  {
    m[i] = a[i] / na + sign * b[i] / nb;
  }
  const double nm = Norm3(m);
  const double sine2 = 2.0 * std::fabs(c) / (1.0 + std::fabs(c));
  const double sine = std::sqrt(sine2), cosine = std::sqrt(1.0 - sine2);
  for (int i = 0; i < 3; ++i)
  {
    W[i] = cosine * n[i] / nn + (nm > 0 ? sine * m[i] / nm : 0.0);
  }
  return c == 0.0;
}
}

std::string GeometryFromAffineMatrix(
  const double P[12], const int size[2], ProjectionGeometry& geometry)
{
  if (!IsAffineMatrix(P))
  {
    return "the projection matrix is not affine (its last row must be 0 0 0 c, c not 0)";
  }
  double a[3], b[3];
  for (int i = 0; i < 3; ++i)
  {
    a[i] = P[i] / P[11];
    b[i] = P[4 + i] / P[11];
  }
  double n[3];
  Cross3(a, b, n);
  if (!(Norm3(n) > 1e-12 * Norm3(a) * Norm3(b)))
  {
    return "the affine projection matrix's first two rows are not independent (no direction for "
           "the rays)";
  }
  double W[3];
  const bool alongW = DetectorNormal(a, b, W);
  // a = (U - o0 W) / s0 and b = -(V - o1 W) / s1 (MatrixFromGeometry); rays
  // along W have o0 = o1 = 0 exactly.
  ProjectionGeometry g;
  double aPlane[3], bPlane[3];
  for (int i = 0; i < 3; ++i)
  {
    aPlane[i] = alongW ? a[i] : a[i] - Dot3(a, W) * W[i];
    bPlane[i] = alongW ? b[i] : b[i] - Dot3(b, W) * W[i];
  }
  g.Spacing[0] = 1.0 / Norm3(aPlane);
  g.Spacing[1] = 1.0 / Norm3(bPlane);
  for (int i = 0; i < 3; ++i)
  {
    g.U[i] = aPlane[i] * g.Spacing[0];
    g.V[i] = -bPlane[i] * g.Spacing[1];
  }
  Cross3(g.V, g.U, g.W); // the perspective frame's handedness (GeometryFromPinhole)
  g.Obliquity[0] = alongW ? 0.0 : -Dot3(a, g.W) * g.Spacing[0];
  g.Obliquity[1] = alongW ? 0.0 : Dot3(b, g.W) * g.Spacing[1];
  g.Size[0] = size[0];
  g.Size[1] = size[1];
  g.Origin[0] = -(P[3] / P[11]) * g.Spacing[0];
  g.Origin[1] = (P[7] / P[11] - (size[1] - 1)) * g.Spacing[1];
  const std::string problem = g.Validate();
  if (!problem.empty())
  {
    return problem;
  }
  geometry = g;
  return std::string();
}

std::string ProjectionMatrixProblem(const double P[12])
{
  if (IsAffineMatrix(P))
  {
    const int size[2] = { 1, 1 };
    ProjectionGeometry unused;
    return GeometryFromAffineMatrix(P, size, unused);
  }
  PinholeCamera unused;
  return PinholeFromMatrix(P, unused);
}

PinholeCamera PinholeFromGeometry(const ProjectionGeometry& g)
{
  PinholeCamera c;
  c.Fx = g.FocalDistance / g.Spacing[0];
  c.Fy = g.FocalDistance / g.Spacing[1];
  c.Cx = -g.Origin[0] / g.Spacing[0];
  c.Cy = (g.Size[1] - 1) + g.Origin[1] / g.Spacing[1];
  for (int a = 0; a < 3; ++a)
  {
    c.R[a] = g.U[a];
    c.R[3 + a] = -g.V[a];
    c.R[6 + a] = g.W[a];
  }
  for (int r = 0; r < 3; ++r)
  {
    c.T[r] = -Dot3(c.R + 3 * r, g.Eye);
  }
  return c;
}

void MatrixFromGeometry(const ProjectionGeometry& g, double P[12])
{
  if (g.Perspective)
  {
    MatrixFromPinhole(PinholeFromGeometry(g), P);
    return;
  }
  // Plane coordinates (x . U - o0 x . W, x . V - o1 x . W), then pixels.
  for (int a = 0; a < 3; ++a)
  {
    P[a] = (g.U[a] - g.Obliquity[0] * g.W[a]) / g.Spacing[0];
    P[4 + a] = -(g.V[a] - g.Obliquity[1] * g.W[a]) / g.Spacing[1];
    P[8 + a] = 0.0;
  }
  P[3] = -g.Origin[0] / g.Spacing[0];
  P[7] = (g.Size[1] - 1) + g.Origin[1] / g.Spacing[1];
  P[11] = 1.0;
}

bool ProjectPoint(const double P[12], const double x[3], double& u, double& v)
{
  const double w = Dot3(P + 8, x) + P[11];
  if (!(w > 0))
  {
    return false;
  }
  const double pu = (Dot3(P, x) + P[3]) / w;
  const double pv = (Dot3(P + 4, x) + P[7]) / w;
  if (!std::isfinite(pu) || !std::isfinite(pv))
  {
    return false;
  }
  u = pu;
  v = pv;
  return true;
}

} // namespace mcx
