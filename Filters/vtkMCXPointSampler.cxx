#include "vtkMCXPointSampler.h"

#include "mcxProjectionGeometry.h"
#include "vtkMCXBatchedForPrivate.h"
#include "vtkMCXIndexViewPrivate.h"
#include "vtkMCXMemoryCheckPrivate.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkMCXPointSampler);

// The public constants are the core's, seen from VTK.
static_assert(vtkMCXPointSampler::HYBRID == static_cast<int>(mcx::Strategy::Hybrid) &&
    vtkMCXPointSampler::MONTE_CARLO == static_cast<int>(mcx::Strategy::MonteCarlo) &&
    vtkMCXPointSampler::QUASI_MONTE_CARLO == static_cast<int>(mcx::Strategy::QuasiMonteCarlo),
  "strategy values differ from mcx::Strategy");
static_assert(vtkMCXPointSampler::TENT == static_cast<int>(mcx::Kernel::Tent) &&
    vtkMCXPointSampler::BOX == static_cast<int>(mcx::Kernel::Box),
  "kernel values differ from mcx::Kernel");
static_assert(
  vtkMCXPointSampler::LargestSampleExponent == static_cast<int>(mcx::MaximumSampleExponent),
  "the largest sample exponent differs from the core's");
vtkCxxSetObjectMacro(vtkMCXPointSampler, TransferFunction, vtkPiecewiseFunction);
vtkInformationKeyRestrictedMacro(vtkMCXPointSampler, SUPPORT_CORNERS, DoubleVector, 24);

namespace
{
template <typename IdType, typename Real>
bool GeneratePoints(vtkAlgorithm* self, const mcx::IndexView& view, const mcx::TransferTable& table,
  mcx::Strategy strategy, mcx::Kernel kernel, vtkTypeUInt64 seed, unsigned m, bool centres,
  Real* points)
{
  mcx::SampleSource<IdType> source = view.MakeSource<IdType>(table);
  source.Centres = centres;
  source.Method = strategy;
  source.Reconstruction = kernel;
  source.Seed = seed;
  source.Exponent = m;
  double origin[3], matrix[9];
  view.SourceToWorld(origin, matrix);
  auto store = [&](std::uint64_t k, const double p[3])
  {
    Real* x = points + 3 * k;
    for (int r = 0; r < 3; ++r)
    {
      x[r] = static_cast<Real>(
        origin[r] + matrix[3 * r] * p[0] + matrix[3 * r + 1] * p[1] + matrix[3 * r + 2] * p[2]);
    }
  };
  return mcx::BatchedFor(
    self, source.NumberOfStorageItems(), 0.05, 1.0,
    [&](std::uint64_t b, std::uint64_t e) { source.GenerateForStorage(b, e, store); }, 1);
}
}

vtkMCXPointSampler::vtkMCXPointSampler()
{
  this->SetProgressText("X-Ray Point Sampler"); // what progress bars show (ParaView's label)
}

vtkMCXPointSampler::~vtkMCXPointSampler()
{
  this->SetTransferFunction(nullptr);
}

void vtkMCXPointSampler::SetNumberOfSamples(vtkTypeInt64 n)
{
  this->SetSampleExponent(static_cast<int>(mcx::ExponentForSampleCount(n)));
}

void vtkMCXPointSampler::SetReusePoints(bool reuse)
{
  if (!reuse)
  {
    this->KeptPoints = nullptr; // not an output change: no Modified()
  }
  if (reuse != this->ReusePoints)
  {
    this->ReusePoints = reuse;
    this->Modified();
  }
}

vtkTypeInt64 vtkMCXPointSampler::GetNumberOfSamples()
{
  return static_cast<vtkTypeInt64>(mcx::SampleCount(static_cast<unsigned>(this->SampleExponent)));
}

vtkMTimeType vtkMCXPointSampler::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->TransferFunction)
  {
    t = std::max(t, this->TransferFunction->GetMTime());
  }
  return t;
}

int vtkMCXPointSampler::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkMCXPointSampler::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  double corners[24];
  const double radius = mcx::KernelRadius(static_cast<mcx::Kernel>(this->Kernel));
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (mcx::SupportCornersFromInformation(inputVector[0]->GetInformationObject(0), radius, corners))
  {
    outInfo->Set(SUPPORT_CORNERS(), corners, 24);
  }
  else
  {
    outInfo->Remove(SUPPORT_CORNERS());
  }
  return 1;
}

int vtkMCXPointSampler::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  return 1;
}

int vtkMCXPointSampler::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  mcx::IndexView view;
  mcx::TransferTable table;
  double integral = 0.0;
  if (!mcx::PrepareSampling(this, "sample", input, this->TransferFunction, view, table, integral))
  {
    this->KeptPoints = nullptr;
    output->Initialize(); // no stale cloud of an earlier request
    return 0;
  }

  const unsigned m = table.IsEmpty() ? 0u : static_cast<unsigned>(this->SampleExponent);
  const vtkIdType count = static_cast<vtkIdType>(mcx::SampleCount(m));
  const int pointType = this->OutputPointsPrecision == DOUBLE_PRECISION ? VTK_DOUBLE : VTK_FLOAT;
  vtkSmartPointer<vtkPoints> points = this->ReusablePoints(output, pointType, count);
  this->KeptPoints = nullptr; // an old cloud is not held while a new one is allocated
  if (!points &&
    !mcx::CheckMemory(this, 3.0 * (pointType == VTK_DOUBLE ? 8 : 4) * static_cast<double>(count),
      "A cloud of " + std::to_string(count) + " points"))
  {
    output->Initialize();
    return 0;
  }
  if (points)
  {
    points->Modified();
  }
  else
  {
    points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataType(pointType);
    points->SetNumberOfPoints(count);
    if (points->GetNumberOfPoints() != count)
    {
      vtkErrorMacro("Cannot allocate a cloud of " << count << " points.");
      output->Initialize();
      return 0;
    }
  }

  bool completed = true;
  if (count > 0)
  {
    const auto strategy = static_cast<mcx::Strategy>(this->Strategy);
    const auto kernel = static_cast<mcx::Kernel>(this->Kernel);
    const bool centres = this->Deposit == FOOTPRINT;
    void* raw = points->GetVoidPointer(0);
    const bool isDouble = this->OutputPointsPrecision == DOUBLE_PRECISION;
    if (view.WideIds)
    {
      completed = isDouble ? GeneratePoints<std::uint64_t>(this, view, table, strategy, kernel,
                               this->Seed, m, centres, static_cast<double*>(raw))
                           : GeneratePoints<std::uint64_t>(this, view, table, strategy, kernel,
                               this->Seed, m, centres, static_cast<float*>(raw));
    }
    else
    {
      completed = isDouble ? GeneratePoints<std::uint32_t>(this, view, table, strategy, kernel,
                               this->Seed, m, centres, static_cast<double*>(raw))
                           : GeneratePoints<std::uint32_t>(this, view, table, strategy, kernel,
                               this->Seed, m, centres, static_cast<float*>(raw));
    }
  }
  if (!completed)
  {
    output->Initialize();
    return 1;
  }

  output->SetPoints(points);
  if (this->ReusePoints)
  {
    this->KeptPoints = points;
  }
  // Only what the cloud's consumers read: not the index's arrays (the
  // pipeline passes the input's field data on; SortedVoxelIds alone is 4
  // bytes per voxel).
  vtkFieldData* fd = output->GetFieldData();
  fd->Initialize();
  mcx::AddFieldValue(
    fd, SampleWeightName(), count > 0 ? integral / static_cast<double>(count) : 0.0);
  mcx::AddFieldValue(fd, IntegralName(), integral);
  mcx::AddFieldValue(fd, SampleExponentName(), static_cast<long long>(m));
  mcx::AddFieldValue(fd, DepositName(), static_cast<long long>(this->Deposit));
  mcx::AddFieldValue(fd, KernelName(), static_cast<long long>(this->Kernel));
  mcx::AddFieldValue(fd, StrategyName(), static_cast<long long>(this->Strategy));
  mcx::AddFieldValue(fd, SeedName(), static_cast<long long>(this->Seed));
  double origin[3], axes[9];
  view.SourceToWorld(origin, axes);
  vtkNew<vtkDoubleArray> voxelAxes;
  voxelAxes->SetName(VoxelAxesName());
  voxelAxes->SetNumberOfValues(9);
  std::copy(axes, axes + 9, voxelAxes->GetPointer(0));
  fd->AddArray(voxelAxes);
  double corners[24];
  mcx::ComputeSupportCorners(view.Extent, view.Origin, view.Spacing, view.Direction,
    mcx::KernelRadius(static_cast<mcx::Kernel>(this->Kernel)), corners);
  vtkNew<vtkDoubleArray> support;
  support->SetName(SupportCornersName());
  support->SetNumberOfValues(24);
  std::copy(corners, corners + 24, support->GetPointer(0));
  fd->AddArray(support);
  return 1;
}

vtkPoints* vtkMCXPointSampler::ReusablePoints(vtkPolyData* output, int type, vtkIdType count) const
{
  vtkPoints* kept = this->KeptPoints;
  if (!this->ReusePoints || !kept || kept->GetDataType() != type ||
    kept->GetNumberOfPoints() != count || !kept->GetData())
  {
    return nullptr;
  }
  // The executive usually empties the output before RequestData; when it
  // has not, the output's reference is the old cloud's own.
  const int holders = 1 + (output->GetPoints() == kept ? 1 : 0);
  return kept->GetReferenceCount() == holders && kept->GetData()->GetReferenceCount() == 1
    ? kept
    : nullptr;
}

void vtkMCXPointSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TransferFunction: " << this->TransferFunction << "\n";
  os << indent << "SampleExponent: " << this->SampleExponent << "\n";
  os << indent << "Strategy: " << this->Strategy << "\n";
  os << indent << "Kernel: " << this->Kernel << "\n";
  os << indent << "Deposit: " << this->Deposit << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "ReusePoints: " << this->ReusePoints << "\n";
  os << indent << "KeptPoints: " << (this->KeptPoints ? this->KeptPoints->GetNumberOfPoints() : 0)
     << " points\n";
  os << indent << "OutputPointsPrecision: " << this->OutputPointsPrecision << "\n";
}
