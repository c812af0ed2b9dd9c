#include "mcxCameraSpec.h"

#include "mcxFail.h"
#include "mcxOptionValues.h"

#include "vtkCamera.h"
#include "vtkMath.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace mcxapp
{

namespace
{
void SetParallel(vtkCamera* camera, const std::string& kind, bool hasNear)
{
  const double scale = ParseNumber(kind.substr(9), "--camera parallel");
  if (!(scale > 0))
  {
    Fail("--camera parallel scale must be positive");
  }
  camera->ParallelProjectionOn();
  camera->SetParallelScale(scale);
  if (hasNear)
  {
    Fail("--camera near= applies to perspective views only");
  }
}

// Integration starts at the near plane: 0.001 times the camera distance
// unless near=D says otherwise.
void SetPerspective(
  vtkCamera* camera, const std::string& kind, const std::string* nearPart, double distance)
{
  const double angle = ParseNumber(kind.substr(6), "--camera angle");
  if (!(angle > 0 && angle < 180))
  {
    Fail("--camera angle must lie in (0, 180) degrees");
  }
  camera->ParallelProjectionOff();
  camera->SetViewAngle(angle);
  double nearDistance = 1e-3 * distance;
  if (nearPart)
  {
    if (nearPart->rfind("near=", 0) != 0)
    {
      Fail("bad --camera '" + *nearPart + "' (expected near=D)");
    }
    nearDistance = ParseNumber(nearPart->substr(5), "--camera near");
    if (!(nearDistance > 0))
    {
      Fail("--camera near must be positive");
    }
  }
  camera->SetClippingRange(nearDistance, std::max(nearDistance * 2, 1e6 * distance));
}
}

vtkSmartPointer<vtkCamera> ParseCamera(const std::string& text)
{
  const std::vector<std::string> parts = Split(text, ':');
  if (parts.size() != 4 && parts.size() != 5)
  {
    Fail("bad --camera '" + text + "' (expected P:F:U:parallel=S or P:F:U:angle=A[:near=D])");
  }
  double position[3], focal[3], up[3];
  ParseTriple(parts[0], position, "--camera position");
  ParseTriple(parts[1], focal, "--camera focal point");
  ParseTriple(parts[2], up, "--camera view-up");
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetPosition(position);
  camera->SetFocalPoint(focal);
  camera->SetViewUp(up);
  const double distance = std::sqrt(vtkMath::Distance2BetweenPoints(position, focal));
  if (!std::isfinite(distance))
  {
    Fail("--camera position and focal point are too far apart (their distance overflows)");
  }
  if (!(distance > 0))
  {
    Fail("--camera position and focal point coincide");
  }
  double direction[3] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] },
         side[3];
  vtkMath::Cross(direction, up, side);
  if (!(vtkMath::Norm(side) > 1e-12 * distance * vtkMath::Norm(up)) || !std::isfinite(vtkMath::Norm(side)))
  {
    Fail("--camera view-up is zero or along the direction of view");
  }
  const std::string& kind = parts[3];
  if (kind.rfind("parallel=", 0) == 0)
  {
    SetParallel(camera, kind, parts.size() == 5);
  }
  else if (kind.rfind("angle=", 0) == 0)
  {
    SetPerspective(camera, kind, parts.size() == 5 ? &parts[4] : nullptr, distance);
  }
  else
  {
    Fail("bad --camera kind '" + kind + "' (expected parallel=S or angle=A)");
  }
  return camera;
}

void AxisViewDetector(const std::string& axis, double detectorU[3], double detectorV[3])
{
  static const std::map<std::string, int> axes = { { "+x", 0 }, { "-x", 0 }, { "x", 0 },
    { "+y", 1 }, { "-y", 1 }, { "y", 1 }, { "+z", 2 }, { "-z", 2 }, { "z", 2 } };
  const auto found = axes.find(axis);
  if (found == axes.end())
  {
    Fail("unknown --view '" + axis + "' (expected +x, -x, +y, -y, +z or -z)");
  }
  for (int a = 0; a < 3; ++a)
  {
    detectorU[a] = detectorV[a] = 0;
  }
  detectorU[found->second == 0 ? 1 : 0] = 1;
  detectorV[found->second == 2 ? 1 : 2] = 1;
}

} // namespace mcxapp
