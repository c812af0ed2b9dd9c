#include "vtkMCXCameraGeometry.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"

#include <cmath>

namespace mcx
{

namespace
{
// An off-axis or sheared perspective camera (head-tracked screens, CAVEs,
// oblique frusta) from VTK's composite matrix M = P V: still a central
// projection, whose eye is where rows 0, 1 and 3 vanish, the view
// direction W is row 3's (clip w grows along it), and on a plane at
// distance F along W, n_k = (row_k . (x - eye)) / (|row 3| F) is affine in
// the plane coordinate along the part of row k orthogonal to W: the screen's
// axes. Fills eye and axes, and scale and offset with n = scale p + offset.
std::string OffAxisGeometry(vtkCamera* camera, double aspect, double distance,
  ProjectionGeometry& g, double scale[2], double offset[2])
{
  vtkMatrix4x4* m = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  double rows[4][4];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      rows[r][c] = m->GetElement(r, c);
    }
  }
  double a[3][3] = { { rows[0][0], rows[0][1], rows[0][2] }, { rows[1][0], rows[1][1], rows[1][2] },
    { rows[3][0], rows[3][1], rows[3][2] } };
  double eye[3] = { -rows[0][3], -rows[1][3], -rows[3][3] };
  double* system[3] = { a[0], a[1], a[2] };
  if (!vtkMath::SolveLinearSystem(system, eye, 3))
  {
    return "the camera's off-axis projection has no eye point";
  }
  const double depthScale = vtkMath::Norm(rows[3], 3);
  double w[3] = { rows[3][0] / depthScale, rows[3][1] / depthScale, rows[3][2] / depthScale };
  double axes[2][3];
  for (int k = 0; k < 2; ++k)
  {
    const double along = vtkMath::Dot(rows[k], w);
    for (int i = 0; i < 3; ++i)
    {
      axes[k][i] = rows[k][i] - along * w[i];
    }
    const double length = vtkMath::Normalize(axes[k]);
    scale[k] = length / (depthScale * distance);
    offset[k] = along / depthScale;
  }
  if (std::fabs(vtkMath::Dot(axes[0], axes[1])) > 1e-9)
  {
    return "the camera's off-axis screen is not rectangular";
  }
  // The near plane (normalized depth -1) along W from the eye: at E + t W,
  // (row 2 + row 3) . (E + t W, 1) = 0, and row 3 vanishes at the eye.
  double sum[3];
  for (int i = 0; i < 3; ++i)
  {
    sum[i] = rows[2][i] + rows[3][i];
  }
  const double nearDistance = -(vtkMath::Dot(rows[2], eye) + rows[2][3]) / vtkMath::Dot(sum, w);
  if (!(nearDistance > 0) || !std::isfinite(nearDistance))
  {
    return "the camera's off-axis near plane is not in front of the eye";
  }
  g.NearDistance = nearDistance;
  for (int i = 0; i < 3; ++i)
  {
    g.Eye[i] = eye[i];
    g.U[i] = axes[0][i];
    g.V[i] = axes[1][i];
    g.W[i] = w[i];
  }
  return std::string();
}

// A sheared or off-axis parallel camera from VTK's composite matrix M = P V,
// affine here: n_k = row_k . x + row_k[3]. The rays run along R, where rows
// 0 and 1 do not change, and W is row 2's direction (normalized depth grows
// from -1 at the near plane to 1 at the far one). Row k's part
// orthogonal to W, |.| times screen axis k, and its part along W, -|.| o_k,
// make n_k = |.| (x . axis_k - o_k x . W) + row_k[3]: the plane coordinate
// of ProjectionGeometry, with obliquity o_k = R . axis_k / R . W.
std::string ObliqueParallelGeometry(
  vtkCamera* camera, double aspect, ProjectionGeometry& g, double scale[2], double offset[2])
{
  vtkMatrix4x4* m = camera->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  double rows[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      rows[r][c] = m->GetElement(r, c);
    }
  }
  double w[3] = { rows[2][0], rows[2][1], rows[2][2] };
  if (!(vtkMath::Normalize(w) > 0) || m->GetElement(3, 0) != 0 || m->GetElement(3, 1) != 0 ||
    m->GetElement(3, 2) != 0)
  {
    return "the camera's parallel projection is not an affine map with a depth";
  }
  double axes[2][3];
  for (int k = 0; k < 2; ++k)
  {
    const double along = vtkMath::Dot(rows[k], w);
    for (int i = 0; i < 3; ++i)
    {
      axes[k][i] = rows[k][i] - along * w[i];
    }
    scale[k] = vtkMath::Normalize(axes[k]);
    offset[k] = m->GetElement(k, 3);
    g.Obliquity[k] = scale[k] > 0 ? -along / scale[k] : 0.0;
  }
  if (std::fabs(vtkMath::Dot(axes[0], axes[1])) > 1e-9)
  {
    return "the camera's oblique parallel screen is not rectangular";
  }
  for (int i = 0; i < 3; ++i)
  {
    g.U[i] = axes[0][i];
    g.V[i] = axes[1][i];
    g.W[i] = w[i];
  }
  return std::string();
}
}

std::string GeometryFromCamera(
  vtkCamera* camera, const int size[2], double spacing, double aspect, ProjectionGeometry& g)
{
  double position[3], focal[3], up[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  camera->GetViewUp(up);
  for (const double* point : { position, focal, up })
  {
    if (!std::isfinite(point[0]) || !std::isfinite(point[1]) || !std::isfinite(point[2]))
    {
      return "the camera's position, focal point and view-up must be finite";
    }
  }
  double w[3] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] };
  const double distance = vtkMath::Normalize(w);
  if (!(distance > 0) || !std::isfinite(distance))
  {
    return "the camera's position and focal point coincide";
  }
  const double along = vtkMath::Dot(up, w);
  double v[3] = { up[0] - along * w[0], up[1] - along * w[1], up[2] - along * w[2] };
  if (!(vtkMath::Normalize(v) > 1e-12))
  {
    return "the camera's view-up is parallel to its direction of projection";
  }
  double u[3];
  vtkMath::Cross(w, v, u); // screen right = direction of projection x view-up
  vtkMath::Normalize(u);
  for (int a = 0; a < 3; ++a)
  {
    g.U[a] = u[a];
    g.V[a] = v[a];
    g.W[a] = w[a];
    g.Eye[a] = position[a];
  }
  g.Obliquity[0] = g.Obliquity[1] = 0.0;
  g.Size[0] = size[0] > 0 ? size[0] : 512;
  g.Size[1] = size[1] > 0 ? size[1] : 512;
  g.Perspective = !camera->GetParallelProjection();
  if (!(aspect > 0) || !std::isfinite(aspect))
  {
    aspect = static_cast<double>(g.Size[0]) / g.Size[1];
  }
  // VTK's projection P maps a view-space point to normalized device
  // coordinates n = scale * x + offset along each screen axis: on the focal
  // plane (z = -D) of a frustum, n = (P[k][k] / D) x - P[k][2]; for an
  // orthographic box, n = P[k][k] x + P[k][3]. The window centre lives in
  // the offsets.
  vtkMatrix4x4* p = camera->GetProjectionTransformMatrix(aspect, -1, 1);
  double centre[2] = { 0.0, 0.0 };
  double scales[2], offsets[2];
  if (g.Perspective)
  {
    g.FocalDistance = distance;
    g.NearDistance = camera->GetClippingRange()[0];
  }
  else
  {
    centre[0] = vtkMath::Dot(focal, u);
    centre[1] = vtkMath::Dot(focal, v);
  }
  for (int k = 0; k < 2; ++k)
  {
    scales[k] = g.Perspective ? p->GetElement(k, k) / distance : p->GetElement(k, k);
    offsets[k] = g.Perspective ? -p->GetElement(k, 2) : p->GetElement(k, 3);
  }
  // Projections beyond the plain frustum or box: off-axis screens, shear, a
  // stereo eye's shift, or an explicit matrix.
  const double* shear = camera->GetViewShear();
  const bool beyond = camera->GetUseOffAxisProjection() || shear[0] != 0 || shear[1] != 0 ||
    camera->GetUseExplicitProjectionTransformMatrix();
  if (g.Perspective && (beyond || camera->GetStereo()))
  {
    const std::string problem = OffAxisGeometry(camera, aspect, distance, g, scales, offsets);
    if (!problem.empty())
    {
      return problem;
    }
  }
  else if (!g.Perspective && beyond)
  {
    const std::string problem = ObliqueParallelGeometry(camera, aspect, g, scales, offsets);
    if (!problem.empty())
    {
      return problem;
    }
    centre[0] = centre[1] = 0.0; // the composite matrix's offsets are absolute
  }
  for (int k = 0; k < 2; ++k)
  {
    const double scale = scales[k];
    const double offset = offsets[k];
    if (!(scale > 0) || !std::isfinite(scale) || !std::isfinite(offset))
    {
      return "the camera's view angle or parallel scale gives no image";
    }
    // The plane coordinate of n is (n - offset) / scale; pixel i of the
    // image is centred at n = -1 + (2 i + 1) / size.
    const double middle = centre[k] - offset / scale;
    g.Spacing[k] = spacing > 0 ? spacing : 2.0 / (g.Size[k] * scale);
    g.Origin[k] = middle - 0.5 * (g.Size[k] - 1) * g.Spacing[k];
  }
  return std::string();
}

} // namespace mcx
