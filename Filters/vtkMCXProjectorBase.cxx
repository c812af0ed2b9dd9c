#include "vtkMCXProjectorBase.h"

#include "mcxProjectionGeometry.h"
#include "mcxProjectionMatrix.h"
#include "mcxSampleGenerator.h"
#include "vtkMCXCameraGeometry.h"
#include "vtkMCXCloudDeposit.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXMemoryCheck.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjectorBaseInternals.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkCxxSetObjectMacro(vtkMCXProjectorBase, Camera, vtkCamera);
vtkCxxSetObjectMacro(vtkMCXProjectorBase, TransferFunction, vtkPiecewiseFunction);

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

namespace
{
// The corners of the volume's support as the pipeline information tells
// them (a cloud's SUPPORT_CORNERS, else an image's extent and placement).
bool InformationCorners(vtkInformation* inInfo, double kernelRadius, double corners[24])
{
  if (inInfo->Has(vtkMCXPointSampler::SUPPORT_CORNERS()))
  {
    inInfo->Get(vtkMCXPointSampler::SUPPORT_CORNERS(), corners);
    return true;
  }
  return mcx::SupportCornersFromInformation(inInfo, kernelRadius, corners);
}

// The same corners as the input data tell them: an image's whole extent
// (a process's piece is part of it) with the data's own origin, spacing and
// direction, or a cloud's SupportCorners field.
bool DataCorners(
  vtkDataObject* input, vtkInformation* inInfo, double kernelRadius, double corners[24])
{
  if (auto* image = vtkImageData::SafeDownCast(input))
  {
    int extent[6];
    image->GetExtent(extent);
    if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    {
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
    }
    if (extent[1] < extent[0] || extent[3] < extent[2] || extent[5] < extent[4])
    {
      return false;
    }
    mcx::ComputeSupportCorners(extent, image->GetOrigin(), image->GetSpacing(),
      image->GetDirectionMatrix()->GetData(), kernelRadius, corners);
    return true;
  }
  return mcx::CloudSupportCorners(input, corners);
}
}

namespace
{
// The view of the projection matrix, its pixels measured on the plane at
// FocalPlaneDistance, else through the support's centre, else where pixels
// are one world unit wide.
std::string GeometryFromMatrix(
  const vtkMCXProjectorBase& self, const double* corners, mcx::ProjectionGeometry& g)
{
  const int* size = const_cast<vtkMCXProjectorBase&>(self).GetImageSize();
  if (size[0] < 1 || size[1] < 1)
  {
    return "a projection matrix needs ImageSize (columns and rows of its detector)";
  }
  double P[12];
  self.GetProjectionMatrix(P);
  if (mcx::IsAffineMatrix(P))
  {
    return mcx::GeometryFromAffineMatrix(P, size, g); // a parallel view: no focal plane
  }
  mcx::PinholeCamera camera;
  std::string problem = mcx::PinholeFromMatrix(P, camera);
  if (!problem.empty())
  {
    return problem;
  }
  double distance = const_cast<vtkMCXProjectorBase&>(self).GetFocalPlaneDistance();
  if (!(distance > 0) && corners)
  {
    double source[3], centre[3] = { 0, 0, 0 };
    camera.Source(source);
    for (int c = 0; c < 8; ++c)
    {
      for (int a = 0; a < 3; ++a)
      {
        centre[a] += corners[3 * c + a] / 8.0;
      }
    }
    distance = camera.R[6] * (centre[0] - source[0]) + camera.R[7] * (centre[1] - source[1]) +
      camera.R[8] * (centre[2] - source[2]);
  }
  if (!(distance > 0))
  {
    distance = camera.Fx;
  }
  return mcx::GeometryFromPinhole(camera, size, distance, g);
}
}

void vtkMCXProjectorBase::SetProjectionMatrix(const double matrix[12])
{
  if (!std::equal(matrix, matrix + 12, this->ProjectionMatrix))
  {
    std::copy(matrix, matrix + 12, this->ProjectionMatrix);
    this->Modified();
  }
}

void vtkMCXProjectorBase::GetProjectionMatrix(double matrix[12]) const
{
  std::copy(this->ProjectionMatrix, this->ProjectionMatrix + 12, matrix);
}

std::string vtkMCXProjectorBase::vtkInternals::ComputeGeometry(
  const vtkMCXProjectorBase& self, const double* corners, mcx::ProjectionGeometry& g, double& depth)
{
  std::string problem;
  const bool framed = corners != nullptr;
  // What the setters cannot clamp: a NaN spacing, a negative size.
  if (!std::isfinite(self.PixelSpacing))
  {
    return "PixelSpacing must be a finite number (0: automatic)";
  }
  if (self.ImageSize[0] < 0 || self.ImageSize[1] < 0)
  {
    return "ImageSize must be 0 (automatic) or positive, not " +
      std::to_string(self.ImageSize[0]) + " x " + std::to_string(self.ImageSize[1]);
  }
  if (self.UseProjectionMatrix)
  {
    problem = GeometryFromMatrix(self, corners, g);
  }
  else if (self.Camera)
  {
    problem = mcx::GeometryFromCamera(self.Camera, self.ImageSize, self.PixelSpacing, 0.0, g);
  }
  else
  {
    for (int a = 0; a < 3; ++a)
    {
      g.U[a] = self.DetectorAxisU[a];
      g.V[a] = self.DetectorAxisV[a];
    }
    vtkMath::Cross(g.U, g.V, g.W);
    const bool explicitImage =
      self.ImageSize[0] > 0 && self.ImageSize[1] > 0 && self.PixelSpacing > 0;
    if (!framed && !explicitImage)
    {
      problem = "the input carries no volume extent to frame the image; set ImageSize and "
                "PixelSpacing, or a camera";
    }
    else if (framed &&
      !mcx::FrameCorners(g, corners, self.ImageSize, self.PixelSpacing, self.DefaultImageSize))
    {
      problem = "the volume cannot be framed in this view";
    }
    else if (!framed)
    {
      for (int k = 0; k < 2; ++k)
      {
        g.Size[k] = self.ImageSize[k];
        g.Spacing[k] = self.PixelSpacing;
      }
    }
    if (problem.empty() && (!framed || !self.CenterOnVolume))
    {
      for (int k = 0; k < 2; ++k)
      {
        g.Origin[k] = self.DetectorCenter[k] - 0.5 * (g.Size[k] - 1) * g.Spacing[k];
      }
    }
  }
  if (problem.empty())
  {
    problem = g.Validate();
  }
  if (!problem.empty())
  {
    return "Invalid projection: " + problem;
  }
  // The detector plane's depth: the camera's focal plane, else the support's centre.
  depth = self.Camera && !self.UseProjectionMatrix ? vtkMath::Dot(self.Camera->GetFocalPoint(), g.W)
                                                   : 0.0;
  if ((!self.Camera || self.UseProjectionMatrix) && framed)
  {
    for (int c = 0; c < 8; ++c)
    {
      depth += vtkMath::Dot(corners + 3 * c, g.W) / 8.0;
    }
  }
  return mcx::MemoryProblem(
    static_cast<double>(g.Size[0]) * g.Size[1] * mcx::ProjectionBytesPerPixel(),
    "An image of " + std::to_string(g.Size[0]) + " x " + std::to_string(g.Size[1]) + " pixels");
}

int vtkMCXProjectorBase::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInternals& in = *this->Internals;
  in.Framed = InformationCorners(
    inInfo, mcx::KernelRadius(static_cast<mcx::Kernel>(this->Kernel)), in.Corners);
  mcx::ProjectionGeometry g;
  double depth = 0.0;
  const std::string failure = this->AgreeOnFailure(
    inInfo, vtkInternals::ComputeGeometry(*this, in.Framed ? in.Corners : nullptr, g, depth));
  // A failed request leaves no stale image of an earlier one behind.
  vtkImageData* output = vtkImageData::GetData(outputVector);
  in.InformationFailed = !failure.empty();
  if (!failure.empty())
  {
    vtkErrorMacro(<< failure << ".");
    output->Initialize();
    // Not the input's extent, which the pipeline copied here by default: an
    // update extent made from it would outlive the failure and be refused
    // once the image is valid again (a 3D extent for a 2D image).
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    return 0;
  }
  in.Geometry = g;
  in.PlaneDepth = depth;
  const int extent[6] = { 0, g.Size[0] - 1, 0, g.Size[1] - 1, 0, 0 };
  double origin[3], direction[9];
  this->OutputPlacement(origin, direction);
  const double spacing[3] = { g.Spacing[0], g.Spacing[1], 1.0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), direction, 9);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_DOUBLE, 1);
  return 1;
}

bool vtkMCXProjectorBase::FrameOnInputData(vtkDataObject* input, vtkInformation* inInfo)
{
  // A camera or a matrix frames the image itself. Without one the volume frames it, and
  // the information may not have told where the volume lies: ParaView's
  // input post filter and VTK 9.1's pass-through filters drop the
  // DIRECTION key (a NIfTI volume in LPS came out mostly off the image).
  vtkInternals& in = *this->Internals;
  if (in.InformationFailed)
  {
    return false; // RequestInformation said why; its geometry is not this request's
  }
  double corners[24];
  if (this->Camera || this->UseProjectionMatrix ||
    !DataCorners(
      input, inInfo, mcx::KernelRadius(static_cast<mcx::Kernel>(this->Kernel)), corners) ||
    (in.Framed && std::equal(corners, corners + 24, in.Corners)))
  {
    return true;
  }
  mcx::ProjectionGeometry g;
  double depth = 0.0;
  const std::string failure = vtkInternals::ComputeGeometry(*this, corners, g, depth);
  if (!failure.empty())
  {
    vtkErrorMacro(<< failure << ".");
    return false;
  }
  in.Framed = true;
  std::copy(corners, corners + 24, in.Corners);
  in.Geometry = g;
  in.PlaneDepth = depth;
  return true;
}

std::string vtkMCXProjectorBase::AgreeOnFailure(vtkInformation*, const std::string& failure)
{
  return failure;
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
  double origin[3], direction[9];
  this->OutputPlacement(origin, direction);
  output->SetOrigin(origin);
  output->SetDirectionMatrix(direction);
  output->SetSpacing(g.Spacing[0], g.Spacing[1], 1.0);
  vtkNew<vtkDoubleArray> values;
  values->SetName(vtkMCXTypes::LineIntegralName());
  values->SetNumberOfValues(static_cast<vtkIdType>(g.Size[0]) * g.Size[1]);
  values->FillValue(0.0);
  output->GetPointData()->Initialize();
  output->GetPointData()->SetScalars(values);
  vtkNew<vtkDoubleArray> matrix;
  matrix->SetName(vtkMCXTypes::ProjectionMatrixName());
  matrix->SetNumberOfComponents(12); // one tuple: the matrix, row-major
  matrix->SetNumberOfTuples(1);
  mcx::MatrixFromGeometry(g, matrix->GetPointer(0));
  // The field data start afresh here, with the matrix; the subclasses add to them.
  output->GetFieldData()->Initialize();
  output->GetFieldData()->AddArray(matrix);
  return values;
}

void vtkMCXProjectorBase::OutputPlacement(double origin[3], double direction[9]) const
{
  const mcx::ProjectionGeometry& g = this->Internals->Geometry;
  if (!this->PlaceOnDetectorPlane)
  {
    const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    std::copy(identity, identity + 9, direction);
    origin[0] = g.Origin[0];
    origin[1] = g.Origin[1];
    origin[2] = 0.0;
    return;
  }
  // Columns U, V and U x V (a rotation: +W or -W, the normal of the image's
  // front face); pixel (0, 0) where the plane coordinates Origin put it:
  // absolute along U and V for a parallel view (moved along the oblique rays
  // to the plane's depth), from the principal point on the focal plane for a
  // perspective one.
  double normal[3];
  vtkMath::Cross(g.U, g.V, normal);
  for (int r = 0; r < 3; ++r)
  {
    direction[3 * r] = g.U[r];
    direction[3 * r + 1] = g.V[r];
    direction[3 * r + 2] = normal[r];
    const double depth = this->Internals->PlaneDepth;
    const double onAxis = g.Perspective
      ? g.Eye[r] + g.FocalDistance * g.W[r]
      : depth * (g.W[r] + g.Obliquity[0] * g.U[r] + g.Obliquity[1] * g.V[r]);
    origin[r] = onAxis + g.Origin[0] * g.U[r] + g.Origin[1] * g.V[r];
  }
}

void vtkMCXProjectorBase::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "ProjectionMatrix:";
  for (double value : this->ProjectionMatrix)
  {
    os << " " << value;
  }
  os << "\n";
  os << indent << "UseProjectionMatrix: " << this->UseProjectionMatrix << "\n";
  os << indent << "FocalPlaneDistance: " << this->FocalPlaneDistance << "\n";
  os << indent << "PlaceOnDetectorPlane: " << this->PlaceOnDetectorPlane << "\n";
  os << indent << "DetectorAxisU: " << this->DetectorAxisU[0] << " " << this->DetectorAxisU[1]
     << " " << this->DetectorAxisU[2] << "\n";
  os << indent << "DetectorAxisV: " << this->DetectorAxisV[0] << " " << this->DetectorAxisV[1]
     << " " << this->DetectorAxisV[2] << "\n";
  os << indent << "DetectorCenter: " << this->DetectorCenter[0] << " " << this->DetectorCenter[1]
     << "\n";
  os << indent << "CenterOnVolume: " << this->CenterOnVolume << "\n";
  os << indent << "ImageSize: " << this->ImageSize[0] << " " << this->ImageSize[1] << "\n";
  os << indent << "PixelSpacing: " << this->PixelSpacing << "\n";
  os << indent << "DefaultImageSize: " << this->DefaultImageSize << "\n";
  os << indent << "TransferFunction: " << this->TransferFunction << "\n";
  os << indent << "Kernel: " << this->Kernel << "\n";
}
