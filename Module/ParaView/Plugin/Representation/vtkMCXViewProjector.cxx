#include "vtkMCXViewProjector.h"

#include "mcxAutomaticWindow.h"
#include "vtkMCXAttenuationModePrivate.h"
#include "vtkMCXCostPrivate.h"
#include "vtkMCXDistributed.h"

#include "vtkCamera.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"

#include <algorithm>

#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMCXViewProjector);

namespace
{
// vtkMCXXRayMapper's automatic window (mcxAutomaticWindow.h), for the image
// as a whole; false for an empty image.
bool AutomaticWindow(vtkDataArray* values, const int dimensions[3], double& window)
{
  return mcx::AutomaticWindow([values](std::size_t p)
    { return values->GetComponent(static_cast<vtkIdType>(p), 0); },
    dimensions[0], dimensions[1], window);
}

// Sets an int[2] for a scope and puts the old values back (the superclass
// reads ImageSize; the filter is not modified by a run).
class ScopedSize
{
public:
  ScopedSize(int* target, const int* value)
    : Target(target)
    , Old{ target[0], target[1] }
  {
    target[0] = value[0];
    target[1] = value[1];
  }
  ~ScopedSize()
  {
    this->Target[0] = this->Old[0];
    this->Target[1] = this->Old[1];
  }
  ScopedSize(const ScopedSize&) = delete;
  ScopedSize& operator=(const ScopedSize&) = delete;

private:
  int* Target;
  int Old[2];
};
}

vtkMCXViewProjector::vtkMCXViewProjector() = default;

vtkMCXViewProjector::~vtkMCXViewProjector()
{
  this->SetCamera(nullptr);
}

void vtkMCXViewProjector::SetViewCameraInUse(bool use)
{
  if (this->ViewCameraInUse != use)
  {
    this->ViewCameraInUse = use;
    this->SetCamera(use ? this->ViewCamera.GetPointer() : nullptr);
    this->Modified();
  }
}

// The camera's own setters mark it modified, and the projector's MTime
// includes its camera's (vtkMCXProjectorBase::GetMTime).
void vtkMCXViewProjector::SetViewCameraPosition(double x, double y, double z)
{
  this->ViewCamera->SetPosition(x, y, z);
}

void vtkMCXViewProjector::SetViewCameraFocalPoint(double x, double y, double z)
{
  this->ViewCamera->SetFocalPoint(x, y, z);
}

void vtkMCXViewProjector::SetViewCameraViewUp(double x, double y, double z)
{
  this->ViewCamera->SetViewUp(x, y, z);
}

void vtkMCXViewProjector::SetViewCameraViewAngle(double degrees)
{
  this->ViewCamera->SetViewAngle(degrees);
}

void vtkMCXViewProjector::SetViewCameraParallelScale(double scale)
{
  this->ViewCamera->SetParallelScale(scale);
}

void vtkMCXViewProjector::SetViewCameraParallelProjection(bool parallel)
{
  this->ViewCamera->SetParallelProjection(parallel);
}

bool vtkMCXViewProjector::ViewImageSize(int size[2]) const
{
  if (!this->ViewCameraInUse || !(this->ViewAspect > 0.0) || this->ImageSize[0] != 0 ||
    this->ImageSize[1] != 0)
  {
    return false;
  }
  // The longer side is the automatic size; the other keeps the view's aspect.
  const int longest = this->DefaultImageSize;
  const bool wide = this->ViewAspect >= 1.0;
  const double other = wide ? longest / this->ViewAspect : longest * this->ViewAspect;
  const int shorter = std::max(1, static_cast<int>(std::lround(other)));
  size[0] = wide ? longest : shorter;
  size[1] = wide ? shorter : longest;
  return true;
}

int vtkMCXViewProjector::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  int size[2];
  if (!this->ViewImageSize(size))
  {
    return this->Superclass::RequestInformation(request, inputVector, outputVector);
  }
  ScopedSize scoped(this->ImageSize, size);
  return this->Superclass::RequestInformation(request, inputVector, outputVector);
}

int vtkMCXViewProjector::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  int size[2] = { this->ImageSize[0], this->ImageSize[1] };
  this->ViewImageSize(size);
  ScopedSize scoped(this->ImageSize, size);
  // An index input projects 2^m - 1 samples, unless every voxel once or a
  // target chooses the count (from a pilot run, up to the maximum).
  if (vtkImageData::GetData(inputVector[0], 0) && this->GetStrategy() != vtkMCXTypes::EVERY_VOXEL)
  {
    const bool targeted =
      this->GetTargetRelativeError() > 0.0 || this->GetTargetQuantizationLevels() > 0;
    const int exponent = targeted ? this->GetMaximumSampleExponent() : this->GetSampleExponent();
    const std::string cost = mcx::ProjectionCost(std::ldexp(1.0, exponent) - 1.0);
    if (!cost.empty())
    {
      vtkWarningMacro("X-Ray Projector: " << cost << (targeted ? " at most" : "")
                                          << " before the image is shown.");
    }
  }
  // HU to mu: the index is projected under mu(HU) x the TF for this run
  // only (the member is swapped back, not set: the TF and this filter stay
  // unmodified).
  double range[2];
  bool known = this->Attenuation == HU_TO_MU &&
    mcx::IndexDensityRange(vtkImageData::GetData(inputVector[0], 0), range);
  vtkMultiProcessController* controller = this->GetController();
  if (this->Attenuation == HU_TO_MU && mcx::IsDistributed(controller))
  {
    // Each process holds its slab's index: the whole volume's densities
    // decide where air is, the same on every process.
    const double local[2] = { known ? range[0] : VTK_DOUBLE_MAX,
      known ? -range[1] : VTK_DOUBLE_MAX };
    double whole[2];
    controller->AllReduce(local, whole, 2, vtkCommunicator::MIN_OP);
    known = whole[0] <= -whole[1];
    range[0] = whole[0];
    range[1] = -whole[1];
  }
  vtkSmartPointer<vtkPiecewiseFunction> attenuation;
  if (known)
  {
    attenuation = mcx::WeightedAttenuation(this->TransferFunction, this->WaterAttenuation, range);
  }
  vtkPiecewiseFunction* weight = this->TransferFunction;
  if (attenuation)
  {
    this->TransferFunction = attenuation;
  }
  const int projected = this->Superclass::RequestData(request, inputVector, outputVector);
  this->TransferFunction = weight;
  if (!projected)
  {
    return 0;
  }
  vtkImageData* image = vtkImageData::GetData(outputVector, 0);
  vtkDataArray* values =
    image ? image->GetPointData()->GetArray(vtkMCXTypes::LineIntegralName()) : nullptr;
  double window = 0.0;
  if (values && AutomaticWindow(values, image->GetDimensions(), window))
  {
    vtkNew<vtkDoubleArray> automatic;
    automatic->SetName(AutomaticWindowName());
    automatic->InsertNextValue(window);
    image->GetFieldData()->AddArray(automatic);
  }
  return 1;
}

void vtkMCXViewProjector::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ViewCameraInUse: " << this->ViewCameraInUse << "\n";
  os << indent << "ViewAspect: " << this->ViewAspect << "\n";
  os << indent << "Attenuation: " << this->Attenuation << "\n";
  os << indent << "WaterAttenuation: " << this->WaterAttenuation << "\n";
  os << indent << "ViewCamera:\n";
  this->ViewCamera->PrintSelf(os, indent.GetNextIndent());
}
