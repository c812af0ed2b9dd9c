#include "mcxRadiographSettings.h"

#include "mcxFail.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkMCXRadiograph.h"
#include "vtkMCXRadiographGeometry.h"
#include "vtkMCXXRayMapper.h"
#include "vtkNew.h"

#include <string>

namespace mcxapp
{

vtkSmartPointer<vtkCamera> RadiographSettings::MakeCamera(
  vtkImageData* volume, int size[2], double& spacing) const
{
  vtkNew<vtkMCXRadiographGeometry> radiograph;
  radiograph->SetSourceToAxisDistance(this->SourceToAxis);
  radiograph->SetSourceToImageDistance(this->SourceToImage);
  radiograph->SetDetectorPixels(this->Detector[0], this->Detector[1]);
  radiograph->SetPixelPitch(this->Pitch);
  radiograph->SetGantryAngle(this->Gantry);
  double bounds[6];
  volume->GetBounds(bounds);
  const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  radiograph->SetIsocenter(this->HasIsocenter ? this->Isocenter : centre);
  auto camera = vtkSmartPointer<vtkCamera>::New();
  if (!radiograph->ConfigureCamera(camera)) // the geometry's error says why
  {
    Fail("bad radiograph geometry");
  }
  size[0] = this->Detector[0];
  size[1] = this->Detector[1];
  spacing = radiograph->GetPixelSpacingAtIsocenter();
  return camera;
}

// vtkMCXRadiograph and the mapper share the five physics properties.
template <typename Physics>
void RadiographSettings::Configure(Physics* physics) const
{
  physics->SetBeerLambert(this->BeerLambert);
  physics->SetIncidentIntensity(this->IncidentIntensity);
  physics->SetPhotonsPerPixel(this->Photons);
  physics->SetNoiseSeed(this->NoiseSeed);
  physics->SetNegativeLog(this->NegativeLog);
}
template void RadiographSettings::Configure(vtkMCXRadiograph*) const;
template void RadiographSettings::Configure(vtkMCXXRayMapper*) const;

} // namespace mcxapp
