// Compiled only by the Core.SeesNoVTK test, with the core's flags alone: it
// must fail, because no VTK header is within the core's reach.
#include "mcxFixedPoint.h"

#include "vtkObject.h"
