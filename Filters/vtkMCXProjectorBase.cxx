#include "vtkMCXProjectorBase.h"

#include "mcxIndexView.h"
#include "mcxProjectionGeometry.h"
#include "mcxSampleGenerator.h"
#include "vtkMCXPointSampler.h"

#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <cmath>

struct vtkMCXProjectorBase::vtkInternals
{
  mcx::ProjectionGeometry Geometry;
};

vtkCxxSetObjectMacro(vtkMCXProjectorBase, Camera, vtkCamera);
vtkCxxSetObjectMacro(vtkMCXProjectorBase, TransferFunction, vtkPiecewiseFunction);

namespace
{
// The view of a camera: axes, eye, and field of view. Returns why it fails, or "".
std::string GeometryFromCamera(vtkCamera* camera, const int size[2], double spacing,
  mcx::ProjectionGeometry& g)
{
  double position[3], focal[3], up[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  camera->GetViewUp(up);
  double w[3] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] };
  const double distance = vtkMath::Normalize(w);
  if (!(distance > 0) || !std::isfinite(distance))
  {
    return "the camera's position and focal point coincide";
  }
  const double along = vtkMath::Dot(up, w);
  double v[3] = { up[0] - along * w[0], up[1] - along * w[1], up[2] - along * w[2] };
  if (!(vtkMath::Normalize(v) > 1e-12))
  {
    return "the camera's view-up is parallel to its direction of projection";
  }
  double u[3];
  vtkMath::Cross(w, v, u); // screen right = direction of projection x view-up
  vtkMath::Normalize(u);
  for (int a = 0; a < 3; ++a)
  {
    g.U[a] = u[a];
    g.V[a] = v[a];
    g.W[a] = w[a];
    g.Eye[a] = position[a];
  }
  g.Size[0] = size[0] > 0 ? size[0] : 512;
  g.Size[1] = size[1] > 0 ? size[1] : 512;
  g.Perspective = !camera->GetParallelProjection();
  const int across = camera->GetUseHorizontalViewAngle() ? g.Size[0] : g.Size[1];
  double centre[2] = { 0.0, 0.0 };
  if (g.Perspective)
  {
    g.FocalDistance = distance;
    g.NearDistance = camera->GetClippingRange()[0];
    if (!(spacing > 0))
    {
      spacing = 2.0 * distance * std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2.0) / across;
    }
  }
  else
  {
    centre[0] = vtkMath::Dot(focal, u);
    centre[1] = vtkMath::Dot(focal, v);
    if (!(spacing > 0))
    {
      spacing = 2.0 * camera->GetParallelScale() / g.Size[1];
    }
  }
  for (int k = 0; k < 2; ++k)
  {
    g.Spacing[k] = spacing;
    g.Origin[k] = centre[k] - 0.5 * (g.Size[k] - 1) * spacing;
  }
  return std::string();
}
}

vtkMCXProjectorBase::vtkMCXProjectorBase()
  : Internals(new vtkInternals)
{
}

vtkMCXProjectorBase::~vtkMCXProjectorBase()
{
  this->SetCamera(nullptr);
  this->SetTransferFunction(nullptr);
  delete this->Internals;
}

const mcx::ProjectionGeometry& vtkMCXProjectorBase::GetGeometry() const
{
  return this->Internals->Geometry;
}

vtkMTimeType vtkMCXProjectorBase::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->Camera)
  {
    t = std::max(t, this->Camera->GetMTime());
  }
  if (this->TransferFunction)
  {
    t = std::max(t, this->TransferFunction->GetMTime());
  }
  return t;
}

int vtkMCXProjectorBase::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  mcx::ProjectionGeometry g;
  std::string problem;
  if (this->Camera)
  {
    problem = GeometryFromCamera(this->Camera, this->ImageSize, this->PixelSpacing, g);
  }
  else
  {
    double corners[24];
    bool framed = false;
    if (inInfo->Has(vtkMCXPointSampler::SUPPORT_CORNERS()))
    {
      inInfo->Get(vtkMCXPointSampler::SUPPORT_CORNERS(), corners);
      framed = true;
    }
    else
    {
      framed = mcx::SupportCornersFromInformation(
        inInfo, mcx::KernelRadius(static_cast<mcx::Kernel>(this->Kernel)), corners);
    }
    for (int a = 0; a < 3; ++a)
    {
      g.U[a] = this->DetectorAxisU[a];
      g.V[a] = this->DetectorAxisV[a];
    }
    vtkMath::Cross(g.U, g.V, g.W);
    const bool explicitImage = this->ImageSize[0] > 0 && this->ImageSize[1] > 0 && this->PixelSpacing > 0;
    if (!framed && !explicitImage)
    {
      problem = "the input carries no volume extent to frame the image; set ImageSize and "
                "PixelSpacing, or a camera";
    }
    else if (framed &&
      !mcx::FrameCorners(g, corners, this->ImageSize, this->PixelSpacing, this->DefaultImageSize))
    {
      problem = "the volume cannot be framed in this view";
    }
    else if (!framed)
    {
      for (int k = 0; k < 2; ++k)
      {
        g.Size[k] = this->ImageSize[k];
        g.Spacing[k] = this->PixelSpacing;
      }
    }
    if (problem.empty() && (!framed || !this->CenterOnVolume))
    {
      for (int k = 0; k < 2; ++k)
      {
        g.Origin[k] = this->DetectorCenter[k] - 0.5 * (g.Size[k] - 1) * g.Spacing[k];
      }
    }
  }
  if (problem.empty())
  {
    problem = g.Validate();
  }
  if (!problem.empty())
  {
    vtkErrorMacro("Invalid projection: " << problem << ".");
    return 0;
  }
  this->Internals->Geometry = g;
  const int extent[6] = { 0, g.Size[0] - 1, 0, g.Size[1] - 1, 0, 0 };
  const double origin[3] = { g.Origin[0], g.Origin[1], 0.0 };
  const double spacing[3] = { g.Spacing[0], g.Spacing[1], 1.0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_DOUBLE, 1);
  return 1;
}

int vtkMCXProjectorBase::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
  return 1;
}

vtkDoubleArray* vtkMCXProjectorBase::AllocateLineIntegral(vtkImageData* output)
{
  const mcx::ProjectionGeometry& g = this->Internals->Geometry;
  output->SetExtent(0, g.Size[0] - 1, 0, g.Size[1] - 1, 0, 0);
  output->SetOrigin(g.Origin[0], g.Origin[1], 0.0);
  output->SetSpacing(g.Spacing[0], g.Spacing[1], 1.0);
  vtkNew<vtkDoubleArray> values;
  values->SetName(LineIntegralName());
  values->SetNumberOfValues(static_cast<vtkIdType>(g.Size[0]) * g.Size[1]);
  values->FillValue(0.0);
  output->GetPointData()->Initialize();
  output->GetPointData()->SetScalars(values);
  return values;
}

void vtkMCXProjectorBase::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "DetectorAxisU: " << this->DetectorAxisU[0] << " " << this->DetectorAxisU[1]
     << " " << this->DetectorAxisU[2] << "\n";
  os << indent << "DetectorAxisV: " << this->DetectorAxisV[0] << " " << this->DetectorAxisV[1]
     << " " << this->DetectorAxisV[2] << "\n";
  os << indent << "DetectorCenter: " << this->DetectorCenter[0] << " " << this->DetectorCenter[1] << "\n";
  os << indent << "CenterOnVolume: " << this->CenterOnVolume << "\n";
  os << indent << "ImageSize: " << this->ImageSize[0] << " " << this->ImageSize[1] << "\n";
  os << indent << "PixelSpacing: " << this->PixelSpacing << "\n";
  os << indent << "DefaultImageSize: " << this->DefaultImageSize << "\n";
  os << indent << "TransferFunction: " << this->TransferFunction << "\n";
  os << indent << "Kernel: " << this->Kernel << "\n";
}
