// The detector geometry of a vtkCamera, shared by the off-line projectors and
// the mapper so that both see a camera exactly as VTK's renderer does.
#ifndef vtkMCXCameraGeometryPrivate_h
#define vtkMCXCameraGeometryPrivate_h

#include "MonteCarloXRayFiltersModule.h" // for the export macro
#include "mcxProjectionGeometry.h"

#include <string>

class vtkCamera;

namespace mcx
{

/// Fills the axes, eye and field of view of `camera` for an image of `size`
/// pixels (0 = 512) with square pixels of `spacing` world units on the focal
/// plane (0 = what the camera's view angle or parallel scale gives, as VTK
/// renders it). Returns why the camera is unusable, or "".
MONTECARLOXRAYFILTERS_EXPORT std::string GeometryFromCamera(
  vtkCamera* camera, const int size[2], double spacing, ProjectionGeometry& g);

} // namespace mcx

#endif
