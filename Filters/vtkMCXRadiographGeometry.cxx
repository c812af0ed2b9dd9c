#include "vtkMCXRadiographGeometry.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkMCXRadiographGeometry);

void vtkMCXRadiographGeometry::SetDetectorPixels(int columns, int rows)
{
  columns = std::min(std::max(columns, 1), MaximumDetectorPixels);
  rows = std::min(std::max(rows, 1), MaximumDetectorPixels);
  if (columns != this->DetectorPixels[0] || rows != this->DetectorPixels[1])
  {
    this->DetectorPixels[0] = columns;
    this->DetectorPixels[1] = rows;
    this->Modified();
  }
}

bool vtkMCXRadiographGeometry::IsValid()
{
  const double sad = this->SourceToAxisDistance, sid = this->SourceToImageDistance;
  const char* problem = nullptr;
  if (!(sad > 0) || !std::isfinite(sad))
  {
    problem = "the source-to-axis distance must be positive and finite";
  }
  else if (!(sid > 0) || !std::isfinite(sid))
  {
    problem = "the source-to-image distance must be positive and finite";
  }
  else if (!(this->PixelPitch > 0) || !std::isfinite(this->PixelPitch))
  {
    problem = "the pixel pitch must be positive and finite";
  }
  else if (!std::isfinite(this->GantryAngle) || !std::isfinite(this->Isocenter[0]) ||
    !std::isfinite(this->Isocenter[1]) || !std::isfinite(this->Isocenter[2]))
  {
    problem = "the gantry angle and the isocentre must be finite";
  }
  if (problem)
  {
    vtkErrorMacro("Invalid radiograph geometry: " << problem << ".");
    return false;
  }
  return true;
}

bool vtkMCXRadiographGeometry::ConfigureCamera(vtkCamera* camera)
{
  if (!camera)
  {
    vtkErrorMacro("ConfigureCamera needs a vtkCamera, not null.");
    return false;
  }
  if (!this->IsValid())
  {
    return false;
  }
  const double angle = vtkMath::RadiansFromDegrees(this->GantryAngle);
  const double sad = this->SourceToAxisDistance;
  const double* iso = this->Isocenter;
  camera->SetParallelProjection(false);
  camera->SetUseHorizontalViewAngle(false);
  camera->SetFocalPoint(iso[0], iso[1], iso[2]);
  camera->SetPosition(iso[0] + sad * std::cos(angle), iso[1] + sad * std::sin(angle), iso[2]);
  camera->SetViewUp(0, 0, 1);
  const double height = this->DetectorPixels[1] * this->PixelPitch;
  camera->SetViewAngle(
    2.0 * vtkMath::DegreesFromRadians(std::atan(0.5 * height / this->SourceToImageDistance)));
  // Integrate from just in front of the source: nothing a radiograph sees is nearer.
  camera->SetClippingRange(1e-3 * sad, 10.0 * std::max(sad, this->SourceToImageDistance));
  return true;
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
  os << indent << "DetectorPixels: " << this->DetectorPixels[0] << " " << this->DetectorPixels[1]
     << "\n";
  os << indent << "PixelPitch: " << this->PixelPitch << "\n";
  os << indent << "GantryAngle: " << this->GantryAngle << "\n";
  os << indent << "Isocenter: " << this->Isocenter[0] << " " << this->Isocenter[1] << " "
     << this->Isocenter[2] << "\n";
}
