#include "vtkMCXRadiographGeometry.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"

#include <cmath>

vtkStandardNewMacro(vtkMCXRadiographGeometry);

std::string vtkMCXRadiographGeometry::Validate() const
{
  const double sad = this->SourceToAxisDistance, sid = this->SourceToImageDistance;
  if (!(sad > 0) || !std::isfinite(sad))
  {
    return "the source-to-axis distance must be positive and finite";
  }
  if (!(sid > 0) || !std::isfinite(sid))
  {
    return "the source-to-image distance must be positive and finite";
  }
  if (this->DetectorPixels[0] < 1 || this->DetectorPixels[1] < 1)
  {
    return "the detector needs at least 1 x 1 pixels";
  }
  if (!(this->PixelPitch > 0) || !std::isfinite(this->PixelPitch))
  {
    return "the pixel pitch must be positive and finite";
  }
  if (!std::isfinite(this->GantryAngle) || !std::isfinite(this->Isocenter[0]) ||
    !std::isfinite(this->Isocenter[1]) || !std::isfinite(this->Isocenter[2]))
  {
    return "the gantry angle and the isocentre must be finite";
  }
  return std::string();
}

void vtkMCXRadiographGeometry::ConfigureCamera(vtkCamera* camera) const
{
  const double angle = vtkMath::RadiansFromDegrees(this->GantryAngle);
  const double sad = this->SourceToAxisDistance;
  const double* iso = this->Isocenter;
  camera->SetParallelProjection(false);
  camera->SetUseHorizontalViewAngle(false);
  camera->SetFocalPoint(iso[0], iso[1], iso[2]);
  camera->SetPosition(iso[0] + sad * std::cos(angle), iso[1] + sad * std::sin(angle), iso[2]);
  camera->SetViewUp(0, 0, 1);
  const double height = this->DetectorPixels[1] * this->PixelPitch;
  camera->SetViewAngle(2.0 * vtkMath::DegreesFromRadians(std::atan(0.5 * height / this->SourceToImageDistance)));
  // Integrate from just in front of the source: nothing a radiograph sees is nearer.
  camera->SetClippingRange(1e-3 * sad, 10.0 * std::max(sad, this->SourceToImageDistance));
}

double vtkMCXRadiographGeometry::GetPixelSpacingAtIsocenter() const
{
  return this->PixelPitch * this->SourceToAxisDistance / this->SourceToImageDistance;
}

void vtkMCXRadiographGeometry::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SourceToAxisDistance: " << this->SourceToAxisDistance << "\n";
  os << indent << "SourceToImageDistance: " << this->SourceToImageDistance << "\n";
  os << indent << "DetectorPixels: " << this->DetectorPixels[0] << " " << this->DetectorPixels[1] << "\n";
  os << indent << "PixelPitch: " << this->PixelPitch << "\n";
  os << indent << "GantryAngle: " << this->GantryAngle << "\n";
  os << indent << "Isocenter: " << this->Isocenter[0] << " " << this->Isocenter[1] << " " << this->Isocenter[2] << "\n";
}
