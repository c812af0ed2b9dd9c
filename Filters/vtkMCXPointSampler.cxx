#include "vtkMCXPointSampler.h"

#include "mcxEveryVoxelOrder.h"
#include "mcxEveryVoxelSource.h"
#include "mcxProjectionGeometry.h"
#include "vtkMCXBatchedForPrivate.h"
#include "vtkMCXIndexViewPrivate.h"
#include "vtkMCXMemoryCheckPrivate.h"
#include "vtkMCXSMPExecutorPrivate.h"

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
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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
// x = origin + matrix p: a point in voxel coordinates stored in world
// coordinates (IndexView::SourceToWorld).
template <typename Real>
void StoreInWorld(const double origin[3], const double matrix[9], const double p[3], Real* x)
{
  for (int r = 0; r < 3; ++r)
  {
    x[r] = static_cast<Real>(
      origin[r] + matrix[3 * r] * p[0] + matrix[3 * r + 1] * p[1] + matrix[3 * r + 2] * p[2]);
  }
}

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
  { StoreInWorld(origin, matrix, p, points + 3 * k); };
  return mcx::BatchedFor(
    self, source.NumberOfStorageItems(), 0.05, 1.0,
    [&](std::uint64_t b, std::uint64_t e) { source.GenerateForStorage(b, e, store); }, 1);
}

// The voxels' world positions, point k of voxel ids[k]: its centre (the
// footprint deposit) or the centre plus a kernel offset drawn from the
// seed's stream of point k.
template <typename IdType, typename Real>
bool EveryVoxelPositions(vtkAlgorithm* self, const mcx::IndexView& view,
  const std::vector<IdType>& ids, mcx::Kernel kernel, bool centres, vtkTypeUInt64 seed,
  Real* points)
{
  const mcx::VoxelDecoder<IdType> decoder(
    static_cast<std::uint64_t>(view.Dimensions[0]), static_cast<std::uint64_t>(view.Dimensions[1]));
  double origin[3], matrix[9];
  view.SourceToWorld(origin, matrix);
  const std::uint64_t key = mcx::SeedKey(seed);
  return mcx::BatchedFor(self, ids.size(), 0.5, 1.0,
    [&](std::uint64_t b, std::uint64_t e)
    {
      for (std::uint64_t k = b; k < e; ++k)
      {
        std::uint64_t voxel[3];
        decoder.Decode(ids[k], voxel[0], voxel[1], voxel[2]);
        double p[3];
        mcx::EveryVoxelPoint(voxel, kernel, centres, key, k, p);
        StoreInWorld(origin, matrix, p, points + 3 * k);
      }
    });
}

// An every-voxel cloud's PointWeight: point k, of level levels[k], counts
// the level's weight over the mean weight (mcx::EveryVoxelWeight), so the
// weights sum to the point count.
vtkSmartPointer<vtkFloatArray> PointWeights(
  const std::vector<std::uint32_t>& levels, const std::vector<double>& weights, double total)
{
  const vtkIdType count = static_cast<vtkIdType>(levels.size());
  std::vector<float> levelWeights(weights.size());
  for (std::size_t l = 0; l < weights.size(); ++l)
  {
    levelWeights[l] =
      static_cast<float>(mcx::EveryVoxelWeight(weights[l], static_cast<double>(count), total));
  }
  auto pointWeights = vtkSmartPointer<vtkFloatArray>::New();
  pointWeights->SetName(vtkMCXPointSampler::PointWeightName());
  pointWeights->SetNumberOfValues(count);
  float* w = pointWeights->GetPointer(0);
  vtkSMPTools::For(0, count,
    [&](vtkIdType b, vtkIdType e)
    {
      for (vtkIdType k = b; k < e; ++k)
      {
        w[k] = levelWeights[levels[static_cast<std::size_t>(k)]];
      }
    });
  return pointWeights;
}

// What every cloud's consumers read (the pipeline passes the input's field
// data on: only these, not the index's arrays; SortedVoxelIds alone is 4
// bytes per voxel). exponent < 0: no SampleExponent (an every-voxel cloud).
void WriteCloudFields(vtkMCXPointSampler* self, const mcx::IndexView& view, double integral,
  vtkIdType count, int exponent, vtkFieldData* fd)
{
  fd->Initialize();
  mcx::AddFieldValue(fd, vtkMCXPointSampler::SampleWeightName(),
    count > 0 ? integral / static_cast<double>(count) : 0.0);
  mcx::AddFieldValue(fd, vtkMCXPointSampler::IntegralName(), integral);
  if (exponent >= 0)
  {
    mcx::AddFieldValue(
      fd, vtkMCXPointSampler::SampleExponentName(), static_cast<long long>(exponent));
  }
  mcx::AddFieldValue(
    fd, vtkMCXPointSampler::DepositName(), static_cast<long long>(self->GetDeposit()));
  mcx::AddFieldValue(
    fd, vtkMCXPointSampler::KernelName(), static_cast<long long>(self->GetKernel()));
  mcx::AddFieldValue(
    fd, vtkMCXPointSampler::StrategyName(), static_cast<long long>(self->GetStrategy()));
  mcx::AddFieldValue(fd, vtkMCXPointSampler::SeedName(), static_cast<long long>(self->GetSeed()));
  double origin[3], axes[9];
  view.SourceToWorld(origin, axes);
  vtkNew<vtkDoubleArray> voxelAxes;
  voxelAxes->SetName(vtkMCXPointSampler::VoxelAxesName());
  voxelAxes->SetNumberOfValues(9);
  std::copy(axes, axes + 9, voxelAxes->GetPointer(0));
  fd->AddArray(voxelAxes);
  double corners[24];
  mcx::ComputeSupportCorners(view.Extent, view.Origin, view.Spacing, view.Direction,
    mcx::KernelRadius(static_cast<mcx::Kernel>(self->GetKernel())), corners);
  vtkNew<vtkDoubleArray> support;
  support->SetName(vtkMCXPointSampler::SupportCornersName());
  support->SetNumberOfValues(24);
  std::copy(corners, corners + 24, support->GetPointer(0));
  fd->AddArray(support);
}
}

// The voxels of an every-voxel cloud and what they were made for.
struct vtkMCXPointSampler::EveryVoxelCloud
{
  vtkDataArray* Ids = nullptr; // the index's sorted ids: compared only, never dereferenced
  vtkMTimeType IdsTime = 0;
  double World[12] = { 0 }; // the index's source-to-world origin and matrix
  std::vector<char> Kept;   // per level
  int PointType = VTK_FLOAT;
  int Deposit = POINT;
  int Kernel = TENT;
  vtkTypeInt64 Seed = 0;
  vtkSmartPointer<vtkPoints> Points;
  std::vector<std::uint32_t> Levels; // of each point

  void Describe(const mcx::IndexView& view, const std::vector<char>& kept,
    const vtkMCXPointSampler* sampler, int pointType)
  {
    this->Ids = view.Ids;
    this->IdsTime = view.Ids->GetMTime();
    view.SourceToWorld(this->World, this->World + 3);
    this->Kept = kept;
    this->PointType = pointType;
    this->Deposit = sampler->Deposit;
    this->Kernel = sampler->Kernel;
    this->Seed = sampler->Seed;
  }

  bool Fits(const mcx::IndexView& view, const std::vector<char>& kept,
    const vtkMCXPointSampler* sampler, int pointType) const
  {
    EveryVoxelCloud wanted;
    wanted.Describe(view, kept, sampler, pointType);
    return this->Ids == wanted.Ids && this->IdsTime == wanted.IdsTime &&
      std::equal(this->World, this->World + 12, wanted.World) && this->Kept == wanted.Kept &&
      this->PointType == wanted.PointType && this->Deposit == wanted.Deposit &&
      this->Kernel == wanted.Kernel && this->Seed == wanted.Seed;
  }
};

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
    this->KeptVoxels.reset();
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
  if (this->Strategy == EVERY_VOXEL)
  {
    return this->RequestEveryVoxel(input, output);
  }
  this->KeptVoxels.reset();
  // A sampled cloud's points count once each (an output the executive did
  // not empty may still hold an every-voxel cloud's weights).
  output->GetPointData()->RemoveArray(PointWeightName());
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
  WriteCloudFields(this, view, integral, count, static_cast<int>(m), output->GetFieldData());
  return 1;
}

int vtkMCXPointSampler::RequestEveryVoxel(vtkImageData* input, vtkPolyData* output)
{
  this->KeptPoints = nullptr;
  std::unique_ptr<EveryVoxelCloud> cloud = std::move(this->KeptVoxels);
  mcx::IndexView view;
  mcx::TransferTable table;
  double integral = 0.0;
  if (!mcx::PrepareSampling(this, "sample", input, this->TransferFunction, view, table, integral))
  {
    output->Initialize(); // no stale cloud of an earlier request
    return 0;
  }
  std::vector<double> weights = view.EvaluateTransferFunction(this->TransferFunction);
  std::vector<char> kept;
  const vtkIdType count = static_cast<vtkIdType>(view.KeepLevels(weights, kept));
  const vtkIdType largest = (vtkIdType(1) << MaximumPointCloudExponent) - 1;
  if (count > largest)
  {
    vtkErrorMacro("Every voxel: " << count << " voxels of non-zero weight exceed the " << largest
                                  << " points of the largest cloud; sample them instead.");
    output->Initialize();
    return 0;
  }
  const int pointType = this->OutputPointsPrecision == DOUBLE_PRECISION ? VTK_DOUBLE : VTK_FLOAT;
  if (!cloud || !cloud->Fits(view, kept, this, pointType))
  {
    cloud.reset(); // not held while a new one is made
    const double voxels =
      static_cast<double>(view.Dimensions[0]) * view.Dimensions[1] * view.Dimensions[2];
    const double idBytes = view.WideIds ? 8.0 : 4.0;
    if (!mcx::CheckMemory(this,
          static_cast<double>(count) *
              (3.0 * (pointType == VTK_DOUBLE ? 8 : 4) + 4 + 4 + 2 * idBytes) +
            4.0 * voxels,
          "A cloud of every voxel's " + std::to_string(count) + " points"))
    {
      output->Initialize();
      return 0;
    }
    cloud.reset(new EveryVoxelCloud);
    cloud->Describe(view, kept, this, pointType);
    bool completed = true;
    if (!this->MakeEveryVoxelPoints(view, kept, *cloud, completed))
    {
      vtkErrorMacro("Cannot sample every voxel: the index's sorted ids are not distinct voxel ids "
                    "of its volume (a damaged index).");
      output->Initialize();
      return 0;
    }
    if (!completed)
    {
      output->Initialize();
      return 1; // aborted
    }
  }

  output->SetPoints(cloud->Points);
  output->GetPointData()->AddArray(PointWeights(cloud->Levels, weights, table.WeightSum()));
  WriteCloudFields(this, view, integral, count, -1, output->GetFieldData());
  if (this->ReusePoints)
  {
    this->KeptVoxels = std::move(cloud);
  }
  return 1;
}

bool vtkMCXPointSampler::MakeEveryVoxelPoints(const mcx::IndexView& view,
  const std::vector<char>& kept, EveryVoxelCloud& cloud, bool& completed)
{
  const std::int64_t voxels =
    static_cast<std::int64_t>(view.Dimensions[0]) * view.Dimensions[1] * view.Dimensions[2];
  const auto kernel = static_cast<mcx::Kernel>(this->Kernel);
  const bool centres = this->Deposit == FOOTPRINT;
  const auto seed = static_cast<vtkTypeUInt64>(this->Seed);
  auto make = [&](auto id)
  {
    using IdType = decltype(id);
    mcx::EveryVoxelOrder<IdType> order;
    if (!order.Build(mcx::SMPExecutor(), view.IdPointer<IdType>(), view.LevelOffsets,
          view.NumberOfLevels, kept, voxels))
    {
      return false;
    }
    this->UpdateProgress(0.5);
    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataType(cloud.PointType);
    points->SetNumberOfPoints(static_cast<vtkIdType>(order.Size()));
    void* raw = points->GetVoidPointer(0);
    completed = cloud.PointType == VTK_DOUBLE
      ? EveryVoxelPositions(this, view, order.Ids, kernel, centres, seed, static_cast<double*>(raw))
      : EveryVoxelPositions(this, view, order.Ids, kernel, centres, seed, static_cast<float*>(raw));
    cloud.Points = points;
    cloud.Levels = std::move(order.Levels);
    return true;
  };
  return view.WideIds ? make(std::uint64_t(0)) : make(std::uint32_t(0));
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
  os << indent << "KeptVoxels: "
     << (this->KeptVoxels ? static_cast<vtkIdType>(this->KeptVoxels->Levels.size()) : 0)
     << " points\n";
  os << indent << "OutputPointsPrecision: " << this->OutputPointsPrecision << "\n";
}
