// What vtkMCXProjectorBase shares with its subclasses beyond its public
// interface: the detector geometry in the core's terms.
#ifndef vtkMCXProjectorBaseInternals_h
#define vtkMCXProjectorBaseInternals_h

#include "vtkMCXProjectorBase.h"

#include "mcxProjectionGeometry.h"

#include <string>

struct vtkMCXProjectorBase::vtkInternals
{
  mcx::ProjectionGeometry Geometry;
  // Along the view direction, where the detector plane lies in world space
  // (PlaceOnDetectorPlane): W . x for the plane's points.
  double PlaneDepth = 0.0;
  // The volume's support corners that framed Geometry, when it was framed
  // on them (FrameOnInputData compares the data's with them).
  bool Framed = false;
  double Corners[24] = { 0 };
  // Whether the last RequestInformation could make no image: RequestData,
  // which the pipeline may still run, then makes none either, without
  // saying why twice (FrameOnInputData).
  bool InformationFailed = false;

  /// The geometry of the projector's settings, framed on the support's 8
  /// corners (null: none known), and the detector plane's depth; returns why
  /// no image can be made, or "".
  static std::string ComputeGeometry(const vtkMCXProjectorBase& self, const double* corners,
    mcx::ProjectionGeometry& geometry, double& depth);
};

#endif
