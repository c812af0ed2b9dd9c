#include "vtkMCXRadiographGeometry.h"

#include "mcxPlastimatchView.h"
#include "mcxProjectionMatrix.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkMCXRadiographGeometry);

namespace
{
// The core's view of the properties.
mcx::PlastimatchView ViewOf(vtkMCXRadiographGeometry* self)
{
  mcx::PlastimatchView view;
  view.SourceToAxis = self->GetSourceToAxisDistance();
  view.SourceToImage = self->GetSourceToImageDistance();
  self->GetIsocenter(view.Isocenter);
  view.GantryDegrees = self->GetGantryAngle();
  view.HasNormal = self->GetUseDetectorNormal();
  self->GetDetectorNormal(view.Normal);
  self->GetViewUp(view.Up);
  self->GetDetectorPixels(view.Pixels);
  for (int k = 0; k < 2; ++k)
  {
    view.DetectorSize[k] = view.Pixels[k] * self->GetPixelPitch()[k];
  }
  view.HasImageCenter = self->GetUseImageCenter();
  self->GetImageCenter(view.ImageCenter);
  return view;
}
}

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
  mcx::PinholeCamera camera;
  const std::string problem = ViewOf(this).Camera(camera);
  if (!problem.empty())
  {
    vtkErrorMacro("Invalid radiograph geometry: " << problem << ".");
    return false;
  }
  return true;
}

bool vtkMCXRadiographGeometry::GetProjectionMatrix(double matrix[12])
{
  mcx::PinholeCamera camera;
  const std::string problem = ViewOf(this).Camera(camera);
  if (!problem.empty())
  {
    vtkErrorMacro("Invalid radiograph geometry: " << problem << ".");
    return false;
  }
  mcx::MatrixFromPinhole(camera, matrix);
  return true;
}

bool vtkMCXRadiographGeometry::ConfigureCamera(vtkCamera* camera)
{
  if (!camera)
  {
    vtkErrorMacro("ConfigureCamera needs a vtkCamera, not null.");
    return false;
  }
  mcx::PinholeCamera view;
  const std::string problem = ViewOf(this).Camera(view);
  if (!problem.empty())
  {
    vtkErrorMacro("Invalid radiograph geometry: " << problem << ".");
    return false;
  }
  if (this->PixelPitch[0] != this->PixelPitch[1] || this->UseImageCenter)
  {
    vtkErrorMacro("A vtkCamera holds square pixels centred on the isocentre's ray only; use "
                  "GetProjectionMatrix with a projector for this geometry.");
    return false;
  }
  double source[3];
  view.Source(source);
  const double sad = this->SourceToAxisDistance;
  camera->SetParallelProjection(false);
  camera->SetUseHorizontalViewAngle(false);
  camera->SetPosition(source);
  camera->SetFocalPoint(this->Isocenter);
  // The camera's y axis points down the detector: view-up is its opposite.
  camera->SetViewUp(-view.R[3], -view.R[4], -view.R[5]);
  const double height = this->DetectorPixels[1] * this->PixelPitch[1];
  camera->SetViewAngle(
    2.0 * vtkMath::DegreesFromRadians(std::atan(0.5 * height / this->SourceToImageDistance)));
  // Integrate from just in front of the source: nothing a radiograph sees is nearer.
  camera->SetClippingRange(1e-3 * sad, 10.0 * std::max(sad, this->SourceToImageDistance));
  return true;
}

double vtkMCXRadiographGeometry::GetPixelSpacingAtIsocenter() const
{
  return this->PixelPitch[0] * this->SourceToAxisDistance / this->SourceToImageDistance;
}

void vtkMCXRadiographGeometry::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SourceToAxisDistance: " << this->SourceToAxisDistance << "\n";
  os << indent << "SourceToImageDistance: " << this->SourceToImageDistance << "\n";
  os << indent << "DetectorPixels: " << this->DetectorPixels[0] << " " << this->DetectorPixels[1]
     << "\n";
  os << indent << "PixelPitch: " << this->PixelPitch[0] << " " << this->PixelPitch[1] << "\n";
  os << indent << "GantryAngle: " << this->GantryAngle << "\n";
  os << indent << "DetectorNormal: " << this->DetectorNormal[0] << " " << this->DetectorNormal[1]
     << " " << this->DetectorNormal[2] << "\n";
  os << indent << "UseDetectorNormal: " << this->UseDetectorNormal << "\n";
  os << indent << "ViewUp: " << this->ViewUp[0] << " " << this->ViewUp[1] << " " << this->ViewUp[2]
     << "\n";
  os << indent << "ImageCenter: " << this->ImageCenter[0] << " " << this->ImageCenter[1] << "\n";
  os << indent << "UseImageCenter: " << this->UseImageCenter << "\n";
  os << indent << "Isocenter: " << this->Isocenter[0] << " " << this->Isocenter[1] << " "
     << this->Isocenter[2] << "\n";
}
