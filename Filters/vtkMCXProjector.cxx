// The filter: its settings, its pipeline requests, and the three stages of
// an image: the input's samples projected (the index input in
// vtkMCXIndexProjectionPrivate, the cloud input in
// vtkMCXCloudProjectionPrivate, both into a Projection of
// vtkMCXProjectionPrivate.h), then written out as line integrals.
#include "vtkMCXProjector.h"

#include "mcxSampleGenerator.h"
#include "vtkMCXCloudProjectionPrivate.h"
#include "vtkMCXDistributed.h"
#include "vtkMCXIndexProjectionPrivate.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXProjectionPrivate.h"
#include "vtkMCXProjectorBaseInternals.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <new>
#include <stdexcept>
#include <string>

vtkStandardNewMacro(vtkMCXProjector);
vtkCxxSetObjectMacro(vtkMCXProjector, Controller, vtkMultiProcessController);

namespace
{
using mcx::Projection;

// Stage 1: the input's samples, projected (false, reported, when there is
// no image to make).
bool ProjectInput(vtkMCXProjector* self, vtkDataObject* input, const int wholeExtent[6],
  const mcx::ProjectionGeometry& geometry, Projection& projection)
{
  if (auto* cloud = vtkPolyData::SafeDownCast(input))
  {
    return mcx::ProjectCloud(self, cloud, geometry, self->GetFootprintReach(), projection);
  }
  return mcx::ProjectIndex(
    self, vtkImageData::SafeDownCast(input), wholeExtent, geometry, projection);
}

// Stage 3: line integrals and the field data that tells how they were made.
void WriteImage(const Projection& projection, const mcx::ProjectionGeometry& geometry,
  vtkDoubleArray* values, vtkFieldData* fd)
{
  const std::size_t pixels = projection.Sums.size() / 2;
  if (projection.Control.empty())
  {
    mcx::FixedSumsToValues(projection.Sums.data(), pixels, projection.SampleWeight,
      geometry.BeamCrossSection(), values->GetPointer(0));
  }
  else
  {
    mcx::ControlledSumsToValues(projection.Controlled(), values->GetPointer(0));
  }
  mcx::AddFieldValue(
    fd, vtkMCXTypes::SampleCountName(), static_cast<long long>(projection.Count));
  mcx::AddFieldValue(fd, vtkMCXTypes::SampleWeightName(), projection.SampleWeight);
  mcx::AddFieldValue(fd, vtkMCXTypes::IntegralName(), projection.Integral);
  mcx::AddFieldValue(
    fd, vtkMCXTypes::EstimatedRelativeErrorName(), projection.EstimatedError());
  if (projection.Deposit >= 0) // an index input's: a cloud brings its own in its field data
  {
    mcx::AddFieldValue(fd, vtkMCXTypes::DepositName(), static_cast<long long>(projection.Deposit));
    mcx::AddFieldValue(
      fd, vtkMCXTypes::StrategyName(), static_cast<long long>(projection.Strategy));
  }
}
}

vtkMCXProjector::vtkMCXProjector()
{
  this->SetProgressText("X-Ray Projector"); // what progress bars show (ParaView's label)
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkMCXProjector::~vtkMCXProjector()
{
  this->SetController(nullptr);
}

std::string vtkMCXProjector::AgreeOnFailure(vtkInformation* inInfo, const std::string& failure)
{
  // Distributed over an index (a structured input): the processes wait for
  // each other from the index on, so they must fail together.
  if (mcx::IsDistributed(this->Controller) &&
    inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    return mcx::FirstErrorOfAll(this->Controller, failure);
  }
  return failure;
}

int vtkMCXProjector::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Under several processes, this process's z-slab of the index.
  if (mcx::RequestZSlab(this->Controller, inputVector[0]->GetInformationObject(0)))
  {
    return 1;
  }
  return this->Superclass::RequestUpdateExtent(request, inputVector, outputVector);
}

void vtkMCXProjector::SetStrategy(int strategy)
{
  if (strategy == vtkMCXTypes::VIEW_ORDERED)
  {
    vtkErrorMacro("SetStrategy: VIEW_ORDERED sorts a vtkMCXPointSampler's cloud for one view; "
                  "the projector's own samples cannot take it, so the strategy stays "
      << this->Strategy << ".");
    return;
  }
  const int clamped =
    std::min(std::max(strategy, static_cast<int>(vtkMCXTypes::HYBRID)),
      static_cast<int>(vtkMCXTypes::EVERY_VOXEL));
  if (clamped != this->Strategy)
  {
    this->Strategy = clamped;
    this->Modified();
  }
}

void vtkMCXProjector::SetNumberOfSamples(vtkTypeInt64 n)
{
  this->SetSampleExponent(static_cast<int>(mcx::ExponentForSampleCount(n)));
}

vtkTypeInt64 vtkMCXProjector::GetNumberOfSamples()
{
  return static_cast<vtkTypeInt64>(mcx::SampleCount(static_cast<unsigned>(this->SampleExponent)));
}

int vtkMCXProjector::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkMCXProjector::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!this->FrameOnInputData(input, inputVector[0]->GetInformationObject(0)))
  {
    output->Initialize();
    return 0;
  }
  const mcx::ProjectionGeometry& geometry = this->Internals->Geometry;

  int wholeExtent[6] = { 0, -1, 0, -1, 0, -1 };
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent);
  }
  Projection projection;
  try
  {
    if (!ProjectInput(this, input, wholeExtent, geometry, projection))
    {
      output->Initialize();
      return 0;
    }
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro("Out of memory projecting into " << geometry.Size[0] << " x " << geometry.Size[1]
                                                   << " pixels.");
    output->Initialize();
    return 0;
  }
  catch (const std::runtime_error& error)
  {
    vtkErrorMacro("Cannot project: " << error.what() << ".");
    output->Initialize();
    return 0;
  }
  // Distributed, the image is process 0's output and the others' are empty
  // (as parallel VTK and ParaView expect of a result that is one dataset).
  const bool elsewhere = vtkImageData::SafeDownCast(input) &&
    mcx::IsDistributed(this->Controller) && this->Controller->GetLocalProcessId() != 0;
  if (!projection.Completed) // aborted on every process: every one runs again next time
  {
    output->Initialize();
    return 1;
  }
  if (elsewhere)
  {
    mcx::EmptyOutputElsewhere(output, outputVector->GetInformationObject(0));
    return 1;
  }
  if (projection.EveryVoxel && projection.Count > 0 && !projection.RandomParts.empty())
  {
    vtkWarningMacro("Every voxel once, but not without noise: "
      << projection.RandomParts
      << "; that noise is not estimated (the footprint deposit, a smaller image or a larger "
         "FootprintReach avoids it).");
  }
  WriteImage(projection, geometry, this->AllocateLineIntegral(output), output->GetFieldData());
  return 1;
}

void vtkMCXProjector::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleExponent: " << this->SampleExponent << "\n";
  os << indent << "Strategy: " << this->Strategy << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Deposit: " << this->Deposit << "\n";
  os << indent << "FootprintReach: " << this->FootprintReach << "\n";
  os << indent << "TargetRelativeError: " << this->TargetRelativeError << "\n";
  os << indent << "ChooseDepositForTarget: " << this->ChooseDepositForTarget << "\n";
  os << indent << "TargetQuantizationLevels: " << this->TargetQuantizationLevels << "\n";
  os << indent << "MaximumSampleExponent: " << this->MaximumSampleExponent << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
