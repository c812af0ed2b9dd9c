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

vtkSmartPointer<vtkCamera> RadiographSettings::MakeCamera(vtkImageData* volume, int size[2], double& spacing) const
{
  vtkNew<vtkMCXRadiographGeometry> radiograph;
  radiograph->SetSourceToAxisDistance(this->SourceToAxis);
  radiograph->SetSourceToImageDistance(this->SourceToImage);
  radiograph->SetDetectorPixels(this->Detector[0], this->Detector[1]);
  radiograph->SetPixelPitch(this->Pitch);
  radiograph->SetGantryAngle(this->Gantry);
  double bounds[6];
  volume->GetBounds(bounds);
  const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2 };
  radiograph->SetIsocenter(this->HasIsocenter ? this->Isocenter : centre);
  const std::string problem = radiograph->Validate();
  if (!problem.empty())
  {
    Fail("bad radiograph geometry: " + problem);
  }
  auto camera = vtkSmartPointer<vtkCamera>::New();
  radiograph->ConfigureCamera(camera);
  size[0] = this->Detector[0];
  size[1] = this->Detector[1];
  spacing = radiograph->GetPixelSpacingAtIsocenter();
  return camera;
}

void RadiographSettings::Configure(vtkMCXRadiograph* radiograph) const
{
  radiograph->SetBeerLambert(this->BeerLambert);
  radiograph->SetIncidentIntensity(this->IncidentIntensity);
  radiograph->SetPhotonsPerPixel(this->Photons);
  radiograph->SetSeed(this->NoiseSeed);
  radiograph->SetNegativeLog(this->NegativeLog);
}

void RadiographSettings::Configure(vtkMCXXRayMapper* mapper) const
{
  mapper->SetBeerLambert(this->BeerLambert);
  mapper->SetIncidentIntensity(this->IncidentIntensity);
  mapper->SetPhotonsPerPixel(this->Photons);
  mapper->SetNoiseSeed(this->NoiseSeed);
  mapper->SetNegativeLog(this->NegativeLog);
}

} // namespace mcxapp
