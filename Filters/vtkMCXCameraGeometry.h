// The detector geometry of a vtkCamera, shared by the off-line projectors and
// the mapper so that both see a camera exactly as VTK's renderer does.
#ifndef vtkMCXCameraGeometry_h
#define vtkMCXCameraGeometry_h

#include "MonteCarloXRayFiltersModule.h" // for the export macro
#include "mcxProjectionGeometry.h"

#include <string>

class vtkCamera;

namespace mcx
{

/// Fills the axes, eye and detector grid of `camera` for an image of `size`
/// pixels (0 = 512) exactly as VTK's projection matrix for `aspect` (0 =
/// size[0] / size[1], square pixels; a renderer passes its tiled aspect
/// ratio) places them: window centre and tiled viewports included, so that
/// a tile of a large screenshot is that part of the large image. Pixels are
/// `spacing` world units on the focal plane when spacing > 0, centred where
/// the camera's window centre puts the image centre. A perspective camera
/// with off-axis projection (screen corners and eye position, as
/// head-tracked displays set them) or view shear is taken from VTK's
/// composite matrix: the eye, the screen's axes and its normal. So is a
/// parallel camera with shear, off-axis projection or an explicit matrix:
/// its rays may be oblique to the screen (ProjectionGeometry::Obliquity).
/// Returns why the camera is unusable, or "".
MONTECARLOXRAYFILTERS_EXPORT std::string GeometryFromCamera(
  vtkCamera* camera, const int size[2], double spacing, double aspect, ProjectionGeometry& g);

} // namespace mcx

#endif
