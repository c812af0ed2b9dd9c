// The render's view from the command line: --camera P:F:U:KIND for any
// camera, or --view AXIS for a parallel view along a world axis.
#ifndef mcxCameraSpec_h
#define mcxCameraSpec_h

#include "vtkSmartPointer.h"

#include <string>

class vtkCamera;

namespace mcxapp
{

/// The camera of "P:F:U:parallel=S" or "P:F:U:angle=A[:near=D]"; fails on
/// a malformed or degenerate one.
vtkSmartPointer<vtkCamera> ParseCamera(const std::string& text);

/// The detector axes of a parallel view along axis (+x, -x, +y, -y, +z or
/// -z): the two remaining world axes in x, y, z order, never mirrored.
void AxisViewDetector(const std::string& axis, double detectorU[3], double detectorV[3]);

} // namespace mcxapp

#endif
