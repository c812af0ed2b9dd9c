#include "vtkMCXPointSampler.h"

#include "mcxEveryVoxelOrder.h"
#include "mcxEveryVoxelSource.h"
#include "mcxPixelBinner.h"
#include "mcxProjectionGeometry.h"
#include "mcxSampleAccumulator.h"
#include "mcxViewOrder.h"
#include "vtkMCXBatchedForPrivate.h"
#include "vtkMCXCameraGeometryPrivate.h"
#include "vtkMCXCloudDepositPrivate.h"
#include "vtkMCXIndexViewPrivate.h"
#include "vtkMCXMemoryCheckPrivate.h"
#include "vtkMCXSMPExecutorPrivate.h"

#include "vtkCamera.h"
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

// GeneratePoints for a view order: the bins are the table's levels, and
// each point's weight (w / the bin's mean w) goes to weights[k].
template <typename IdType, typename Real>
bool GenerateViewOrderedPoints(vtkAlgorithm* self, const mcx::IndexView& view,
  const mcx::ViewOrder<IdType>& order, const mcx::TransferTable& binTable,
  const std::vector<double>& levelRatios, mcx::Kernel kernel, vtkTypeUInt64 seed, unsigned m,
  bool centres, Real* points, float* weights)
{
  mcx::SampleSource<IdType> source = view.MakeSource<IdType>(binTable);
  source.SortedIds = order.Ids.data();
  source.LevelOffsets = order.BinOffsets.data();
  source.NumberOfLevels = order.NumberOfBins();
  source.LevelInBin = order.LevelInBin.data();
  source.BinFirstLevel = order.BinFirstLevel.data();
  source.LevelRatio = levelRatios.data();
  source.Centres = centres;
  source.Method = mcx::Strategy::Hybrid;
  source.Reconstruction = kernel;
  source.Seed = seed;
  source.Exponent = m;
  double origin[3], matrix[9];
  view.SourceToWorld(origin, matrix);
  auto store = [&](std::uint64_t k, const double p[3], double weight)
  {
    StoreInWorld(origin, matrix, p, points + 3 * k);
    weights[k] = static_cast<float>(weight);
  };
  return mcx::BatchedFor(
    self, source.NumberOfStorageItems(), 0.55, 1.0,
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
  pointWeights->SetName(vtkMCXTypes::PointWeightName());
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

// Each bin's voxels of `order` projected once each, footprints of `kernel`
// in `geometry` (voxel coordinates, as the sort located them): bins x
// pixels sums in the accumulator's fixed-point units (2^32 a whole voxel),
// the bins' images of the control (mcxControlImage.h). Their footprints
// round at random from a stream of their own, the same for every seed, so
// a new seed keeps them. Progress runs from progressBegin to progressEnd;
// false when aborted.
template <typename IdType>
bool ProjectBins(vtkAlgorithm* self, const mcx::IndexView& view,
  const mcx::ViewOrder<IdType>& order, const mcx::ProjectionGeometry& geometry, mcx::Kernel kernel,
  double progressBegin, double progressEnd, std::vector<double>& images)
{
  double origin[3], matrix[9];
  view.SourceToWorld(origin, matrix);
  mcx::DepositSettings settings; // samples in voxel coordinates: the identity VoxelMatrix
  settings.Mode = mcx::Deposit::Footprint;
  settings.Reconstruction = kernel;
  if (geometry.Perspective)
  {
    double corners[24];
    mcx::ComputeSupportCorners(
      view.Extent, view.Origin, view.Spacing, view.Direction, mcx::KernelRadius(kernel), corners);
    mcx::SupportDepthRange(geometry, corners, settings.Depths);
  }
  mcx::SampleAccumulator<mcx::SMPExecutor> accumulator;
  accumulator.Reset(geometry, origin, matrix, std::vector<double>(), settings);
  const std::size_t pixels = accumulator.NumberOfPixels();
  const std::int64_t bins = order.NumberOfBins();
  const mcx::VoxelDecoder<IdType> decoder(
    static_cast<std::uint64_t>(view.Dimensions[0]), static_cast<std::uint64_t>(view.Dimensions[1]));
  const double voxels = static_cast<double>(std::max<std::int64_t>(1, order.BinOffsets.back()));
  images.assign(static_cast<std::size_t>(bins) * pixels, 0.0);
  std::vector<mcx::FixedSum> all(pixels), firstHalf(pixels);
  for (std::int64_t b = 0; b < bins; ++b)
  {
    const std::int64_t first = order.BinOffsets[static_cast<std::size_t>(b)];
    const std::int64_t last = order.BinOffsets[static_cast<std::size_t>(b + 1)];
    const double span = progressEnd - progressBegin;
    const bool completed = mcx::BatchedFor(self, static_cast<std::uint64_t>(last - first),
      progressBegin + span * static_cast<double>(first) / voxels,
      progressBegin + span * static_cast<double>(last) / voxels,
      [&](std::uint64_t begin, std::uint64_t end)
      {
        const auto image = accumulator.Local();
        for (std::uint64_t i = begin; i < end; ++i)
        {
          const std::uint64_t k = static_cast<std::uint64_t>(first) + i;
          std::uint64_t voxel[3];
          decoder.Decode(order.Ids[k], voxel[0], voxel[1], voxel[2]);
          const double p[3] = { static_cast<double>(voxel[0]), static_cast<double>(voxel[1]),
            static_cast<double>(voxel[2]) };
          image.Deposit(k, p);
        }
      });
    if (!completed)
    {
      return false;
    }
    std::fill(all.begin(), all.end(), mcx::FixedSum(0));
    accumulator.Collect(all.data(), firstHalf.data());
    double* image = images.data() + static_cast<std::size_t>(b) * pixels;
    for (std::size_t p = 0; p < pixels; ++p)
    {
      image[p] = mcx::ToDouble(all[p]);
    }
  }
  return true;
}

// The control image (line integrals) of the TF whose weight on each bin is
// binMeans[b]: the bins' images weighed by it, scaled so that it carries
// the cloud's integral as the cloud does. Empty when no bin has weight.
std::vector<double> ControlImage(const std::vector<double>& binImages,
  const std::vector<double>& binMeans, const std::vector<std::int64_t>& binOffsets, double integral,
  const mcx::ProjectionGeometry& geometry)
{
  const std::size_t bins = binMeans.size();
  const std::size_t pixels = bins > 0 ? binImages.size() / bins : 0;
  double weightedVoxels = 0.0; // the integral in units of one voxel of weight 1
  for (std::size_t b = 0; b < bins; ++b)
  {
    weightedVoxels += binMeans[b] * static_cast<double>(binOffsets[b + 1] - binOffsets[b]);
  }
  if (!(weightedVoxels > 0) || pixels == 0)
  {
    return std::vector<double>();
  }
  const double scale = integral / weightedVoxels / (mcx::FixedOne * geometry.BeamCrossSection());
  std::vector<double> control(pixels, 0.0);
  for (std::size_t b = 0; b < bins; ++b)
  {
    const double weight = binMeans[b] * scale;
    if (weight == 0.0)
    {
      continue;
    }
    const double* image = binImages.data() + b * pixels;
    for (std::size_t p = 0; p < pixels; ++p)
    {
      control[p] += weight * image[p];
    }
  }
  return control;
}

// What every cloud's consumers read (the pipeline passes the input's field
// data on: only these, not the index's arrays; SortedVoxelIds alone is 4
// bytes per voxel). exponent < 0: no SampleExponent (an every-voxel cloud).
void WriteCloudFields(vtkMCXPointSampler* self, const mcx::IndexView& view, double integral,
  vtkIdType count, int exponent, vtkFieldData* fd)
{
  fd->Initialize();
  mcx::AddFieldValue(fd, vtkMCXTypes::SampleWeightName(),
    count > 0 ? integral / static_cast<double>(count) : 0.0);
  mcx::AddFieldValue(fd, vtkMCXTypes::IntegralName(), integral);
  if (exponent >= 0)
  {
    mcx::AddFieldValue(
      fd, vtkMCXTypes::SampleExponentName(), static_cast<long long>(exponent));
  }
  mcx::AddFieldValue(
    fd, vtkMCXTypes::DepositName(), static_cast<long long>(self->GetDeposit()));
  mcx::AddFieldValue(
    fd, vtkMCXTypes::KernelName(), static_cast<long long>(self->GetKernel()));
  mcx::AddFieldValue(
    fd, vtkMCXTypes::StrategyName(), static_cast<long long>(self->GetStrategy()));
  mcx::AddFieldValue(fd, vtkMCXTypes::SeedName(), static_cast<long long>(self->GetSeed()));
  double origin[3], axes[9];
  view.SourceToWorld(origin, axes);
  vtkNew<vtkDoubleArray> voxelAxes;
  voxelAxes->SetName(vtkMCXTypes::VoxelAxesName());
  voxelAxes->SetNumberOfValues(9);
  std::copy(axes, axes + 9, voxelAxes->GetPointer(0));
  fd->AddArray(voxelAxes);
  double corners[24];
  mcx::ComputeSupportCorners(view.Extent, view.Origin, view.Spacing, view.Direction,
    mcx::KernelRadius(static_cast<mcx::Kernel>(self->GetKernel())), corners);
  vtkNew<vtkDoubleArray> support;
  support->SetName(vtkMCXTypes::SupportCornersName());
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
  int Deposit = vtkMCXTypes::POINT;
  int Kernel = vtkMCXTypes::TENT;
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

// SetOrderingView's copy of the camera's geometry.
struct vtkMCXPointSampler::OrderingView
{
  mcx::ProjectionGeometry Geometry;
};

// A view order and what it was sorted for.
struct vtkMCXPointSampler::SortedView
{
  vtkDataArray* Ids = nullptr; // the index's sorted ids: compared only, never dereferenced
  vtkMTimeType IdsTime = 0;
  double World[12] = { 0 }; // the index's source-to-world origin and matrix
  mcx::ProjectionGeometry Geometry;
  int Bins = 0;
  mcx::ViewOrder<std::uint32_t> Narrow; // the index's ids are 32-bit
  mcx::ViewOrder<std::uint64_t> Wide;   // or 64-bit (WideIds)
  // The control's bins' images (ProjectBins), and the kernel they were
  // projected with; empty until a controlled cloud needs them.
  std::vector<double> BinImages;
  int BinKernel = -1;

  std::int64_t BinsOf(bool wideIds) const
  {
    return wideIds ? this->Wide.NumberOfBins() : this->Narrow.NumberOfBins();
  }

  void Describe(const mcx::IndexView& view, const mcx::ProjectionGeometry& geometry, int bins)
  {
    this->Ids = view.Ids;
    this->IdsTime = view.Ids->GetMTime();
    view.SourceToWorld(this->World, this->World + 3);
    this->Geometry = geometry;
    this->Bins = bins;
  }

  bool Fits(const mcx::IndexView& view, const mcx::ProjectionGeometry& geometry, int bins) const
  {
    SortedView wanted;
    wanted.Describe(view, geometry, bins);
    return this->Ids == wanted.Ids && this->IdsTime == wanted.IdsTime &&
      std::equal(this->World, this->World + 12, wanted.World) &&
      mcx::SameGeometry(this->Geometry, wanted.Geometry) && this->Bins == wanted.Bins;
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

void vtkMCXPointSampler::SetOrderingView(vtkCamera* camera, int width, int height)
{
  std::unique_ptr<OrderingView> ordering;
  if (camera && width > 0 && height > 0)
  {
    ordering.reset(new OrderingView);
    const int size[2] = { width, height };
    const std::string problem = mcx::GeometryFromCamera(camera, size, 0.0, 0.0, ordering->Geometry);
    if (!problem.empty())
    {
      vtkErrorMacro("Cannot order by this view: " << problem);
      return;
    }
  }
  if (!ordering && !this->Ordering)
  {
    return;
  }
  if (ordering && this->Ordering && mcx::SameGeometry(ordering->Geometry, this->Ordering->Geometry))
  {
    return;
  }
  this->Ordering = std::move(ordering);
  this->Modified();
}

bool vtkMCXPointSampler::HasOrderingView() const
{
  return this->Ordering != nullptr;
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
  if (this->Strategy == vtkMCXTypes::EVERY_VOXEL)
  {
    return this->RequestEveryVoxel(input, output);
  }
  this->KeptVoxels.reset();
  if (this->Strategy == vtkMCXTypes::VIEW_ORDERED)
  {
    return this->RequestViewOrdered(input, output);
  }
  this->KeptViewOrder.reset();
  // A sampled cloud's points count once each (an output the executive did
  // not empty may still hold an every-voxel cloud's weights).
  output->GetPointData()->RemoveArray(vtkMCXTypes::PointWeightName());
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
  vtkSmartPointer<vtkPoints> points = this->CloudPoints(output, pointType, count);
  if (!points)
  {
    output->Initialize();
    return 0;
  }

  bool completed = true;
  if (count > 0)
  {
    const auto strategy = static_cast<mcx::Strategy>(this->Strategy);
    const auto kernel = static_cast<mcx::Kernel>(this->Kernel);
    const bool centres = this->Deposit == vtkMCXTypes::FOOTPRINT;
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

vtkSmartPointer<vtkPoints> vtkMCXPointSampler::CloudPoints(
  vtkPolyData* output, int type, vtkIdType count)
{
  vtkSmartPointer<vtkPoints> points = this->ReusablePoints(output, type, count);
  this->KeptPoints = nullptr; // an old cloud is not held while a new one is allocated
  if (points)
  {
    points->Modified();
    return points;
  }
  if (!mcx::CheckMemory(this, 3.0 * (type == VTK_DOUBLE ? 8 : 4) * static_cast<double>(count),
        "A cloud of " + std::to_string(count) + " points"))
  {
    return nullptr;
  }
  points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataType(type);
  points->SetNumberOfPoints(count);
  if (points->GetNumberOfPoints() != count)
  {
    vtkErrorMacro("Cannot allocate a cloud of " << count << " points.");
    return nullptr;
  }
  return points;
}

int vtkMCXPointSampler::RequestViewOrdered(vtkImageData* input, vtkPolyData* output)
{
  mcx::IndexView view;
  mcx::TransferTable table;
  double integral = 0.0;
  if (!mcx::PrepareSampling(
        this, "sample in view order", input, this->TransferFunction, view, table, integral))
  {
    this->KeptPoints = nullptr;
    output->Initialize(); // no stale cloud of an earlier request
    return 0;
  }
  if (!this->Ordering)
  {
    vtkErrorMacro("Cannot sample in view order: no view to order by (call "
                  "SetOrderingView(camera, width, height) first).");
    output->Initialize();
    return 0;
  }
  if (view.PieceOffsets)
  {
    vtkErrorMacro("Cannot sample in view order: the index is one piece of a distributed volume, "
                  "and the view order needs the whole volume in one process (use HYBRID).");
    output->Initialize();
    return 0;
  }
  std::vector<double> weights = view.EvaluateTransferFunction(this->TransferFunction);
  std::vector<char> kept;
  view.KeepLevels(weights, kept); // the weights as the table takes them
  bool completed = true;
  SortedView* sorted = this->ViewOrderFor(view, completed);
  if (!sorted)
  {
    output->Initialize();
    return completed ? 0 : 1; // an error, or aborted
  }
  if (this->ControlVariate && !this->ProjectBinsFor(view, *sorted, completed))
  {
    output->Initialize();
    return completed ? 0 : 1; // an error, or aborted
  }

  std::vector<double> control;
  const int pointType = this->OutputPointsPrecision == DOUBLE_PRECISION ? VTK_DOUBLE : VTK_FLOAT;
  const auto kernel = static_cast<mcx::Kernel>(this->Kernel);
  const bool centres = this->Deposit == vtkMCXTypes::FOOTPRINT;
  const auto seed = static_cast<vtkTypeUInt64>(this->Seed);
  vtkSmartPointer<vtkPoints> points;
  vtkSmartPointer<vtkFloatArray> pointWeights;
  unsigned m = 0;
  auto generate = [&](const auto& order)
  {
    std::vector<double> binMeans, levelRatios;
    order.Weights(weights.data(), view.LevelOffsets, binMeans, levelRatios);
    const mcx::TransferTable binTable =
      mcx::BuildTransferTable(binMeans.data(), order.BinOffsets.data(), order.NumberOfBins());
    m = binTable.IsEmpty() ? 0u : static_cast<unsigned>(this->SampleExponent);
    if (this->ControlVariate && m > 0)
    {
      control =
        ControlImage(sorted->BinImages, binMeans, order.BinOffsets, integral, sorted->Geometry);
    }
    const vtkIdType count = static_cast<vtkIdType>(mcx::SampleCount(m));
    points = this->CloudPoints(output, pointType, count);
    if (!points)
    {
      return false;
    }
    pointWeights = vtkSmartPointer<vtkFloatArray>::New();
    pointWeights->SetName(vtkMCXTypes::PointWeightName());
    pointWeights->SetNumberOfValues(count);
    void* raw = points->GetVoidPointer(0);
    float* w = pointWeights->GetPointer(0);
    completed = count == 0 ||
      (pointType == VTK_DOUBLE ? GenerateViewOrderedPoints(this, view, order, binTable, levelRatios,
                                   kernel, seed, m, centres, static_cast<double*>(raw), w)
                               : GenerateViewOrderedPoints(this, view, order, binTable, levelRatios,
                                   kernel, seed, m, centres, static_cast<float*>(raw), w));
    return true;
  };
  if (!(view.WideIds ? generate(sorted->Wide) : generate(sorted->Narrow)))
  {
    output->Initialize();
    return 0;
  }
  if (!completed)
  {
    output->Initialize();
    return 1;
  }
  output->SetPoints(points);
  output->GetPointData()->AddArray(pointWeights);
  if (this->ReusePoints)
  {
    this->KeptPoints = points;
  }
  WriteCloudFields(
    this, view, integral, points->GetNumberOfPoints(), static_cast<int>(m), output->GetFieldData());
  if (!control.empty())
  {
    vtkNew<vtkDoubleArray> image;
    image->SetName(vtkMCXTypes::ControlImageName());
    image->SetNumberOfValues(static_cast<vtkIdType>(control.size()));
    std::copy(control.begin(), control.end(), image->GetPointer(0));
    output->GetFieldData()->AddArray(image);
    vtkNew<vtkDoubleArray> controlView;
    controlView->SetName(vtkMCXTypes::ControlViewName());
    controlView->SetNumberOfValues(mcx::GeometryValueCount);
    mcx::GeometryToValues(sorted->Geometry, controlView->GetPointer(0));
    output->GetFieldData()->AddArray(controlView);
    output->GetFieldData()->AddArray(mcx::ControlPointsOf(points));
  }
  return 1;
}

bool vtkMCXPointSampler::ProjectBinsFor(
  const mcx::IndexView& view, SortedView& sorted, bool& completed)
{
  completed = true;
  if (!sorted.BinImages.empty() && sorted.BinKernel == this->Kernel)
  {
    return true;
  }
  sorted.BinImages = std::vector<double>(); // not held while new ones are made
  const double pixels = static_cast<double>(sorted.Geometry.Size[0]) * sorted.Geometry.Size[1];
  const double bins = static_cast<double>(sorted.BinsOf(view.WideIds));
  // The images (8 bytes a bin and pixel), the threads' sums (16) and their collection (32).
  if (!mcx::CheckMemory(this,
        pixels * (8.0 * bins + 16.0 * vtkSMPTools::GetEstimatedNumberOfThreads() + 32.0),
        "The control image's " + std::to_string(static_cast<long long>(bins)) + " bin images"))
  {
    return false;
  }
  const auto kernel = static_cast<mcx::Kernel>(this->Kernel);
  std::vector<double> images;
  completed = view.WideIds
    ? ProjectBins(this, view, sorted.Wide, sorted.Geometry, kernel, 0.3, 0.55, images)
    : ProjectBins(this, view, sorted.Narrow, sorted.Geometry, kernel, 0.3, 0.55, images);
  if (completed)
  {
    sorted.BinImages = std::move(images);
    sorted.BinKernel = this->Kernel;
  }
  return completed;
}

vtkMCXPointSampler::SortedView* vtkMCXPointSampler::ViewOrderFor(
  const mcx::IndexView& view, bool& completed)
{
  completed = true;
  const mcx::ProjectionGeometry& geometry = this->Ordering->Geometry;
  if (this->KeptViewOrder && this->KeptViewOrder->Fits(view, geometry, this->NumberOfOrderingBins))
  {
    return this->KeptViewOrder.get();
  }
  this->KeptViewOrder.reset(); // not held while a new one is sorted
  const std::int64_t voxels = view.LevelOffsets[view.NumberOfLevels];
  const std::int64_t pixels = static_cast<std::int64_t>(geometry.Size[0]) * geometry.Size[1];
  const std::int64_t cells = pixels + 1; // the last: voxels off the image
  std::vector<std::int64_t> binFirstLevel =
    mcx::GroupLevelsIntoBins(view.LevelValues, view.NumberOfLevels, this->NumberOfOrderingBins);
  const std::int64_t keys = (static_cast<std::int64_t>(binFirstLevel.size()) - 1) * cells;
  const mcx::CountingSortLayout layout = mcx::MakeViewOrderLayout(voxels, keys);
  if (!mcx::CheckMemory(this,
        static_cast<double>(voxels) * ((view.WideIds ? 8.0 : 4.0) + 2.0 + 1.0) +
          8.0 * static_cast<double>(layout.NumberOfChunks + 1) * static_cast<double>(keys),
        "The view order of " + std::to_string(voxels) + " voxels"))
  {
    return nullptr;
  }
  std::unique_ptr<SortedView> sorted(new SortedView);
  sorted->Describe(view, geometry, this->NumberOfOrderingBins);
  double origin[3], matrix[9];
  view.SourceToWorld(origin, matrix);
  const mcx::PixelBinner binner(geometry, origin, matrix);
  auto progress = [this](double fraction)
  {
    this->UpdateProgress((this->ControlVariate ? 0.3 : 0.5) * fraction);
    return !this->GetAbortExecute();
  };
  auto sort = [&](auto& order)
  {
    using IdType = typename std::decay_t<decltype(order.Ids)>::value_type;
    const mcx::VoxelDecoder<IdType> decoder(static_cast<std::uint64_t>(view.Dimensions[0]),
      static_cast<std::uint64_t>(view.Dimensions[1]));
    auto cellOf = [&](IdType id)
    {
      std::uint64_t voxel[3];
      decoder.Decode(id, voxel[0], voxel[1], voxel[2]);
      const double p[3] = { static_cast<double>(voxel[0]), static_cast<double>(voxel[1]),
        static_cast<double>(voxel[2]) };
      double fx, fy, f, inverseDepth;
      mcx::ViewCell where;
      if (!binner.Locate(p, fx, fy, f, inverseDepth) || !(fx >= 0 && fx < geometry.Size[0]) ||
        !(fy >= 0 && fy < geometry.Size[1]))
      {
        where.Cell = pixels;
        return where;
      }
      where.Cell = static_cast<std::int64_t>(fx) + static_cast<std::int64_t>(fy) * geometry.Size[0];
      where.Position = mcx::PositionInPixel(fx, fy);
      return where;
    };
    return order.Build(mcx::SMPExecutor(), view.IdPointer<IdType>(), view.LevelOffsets,
      view.NumberOfLevels, std::move(binFirstLevel), cells, cellOf, progress);
  };
  if (!(view.WideIds ? sort(sorted->Wide) : sort(sorted->Narrow)))
  {
    completed = false;
    return nullptr;
  }
  this->KeptViewOrder = std::move(sorted);
  return this->KeptViewOrder.get();
}

int vtkMCXPointSampler::RequestEveryVoxel(vtkImageData* input, vtkPolyData* output)
{
  this->KeptPoints = nullptr;
  this->KeptViewOrder.reset();
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
  const vtkIdType largest = (vtkIdType(1) << vtkMCXTypes::MaximumPointCloudExponent) - 1;
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
  const bool centres = this->Deposit == vtkMCXTypes::FOOTPRINT;
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
  os << indent << "NumberOfOrderingBins: " << this->NumberOfOrderingBins << "\n";
  os << indent << "ControlVariate: " << (this->ControlVariate ? "On" : "Off") << "\n";
  os << indent << "OrderingView: ";
  if (this->Ordering)
  {
    const mcx::ProjectionGeometry& g = this->Ordering->Geometry;
    os << (g.Perspective ? "perspective" : "parallel") << ", " << g.Size[0] << " x " << g.Size[1]
       << " pixels, looking along (" << g.W[0] << ", " << g.W[1] << ", " << g.W[2] << ")\n";
  }
  else
  {
    os << "(none)\n";
  }
  os << indent << "KeptViewOrder: "
     << (this->KeptViewOrder ? static_cast<vtkIdType>(this->KeptViewOrder->Narrow.Ids.size() +
                                 this->KeptViewOrder->Wide.Ids.size())
                             : 0)
     << " voxels\n";
}
