// The filter: its settings, its pipeline requests, and the three stages of
// an image: the input's samples projected (the index input in
// vtkMCXIndexProjectionPrivate, the cloud input in
// vtkMCXCloudProjectionPrivate, both into a Projection of
// vtkMCXProjectionPrivate.h), then written out as line integrals.
#include "vtkMCXProjector.h"

#include "mcxChannelSplit.h"
#include "mcxErrorEstimate.h"
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
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMCXProjector);
vtkCxxSetObjectMacro(vtkMCXProjector, Controller, vtkMultiProcessController);

namespace
{
using mcx::Projection;

// A target the largest sample count leaves unmet is said so, once (the
// first process): the run stopped at 2^MaximumSampleExponent - 1 samples.
void WarnOfAnUnmetTarget(vtkMCXProjector* self, const Projection& projection)
{
  const double targetError = self->GetTargetRelativeError();
  const int targetLevels = self->GetTargetQuantizationLevels();
  const int maximum = self->GetMaximumSampleExponent();
  vtkMultiProcessController* controller = self->GetController();
  if ((targetError <= 0 && targetLevels <= 0) || !projection.Completed || projection.EveryVoxel ||
    projection.Count < mcx::SampleCount(static_cast<unsigned>(maximum)) ||
    (controller && controller->GetLocalProcessId() != 0))
  {
    return;
  }
  if (targetError > 0 && projection.EstimatedError() > targetError)
  {
    vtkWarningWithObjectMacro(self,
      "The target relative error " << targetError << " is not met: the error estimated at 2^"
                                   << maximum
                                   << " - 1 samples, the most MaximumSampleExponent allows, is "
                                   << projection.EstimatedError());
    return;
  }
  const double needed =
    targetLevels > 0 ? mcx::QuantizationSampleCount(projection.Sums, targetLevels) : 0.0;
  if (needed > static_cast<double>(projection.Count))
  {
    vtkWarningWithObjectMacro(self,
      "The target of " << targetLevels << " quantization levels is not met: it asks for " << needed
                       << " samples, more than the 2^" << maximum
                       << " - 1 MaximumSampleExponent allows");
  }
}

// Stage 1: the input's samples, projected (false, reported, when there is
// no image to make).
bool ProjectInput(vtkMCXProjector* self, vtkDataObject* input, const int wholeExtent[6],
  const mcx::ProjectionGeometry& geometry, Projection& projection)
{
  if (auto* cloud = vtkPolyData::SafeDownCast(input))
  {
    if (self->GetNumberOfChannels() > 0)
    {
      vtkErrorWithObjectMacro(self,
        "Cannot project into channels: the channels split the deposit of samples drawn from a "
        "density index, and the input is a stored point cloud (weigh its points per channel "
        "with vtkMCXMaterialWeights instead, or set NumberOfChannels to 0).");
      return false;
    }
    return mcx::ProjectCloud(self, cloud, geometry, self->GetFootprintReach(), projection);
  }
  if (!mcx::ProjectIndex(
        self, vtkImageData::SafeDownCast(input), wholeExtent, geometry, projection))
  {
    return false;
  }
  WarnOfAnUnmetTarget(self, projection);
  return true;
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

namespace
{
// Stage 3 of a split deposit: the channels' line integrals, one component
// each, and their estimated errors.
void WriteChannels(
  const Projection& projection, const mcx::ProjectionGeometry& geometry, vtkImageData* output)
{
  const vtkIdType pixels = output->GetNumberOfPoints();
  const int channels = static_cast<int>(projection.ChannelSums.size());
  if (channels == 0)
  {
    return;
  }
  vtkNew<vtkDoubleArray> lines;
  lines->SetName(vtkMCXTypes::ChannelLineIntegralName());
  lines->SetNumberOfComponents(channels);
  lines->SetNumberOfTuples(pixels);
  vtkNew<vtkDoubleArray> errors;
  errors->SetName(vtkMCXTypes::ChannelEstimatedRelativeErrorName());
  std::vector<double> one(static_cast<std::size_t>(pixels));
  for (int c = 0; c < channels; ++c)
  {
    mcx::FixedSumsToValues(projection.ChannelSums[static_cast<std::size_t>(c)].data(), one.size(),
      projection.SampleWeight, geometry.BeamCrossSection(), one.data());
    for (vtkIdType p = 0; p < pixels; ++p)
    {
      lines->SetTypedComponent(p, c, one[static_cast<std::size_t>(p)]);
    }
    errors->InsertNextValue(projection.ChannelEstimatedError(static_cast<std::size_t>(c)));
  }
  output->GetFieldData()->AddArray(errors);
  output->GetPointData()->AddArray(lines);
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
  WriteChannels(projection, geometry, output);
  return 1;
}

void vtkMCXProjector::SetNumberOfChannels(int channels)
{
  const int clamped = std::min(std::max(channels, 0), static_cast<int>(mcx::MaximumChannels));
  if (clamped != this->GetNumberOfChannels())
  {
    this->ChannelFractions.resize(static_cast<std::size_t>(clamped));
    this->Modified();
  }
}

int vtkMCXProjector::GetNumberOfChannels() const
{
  return static_cast<int>(this->ChannelFractions.size());
}

void vtkMCXProjector::SetChannelFraction(int c, vtkPiecewiseFunction* fraction)
{
  if (c < 0 || c >= this->GetNumberOfChannels())
  {
    vtkErrorMacro("SetChannelFraction: channel " << c << " is not one of the "
                                                 << this->GetNumberOfChannels()
                                                 << " channels (SetNumberOfChannels first).");
    return;
  }
  if (this->ChannelFractions[static_cast<std::size_t>(c)] != fraction)
  {
    this->ChannelFractions[static_cast<std::size_t>(c)] = fraction;
    this->Modified();
  }
}

vtkPiecewiseFunction* vtkMCXProjector::GetChannelFraction(int c) const
{
  return c >= 0 && c < this->GetNumberOfChannels()
    ? this->ChannelFractions[static_cast<std::size_t>(c)].Get()
    : nullptr;
}

vtkMTimeType vtkMCXProjector::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  for (const auto& fraction : this->ChannelFractions)
  {
    if (fraction)
    {
      t = std::max(t, fraction->GetMTime());
    }
  }
  return t;
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
  os << indent << "NumberOfChannels: " << this->GetNumberOfChannels() << "\n";
  for (std::size_t c = 0; c < this->ChannelFractions.size(); ++c)
  {
    os << indent << "ChannelFraction " << c << ": " << this->ChannelFractions[c].Get() << "\n";
  }
}
