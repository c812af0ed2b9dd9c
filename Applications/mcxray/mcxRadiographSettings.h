// The radiograph options that render and view share: a cone-beam geometry
// as radiographers give it, and the physics applied after accumulation.
// Each is off unless asked for.
#ifndef mcxRadiographSettings_h
#define mcxRadiographSettings_h

#include "vtkSmartPointer.h"

class vtkCamera;
class vtkImageData;
class vtkMCXRadiograph;
class vtkMCXXRayMapper;

namespace mcxapp
{

struct RadiographSettings
{
  bool Geometry = false; // any of --sad, --sid, --detector, --pitch, --gantry, --isocenter
  double SourceToAxis = 1000.0;
  double SourceToImage = 1500.0;
  int Detector[2] = { 512, 512 };
  double Pitch = 0.8;
  double Gantry = 0.0;
  bool HasIsocenter = false;
  double Isocenter[3] = { 0, 0, 0 };
  bool BeerLambert = false;
  double IncidentIntensity = 1.0;
  double Photons = 0.0;
  long long NoiseSeed = 0;
  bool NegativeLog = false;

  /// The camera of the radiograph geometry (isocentre: the volume's centre
  /// unless given); sets the image size and the pixel spacing to the
  /// detector's. Fails on an impossible geometry.
  vtkSmartPointer<vtkCamera> MakeCamera(vtkImageData* volume, int size[2], double& spacing) const;

  /// Gives the physics to the off-line filter (vtkMCXRadiograph), or to the
  /// on-screen mapper (vtkMCXXRayMapper): the same five properties.
  template <typename Physics>
  void Configure(Physics* physics) const;
};

} // namespace mcxapp

#endif
