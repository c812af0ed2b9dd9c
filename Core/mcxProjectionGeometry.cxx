#include "mcxProjectionGeometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mcx
{

namespace
{
double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
}

double ProjectionGeometry::RayLengthPerDepth() const
{
  if (this->Perspective)
  {
    return 1.0;
  }
  return std::sqrt(
    1.0 + this->Obliquity[0] * this->Obliquity[0] + this->Obliquity[1] * this->Obliquity[1]);
}

bool SameGeometry(const ProjectionGeometry& a, const ProjectionGeometry& b)
{
  auto same = [](const auto* x, const auto* y, int n) { return std::equal(x, x + n, y); };
  return a.Perspective == b.Perspective && same(a.Eye, b.Eye, 3) && same(a.U, b.U, 3) &&
    same(a.V, b.V, 3) && same(a.W, b.W, 3) && a.FocalDistance == b.FocalDistance &&
    a.NearDistance == b.NearDistance && same(a.Size, b.Size, 2) && same(a.Spacing, b.Spacing, 2) &&
    same(a.Origin, b.Origin, 2) && same(a.Obliquity, b.Obliquity, 2);
}

double TurnDegrees(const ProjectionGeometry& a, const ProjectionGeometry& b)
{
  // The rotation R_ij = A_i . B_j of the axes A = (U, V, W) of a into those
  // of b: trace 1 + 2 cos(angle), antisymmetric part sin(angle) times the
  // axis; atan2 keeps small angles as exact as large ones. Axes of opposite
  // handedness make R a reflection, no turn: a mirrored image.
  auto handedness = [](const ProjectionGeometry& g)
  {
    const double cross[3] = { g.U[1] * g.V[2] - g.U[2] * g.V[1], g.U[2] * g.V[0] - g.U[0] * g.V[2],
      g.U[0] * g.V[1] - g.U[1] * g.V[0] };
    return Dot(cross, g.W) > 0;
  };
  if (handedness(a) != handedness(b))
  {
    return 180.0;
  }
  const double* axesA[3] = { a.U, a.V, a.W };
  const double* axesB[3] = { b.U, b.V, b.W };
  double r[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      r[i][j] = Dot(axesA[i], axesB[j]);
    }
  }
  const double cosine = 0.5 * (r[0][0] + r[1][1] + r[2][2] - 1.0);
  const double sine = 0.5 *
    std::sqrt((r[2][1] - r[1][2]) * (r[2][1] - r[1][2]) +
      (r[0][2] - r[2][0]) * (r[0][2] - r[2][0]) + (r[1][0] - r[0][1]) * (r[1][0] - r[0][1]));
  const double pi = 3.14159265358979323846;
  return std::atan2(sine, cosine) * 180.0 / pi;
}

bool SameFraming(const ProjectionGeometry& a, const ProjectionGeometry& b, const double centre[3],
  double tolerance)
{
  if (a.Perspective != b.Perspective || a.Size[0] != b.Size[0] || a.Size[1] != b.Size[1])
  {
    return false;
  }
  // The point's pixel (fractions of the image) and a pixel's size there.
  auto frame = [centre](const ProjectionGeometry& g, double where[2], double size[2])
  {
    double plane[2];
    if (!ProjectToPlane(g, centre, plane[0], plane[1]))
    {
      return false;
    }
    const double d[3] = { centre[0] - g.Eye[0], centre[1] - g.Eye[1], centre[2] - g.Eye[2] };
    const double scale = g.Perspective ? Dot(d, g.W) / g.FocalDistance : 1.0;
    for (int k = 0; k < 2; ++k)
    {
      where[k] = (plane[k] - g.Origin[k]) / (g.Spacing[k] * g.Size[k]);
      size[k] = g.Spacing[k] * scale;
    }
    return true;
  };
  double whereA[2], sizeA[2], whereB[2], sizeB[2];
  if (!frame(a, whereA, sizeA) || !frame(b, whereB, sizeB))
  {
    return false;
  }
  for (int k = 0; k < 2; ++k)
  {
    if (!(std::fabs(whereB[k] - whereA[k]) <= tolerance) ||
      !(std::fabs(sizeB[k] - sizeA[k]) <= tolerance * sizeA[k]))
    {
      return false;
    }
  }
  return true;
}

void GeometryToValues(const ProjectionGeometry& g, double values[GeometryValueCount])
{
  const double perspective = g.Perspective ? 1.0 : 0.0;
  double* at = values;
  auto put = [&](const double* x, int n) { at = std::copy(x, x + n, at); };
  put(&perspective, 1);
  put(g.Eye, 3);
  put(g.U, 3);
  put(g.V, 3);
  put(g.W, 3);
  put(&g.FocalDistance, 1);
  put(&g.NearDistance, 1);
  const double size[2] = { static_cast<double>(g.Size[0]), static_cast<double>(g.Size[1]) };
  put(size, 2);
  put(g.Spacing, 2);
  put(g.Origin, 2);
  put(g.Obliquity, 2);
}

std::string ProjectionGeometry::Validate() const
{
  const double tolerance = 1e-9;
  const double* axes[3] = { this->U, this->V, this->W };
  // Comparisons written so that NaN fails them.
  for (int a = 0; a < 3; ++a)
  {
    if (!(std::fabs(Dot(axes[a], axes[a]) - 1.0) <= tolerance))
    {
      return "detector axes must be finite unit vectors";
    }
    for (int b = a + 1; b < 3; ++b)
    {
      if (!(std::fabs(Dot(axes[a], axes[b])) <= tolerance))
      {
        return "detector axes must be orthogonal";
      }
    }
  }
  if (!std::isfinite(this->Origin[0]) || !std::isfinite(this->Origin[1]) ||
    !std::isfinite(this->Eye[0]) || !std::isfinite(this->Eye[1]) || !std::isfinite(this->Eye[2]))
  {
    return "the image origin and the eye must be finite";
  }
  // Rays within about 89.4 degrees of the plane normal: beyond, a pixel's beam
  // is a sliver and its weight 1 / cos explodes.
  if (!(std::fabs(this->Obliquity[0]) <= 100 && std::fabs(this->Obliquity[1]) <= 100))
  {
    return "the rays' obliquity must be finite and at most 100 (89.4 degrees)";
  }
  if (this->Perspective && (this->Obliquity[0] != 0 || this->Obliquity[1] != 0))
  {
    return "oblique rays are for parallel views only";
  }
  if (this->Size[0] < 1 || this->Size[1] < 1)
  {
    return "image size must be at least 1x1";
  }
  if (!(this->Spacing[0] > 0 && this->Spacing[1] > 0) || !std::isfinite(this->PixelArea()) ||
    this->PixelArea() <= 0)
  {
    return "pixel spacing must be positive and finite";
  }
  if (this->Perspective)
  {
    if (!(this->FocalDistance > 0) || !std::isfinite(this->FocalDistance))
    {
      return "perspective focal distance must be positive and finite";
    }
    // Bounds the weight D^2 s / z^3 of a sample by about 1e12 / cos^3.
    if (!(this->NearDistance >= 1e-6 * this->FocalDistance) || !std::isfinite(this->NearDistance))
    {
      return "perspective near distance must be finite and at least 1e-6 times the focal distance";
    }
  }
  return std::string();
}

void ComputeSupportCorners(const int extent[6], const double origin[3], const double spacing[3],
  const double direction[9], double kernelRadius, double corners[24])
{
  for (int c = 0; c < 8; ++c)
  {
    double index[3];
    for (int a = 0; a < 3; ++a)
    {
      index[a] = (c >> a) & 1 ? extent[2 * a + 1] + kernelRadius : extent[2 * a] - kernelRadius;
      index[a] *= spacing[a];
    }
    for (int r = 0; r < 3; ++r)
    {
      corners[3 * c + r] = origin[r] + direction[3 * r] * index[0] +
        direction[3 * r + 1] * index[1] + direction[3 * r + 2] * index[2];
    }
  }
}

void CornerDepths(const ProjectionGeometry& g, const double corners[24], double depths[2])
{
  depths[0] = std::numeric_limits<double>::infinity();
  depths[1] = -depths[0];
  for (int c = 0; c < 8; ++c)
  {
    const double d[3] = { corners[3 * c] - g.Eye[0], corners[3 * c + 1] - g.Eye[1],
      corners[3 * c + 2] - g.Eye[2] };
    const double z = Dot(d, g.W);
    depths[0] = std::min(depths[0], z);
    depths[1] = std::max(depths[1], z);
  }
}

void SupportDepthRange(const ProjectionGeometry& g, const double corners[24], double range[2])
{
  range[0] = range[1] = 0.0;
  if (!g.Perspective)
  {
    return;
  }
  double depths[2];
  CornerDepths(g, corners, depths);
  range[0] = std::max(depths[0], g.NearDistance);
  range[1] = std::max(depths[1], range[0]);
}

bool ProjectToPlane(const ProjectionGeometry& g, const double x[3], double& a, double& b)
{
  if (!g.Perspective)
  {
    a = Dot(x, g.U);
    b = Dot(x, g.V);
    if (g.Obliquity[0] != 0 || g.Obliquity[1] != 0) // (rays along W need no W)
    {
      const double depth = Dot(x, g.W);
      a -= g.Obliquity[0] * depth;
      b -= g.Obliquity[1] * depth;
    }
    return true;
  }
  const double d[3] = { x[0] - g.Eye[0], x[1] - g.Eye[1], x[2] - g.Eye[2] };
  const double z = Dot(d, g.W);
  if (!(z > 0))
  {
    return false;
  }
  a = g.FocalDistance * Dot(d, g.U) / z;
  b = g.FocalDistance * Dot(d, g.V) / z;
  return true;
}

bool FrameCorners(ProjectionGeometry& g, const double corners[24], const int requestedSize[2],
  double requestedSpacing, int defaultLongSide)
{
  double lo[2] = { std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  double hi[2] = { -lo[0], -lo[1] };
  int seen = 0;
  for (int c = 0; c < 8; ++c)
  {
    double ab[2];
    const double* x = corners + 3 * c;
    bool visible = ProjectToPlane(g, x, ab[0], ab[1]);
    if (visible && g.Perspective)
    {
      const double d[3] = { x[0] - g.Eye[0], x[1] - g.Eye[1], x[2] - g.Eye[2] };
      visible = Dot(d, g.W) >= g.NearDistance;
    }
    if (visible)
    {
      ++seen;
      for (int k = 0; k < 2; ++k)
      {
        lo[k] = std::min(lo[k], ab[k]);
        hi[k] = std::max(hi[k], ab[k]);
      }
    }
  }
  if (seen == 0)
  {
    return false;
  }
  const double width[2] = { hi[0] - lo[0], hi[1] - lo[1] };
  // FrameMargin pixels on each side: room for the footprint deposit's phase
  // rounding, so that every sample's whole deposit lands in the image.
  const double margins = 2 * FrameMargin;
  double spacing = requestedSpacing;
  int size[2] = { requestedSize[0], requestedSize[1] };
  if (!(spacing > 0))
  {
    if (size[0] > 0 && size[1] > 0)
    {
      spacing = std::max(width[0] / (size[0] - margins), width[1] / (size[1] - margins));
    }
    else
    {
      spacing = std::max(width[0], width[1]) / (std::max(defaultLongSide, 1) - margins);
    }
  }
  if (!(spacing > 0) || !std::isfinite(spacing))
  {
    return false;
  }
  for (int k = 0; k < 2; ++k)
  {
    if (size[k] <= 0)
    {
      // Whole pixels of the support, and two more when their slack leaves
      // less than the margins: the grid keeps its place on the support.
      double pixels = std::ceil(width[k] / spacing - 1e-9);
      if (pixels - width[k] / spacing < margins - 1e-9)
      {
        pixels += 2;
      }
      size[k] = static_cast<int>(std::max(1.0, std::min(pixels, 1.0e6)));
    }
    const double centre = 0.5 * (lo[k] + hi[k]);
    g.Size[k] = size[k];
    g.Spacing[k] = spacing;
    g.Origin[k] = centre - 0.5 * (size[k] - 1) * spacing;
  }
  return true;
}

ProjectionGeometry AxisAlignedParallel(int axis)
{
  ProjectionGeometry g;
  const int first = axis == 0 ? 1 : 0;
  const int second = axis == 2 ? 1 : 2;
  for (int a = 0; a < 3; ++a)
  {
    g.U[a] = a == first ? 1.0 : 0.0;
    g.V[a] = a == second ? 1.0 : 0.0;
    g.W[a] = a == axis ? 1.0 : 0.0;
  }
  return g;
}

} // namespace mcx
