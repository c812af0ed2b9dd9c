// What vtkMCXProjectorBase shares with its subclasses beyond its public
// interface: the detector geometry in the core's terms.
#ifndef vtkMCXProjectorBaseInternals_h
#define vtkMCXProjectorBaseInternals_h

#include "vtkMCXProjectorBase.h"

#include "mcxProjectionGeometry.h"

struct vtkMCXProjectorBase::vtkInternals
{
  mcx::ProjectionGeometry Geometry;
};

#endif
