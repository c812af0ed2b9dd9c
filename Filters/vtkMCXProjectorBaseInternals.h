// What vtkMCXProjectorBase shares with its subclasses beyond its public
// interface: the detector geometry in the core's terms.
#ifndef vtkMCXProjectorBaseInternals_h
#define vtkMCXProjectorBaseInternals_h

#include "vtkMCXProjectorBase.h"

#include "mcxProjectionGeometry.h"

struct vtkMCXProjectorBase::vtkInternals
{
  mcx::ProjectionGeometry Geometry;
  // Along the view direction, where the detector plane lies in world space
  // (PlaceOnDetectorPlane): W . x for the plane's points.
  double PlaneDepth = 0.0;
};

#endif
