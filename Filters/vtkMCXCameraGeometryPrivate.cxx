#include "vtkMCXCameraGeometryPrivate.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"

#include <cmath>

namespace mcx
{

std::string GeometryFromCamera(
  vtkCamera* camera, const int size[2], double spacing, double aspect, ProjectionGeometry& g)
{
  double position[3], focal[3], up[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  camera->GetViewUp(up);
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
    const double scale = g.Perspective ? p->GetElement(k, k) / distance : p->GetElement(k, k);
    const double offset = g.Perspective ? -p->GetElement(k, 2) : p->GetElement(k, 3);
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

bool HasUnmodelledProjection(vtkCamera* camera)
{
  const double* shear = camera->GetViewShear();
  return shear[0] != 0 || shear[1] != 0 || camera->GetUseOffAxisProjection();
}

} // namespace mcx
