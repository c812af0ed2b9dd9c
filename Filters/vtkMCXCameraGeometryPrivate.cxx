#include "vtkMCXCameraGeometryPrivate.h"

#include "vtkCamera.h"
#include "vtkMath.h"

#include <cmath>

namespace mcx
{

std::string GeometryFromCamera(
  vtkCamera* camera, const int size[2], double spacing, ProjectionGeometry& g)
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
  const int across = camera->GetUseHorizontalViewAngle() ? g.Size[0] : g.Size[1];
  double centre[2] = { 0.0, 0.0 };
  if (g.Perspective)
  {
    g.FocalDistance = distance;
    g.NearDistance = camera->GetClippingRange()[0];
    if (!(spacing > 0))
    {
      spacing = 2.0 * distance *
        std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2.0) / across;
    }
  }
  else
  {
    centre[0] = vtkMath::Dot(focal, u);
    centre[1] = vtkMath::Dot(focal, v);
    if (!(spacing > 0))
    {
      spacing = 2.0 * camera->GetParallelScale() / g.Size[1];
    }
  }
  for (int k = 0; k < 2; ++k)
  {
    g.Spacing[k] = spacing;
    g.Origin[k] = centre[k] - 0.5 * (g.Size[k] - 1) * spacing;
  }
  return std::string();
}

} // namespace mcx
