#include "vtkMCXViewOrderedSamplingPrivate.h"

#include "mcxControlImage.h"
#include "mcxGridPixelPositions.h"
#include "mcxPixelBinner.h"
#include "mcxProjectionGeometry.h"
#include "mcxRandom.h"
#include "mcxSampleAccumulator.h"
#include "mcxViewOrder.h"
#include "vtkMCXBatchedForPrivate.h"
#include "vtkMCXCameraGeometry.h"
#include "vtkMCXCloudDeposit.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXMemoryCheck.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXSMPExecutor.h"
#include "vtkMCXSampledCloudPrivate.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace
{
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
    mcx::StoreInWorld(origin, matrix, p, points + 3 * k);
    weights[k] = static_cast<float>(weight);
  };
  return mcx::BatchedFor(
    self, source.NumberOfStorageItems(), 0.55, 1.0,
    [&](std::uint64_t b, std::uint64_t e) { source.GenerateForStorage(b, e, store); }, 1);
}

// Each bin's voxels of `order` projected, footprints of `kernel` in
// `geometry` (voxel coordinates, as the sort located them): bins x pixels
// sums in the accumulator's fixed-point units (2^32 a whole voxel), the
// bins' images of the control (mcxControlImage.h). Without a stride every
// voxel once, rounding at random from a stream of their own, the same for
// every seed, so a new seed keeps them, and no differences; with one (> 2)
// about one voxel in `stride` of each (bin, cell) run (mcx::ControlPicks),
// drawn and rounded from `seed`, each carrying its interval, and
// `differences` gets each bin's image of the even picks less that of the
// odd ones. Progress runs from progressBegin to progressEnd; false when
// aborted.
template <typename IdType>
bool ProjectBins(vtkAlgorithm* self, const mcx::IndexView& view,
  const mcx::ViewOrder<IdType>& order, const mcx::ProjectionGeometry& geometry, mcx::Kernel kernel,
  double stride, vtkTypeUInt64 seed, double progressBegin, double progressEnd,
  std::vector<double>& images, std::vector<double>& differences)
{
  const bool sampled = stride > 1.0;
  double origin[3], matrix[9];
  view.SourceToWorld(origin, matrix);
  mcx::DepositSettings settings; // samples in voxel coordinates: the identity VoxelMatrix
  settings.Mode = mcx::Deposit::Footprint;
  settings.Reconstruction = kernel;
  // A stream of the control's own, apart from the cloud's footprints.
  settings.Seed = sampled ? seed ^ 0x3C6EF372FE94F82Bull : 0;
  if (geometry.Perspective)
  {
    double corners[24];
    mcx::ComputeSupportCorners(
      view.Extent, view.Origin, view.Spacing, view.Direction, mcx::KernelRadius(kernel), corners);
    mcx::SupportDepthRange(geometry, corners, settings.Depths);
  }
  mcx::SampleAccumulator<mcx::SMPExecutor> accumulator;
  accumulator.Reset(geometry, origin, matrix, std::vector<double>(), settings);
  const std::int64_t voxels = order.BinOffsets.back();
  // The even picks are the first half: k < voxels.
  accumulator.SetSplit(sampled ? static_cast<std::uint64_t>(voxels) : 0);
  const std::size_t pixels = accumulator.NumberOfPixels();
  const std::int64_t bins = order.NumberOfBins();
  // The order's cells (not the pixels of `geometry`, when the view has turned since).
  const std::int64_t cells = order.NumberOfCells();
  const mcx::VoxelDecoder<IdType> decoder(
    static_cast<std::uint64_t>(view.Dimensions[0]), static_cast<std::uint64_t>(view.Dimensions[1]));
  const std::uint64_t seedKey = mcx::SeedKey(seed ^ 0xBB67AE8584CAA73Bull);
  // Each bin's work (its voxels, or its picks), which the progress follows.
  std::vector<double> work(static_cast<std::size_t>(bins + 1), 0.0);
  for (std::int64_t b = 0; b < bins; ++b)
  {
    const std::size_t i = static_cast<std::size_t>(b);
    work[i + 1] = work[i] +
      (sampled ? static_cast<double>(
                   mcx::ControlPicks(order.KeyStarts.data() + b * cells, b, cells, stride, seedKey)
                     .Count())
               : static_cast<double>(order.BinOffsets[i + 1] - order.BinOffsets[i]));
  }
  const double span = (progressEnd - progressBegin) / std::max(1.0, work.back());
  images.assign(static_cast<std::size_t>(bins) * pixels, 0.0);
  differences.assign(sampled ? images.size() : 0, 0.0);
  std::vector<mcx::FixedSum> all(pixels), firstHalf(pixels);
  for (std::int64_t b = 0; b < bins; ++b)
  {
    const std::int64_t first = order.BinOffsets[static_cast<std::size_t>(b)];
    const std::int64_t last = order.BinOffsets[static_cast<std::size_t>(b + 1)];
    const std::unique_ptr<mcx::ControlPicks> picks(sampled
        ? new mcx::ControlPicks(order.KeyStarts.data() + b * cells, b, cells, stride, seedKey)
        : nullptr);
    const bool completed = mcx::BatchedFor(self,
      static_cast<std::uint64_t>(picks ? picks->Count() : last - first),
      progressBegin + span * work[static_cast<std::size_t>(b)],
      progressBegin + span * work[static_cast<std::size_t>(b + 1)],
      [&](std::uint64_t begin, std::uint64_t end)
      {
        const auto image = accumulator.Local();
        mcx::FootprintBatch footprints(image);
        auto add = [&](std::int64_t entry, double weight, bool firstHalf)
        {
          std::uint64_t voxel[3];
          decoder.Decode(order.Ids[static_cast<std::size_t>(entry)], voxel[0], voxel[1], voxel[2]);
          const double p[3] = { static_cast<double>(voxel[0]), static_cast<double>(voxel[1]),
            static_cast<double>(voxel[2]) };
          // Every voxel once comes as a first half: its stream keys are its entries.
          const std::int64_t k = firstHalf ? entry : voxels + entry;
          footprints.Add(static_cast<std::uint64_t>(k), p, weight);
        };
        if (picks)
        {
          picks->Visit(static_cast<std::int64_t>(begin), static_cast<std::int64_t>(end), add);
        }
        else
        {
          for (std::uint64_t i = begin; i < end; ++i)
          {
            add(first + static_cast<std::int64_t>(i), 1.0, true);
          }
        }
        footprints.Flush();
      });
    if (!completed)
    {
      return false;
    }
    std::fill(all.begin(), all.end(), mcx::FixedSum(0));
    std::fill(firstHalf.begin(), firstHalf.end(), mcx::FixedSum(0));
    accumulator.Collect(all.data(), firstHalf.data());
    double* image = images.data() + static_cast<std::size_t>(b) * pixels;
    for (std::size_t p = 0; p < pixels; ++p)
    {
      image[p] = mcx::ToDouble(all[p]);
    }
    if (sampled)
    {
      double* difference = differences.data() + static_cast<std::size_t>(b) * pixels;
      for (std::size_t p = 0; p < pixels; ++p)
      {
        difference[p] = 2.0 * mcx::ToDouble(firstHalf[p]) - image[p];
      }
    }
  }
  return true;
}

// The control image (line integrals) of the TF whose weight on each bin is
// binMeans[b]: the bins' images weighed by it, scaled so that it carries
// the cloud's integral as the cloud does, and its variance summed over the
// pixels, from the bins' differences (none: 0). Empty when no bin has
// weight.
std::vector<double> ControlImage(const std::vector<double>& binImages,
  const std::vector<double>& binDifferences, const std::vector<double>& binMeans,
  const std::vector<std::int64_t>& binOffsets, double integral,
  const mcx::ProjectionGeometry& geometry, double& variance)
{
  variance = 0.0;
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
  auto weigh = [&](const std::vector<double>& images)
  {
    std::vector<double> sum(pixels, 0.0);
    for (std::size_t b = 0; b < bins; ++b)
    {
      const double weight = binMeans[b] * scale;
      if (weight == 0.0)
      {
        continue;
      }
      const double* image = images.data() + b * pixels;
      for (std::size_t p = 0; p < pixels; ++p)
      {
        sum[p] += weight * image[p];
      }
    }
    return sum;
  };
  if (!binDifferences.empty())
  {
    // The halves' sums differ by d: the variance of their sum is about d^2.
    for (const double d : weigh(binDifferences))
    {
      variance += d * d;
    }
  }
  return weigh(binImages);
}
}

// The largest view to order by: the projector's largest image.
const double MaximumOrderingPixels = 4294967296.0;

namespace
{
// mcx::SameFraming's tolerance for a kept order: a twentieth of the image.
const double ReframeTolerance = 0.05;

// The world centre of the index's volume.
void VolumeCentre(const mcx::IndexView& view, double centre[3])
{
  double corners[24];
  mcx::ComputeSupportCorners(view.Extent, view.Origin, view.Spacing, view.Direction, 0.0, corners);
  for (int k = 0; k < 3; ++k)
  {
    centre[k] = 0.0;
    for (int c = 0; c < 8; ++c)
    {
      centre[k] += corners[3 * c + k] / 8.0;
    }
  }
}
}

// SetOrderingView's copy of the camera's geometry.
struct vtkMCXViewOrderedSampling::OrderingView
{
  mcx::ProjectionGeometry Geometry;
};

// A view order and what it was sorted for.
struct vtkMCXViewOrderedSampling::SortedView
{
  vtkDataArray* Ids = nullptr; // the index's sorted ids: compared only, never dereferenced
  vtkMTimeType IdsTime = 0;
  double World[12] = { 0 }; // the index's source-to-world origin and matrix
  mcx::ProjectionGeometry Geometry;
  int Bins = 0;
  mcx::ViewOrder<std::uint32_t> Narrow; // the index's ids are 32-bit
  mcx::ViewOrder<std::uint64_t> Wide;   // or 64-bit (WideIds)
  // The control's bins' images and differences (ProjectBins), and the view
  // (the ordering view, which may have turned since the sort), the kernel,
  // the stride and the seed they were projected with; empty until a
  // controlled cloud needs them.
  std::vector<double> BinImages;
  std::vector<double> BinDifferences;
  mcx::ProjectionGeometry BinGeometry;
  int BinKernel = -1;
  double BinStride = 0.0;
  vtkTypeInt64 BinSeed = 0;

  // What the arrays recycled from the previous order (ViewOrder::Recycle,
  // of one width) hold already for an order of `voxels` and `cells`.
  double RecycledBytes(std::int64_t voxels, std::int64_t cells) const
  {
    return this->Narrow.RecyclableBytes(voxels, cells) + this->Wide.RecyclableBytes(voxels, cells);
  }

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

  // Whether this order serves `view` in `geometry`: the same index and bins,
  // sorted for the same view or (reorderAngle above 0) for one turned by at
  // most that many degrees that frames the volume's centre alike.
  bool Fits(const mcx::IndexView& view, const mcx::ProjectionGeometry& geometry, int bins,
    double reorderAngle) const
  {
    SortedView wanted;
    wanted.Describe(view, geometry, bins);
    if (!(this->Ids == wanted.Ids && this->IdsTime == wanted.IdsTime &&
          std::equal(this->World, this->World + 12, wanted.World) && this->Bins == wanted.Bins))
    {
      return false;
    }
    if (mcx::SameGeometry(this->Geometry, geometry))
    {
      return true;
    }
    double centre[3];
    VolumeCentre(view, centre);
    return reorderAngle > 0 && mcx::TurnDegrees(this->Geometry, geometry) <= reorderAngle &&
      mcx::SameFraming(this->Geometry, geometry, centre, ReframeTolerance);
  }

  // The cells of the order: the pixels of its view and one off its image.
  std::int64_t CellsOf(bool wideIds) const
  {
    return wideIds ? this->Wide.NumberOfCells() : this->Narrow.NumberOfCells();
  }
};

vtkMCXViewOrderedSampling::vtkMCXViewOrderedSampling() = default;

vtkMCXViewOrderedSampling::~vtkMCXViewOrderedSampling() = default;

bool vtkMCXViewOrderedSampling::SetView(vtkObject* self, vtkCamera* camera, int width, int height)
{
  std::unique_ptr<OrderingView> ordering;
  // The sort keys of a larger view (bins x pixels) would pass 64 bits.
  if (static_cast<double>(width) * static_cast<double>(height) > MaximumOrderingPixels)
  {
    vtkErrorWithObjectMacro(self,
      "Cannot order by a view of " << width << " x " << height
                                   << " pixels: at most 2^32 pixels (65536 x 65536).");
    return false;
  }
  if (camera && width > 0 && height > 0)
  {
    ordering.reset(new OrderingView);
    const int size[2] = { width, height };
    const std::string problem = mcx::GeometryFromCamera(camera, size, 0.0, 0.0, ordering->Geometry);
    if (!problem.empty())
    {
      vtkErrorWithObjectMacro(self, "Cannot order by this view: " << problem);
      return false;
    }
  }
  if (!ordering && !this->Ordering)
  {
    return false;
  }
  if (ordering && this->Ordering && mcx::SameGeometry(ordering->Geometry, this->Ordering->Geometry))
  {
    return false;
  }
  this->Ordering = std::move(ordering);
  return true;
}

bool vtkMCXViewOrderedSampling::HasView() const
{
  return this->Ordering != nullptr;
}

void vtkMCXViewOrderedSampling::ForgetOrder()
{
  this->KeptViewOrder.reset();
}

vtkMCXViewOrderedSampling::Outcome vtkMCXViewOrderedSampling::Sample(vtkMCXPointSampler* sampler,
  const mcx::IndexView& view, double integral, const PointAllocator& allocate, Cloud& cloud)
{
  if (!this->Ordering)
  {
    vtkErrorWithObjectMacro(sampler,
      "Cannot sample in view order: no view to order by (call "
      "SetOrderingView(camera, width, height) first).");
    return Outcome::Failed;
  }
  if (view.PieceOffsets)
  {
    vtkErrorWithObjectMacro(sampler,
      "Cannot sample in view order: the index is one piece of a distributed volume, "
      "and the view order needs the whole volume in one process (use HYBRID).");
    return Outcome::Failed;
  }
  std::vector<double> weights = view.EvaluateTransferFunction(sampler->GetTransferFunction());
  std::vector<char> kept;
  view.KeepLevels(weights, kept); // the weights as the table takes them
  bool completed = true;
  SortedView* sorted = this->ViewOrderFor(sampler, view, completed);
  if (!sorted)
  {
    return completed ? Outcome::Failed : Outcome::Aborted;
  }
  if (sampler->GetControlVariate() && !this->ProjectBinsFor(sampler, view, *sorted, completed))
  {
    return completed ? Outcome::Failed : Outcome::Aborted;
  }
  const bool allocated = view.WideIds ? this->Generate(sampler, view, sorted->Wide, weights,
                                          integral, *sorted, allocate, cloud, completed)
                                      : this->Generate(sampler, view, sorted->Narrow, weights,
                                          integral, *sorted, allocate, cloud, completed);
  if (!allocated)
  {
    return Outcome::Failed;
  }
  return completed ? Outcome::Made : Outcome::Aborted;
}

template <typename Order>
bool vtkMCXViewOrderedSampling::Generate(vtkMCXPointSampler* sampler, const mcx::IndexView& view,
  const Order& order, const std::vector<double>& weights, double integral, const SortedView& sorted,
  const PointAllocator& allocate, Cloud& cloud, bool& completed)
{
  std::vector<double> binMeans, levelRatios;
  order.Weights(weights.data(), view.LevelOffsets, binMeans, levelRatios);
  const mcx::TransferTable binTable =
    mcx::BuildTransferTable(binMeans.data(), order.BinOffsets.data(), order.NumberOfBins());
  const unsigned m = binTable.IsEmpty() ? 0u : static_cast<unsigned>(sampler->GetSampleExponent());
  cloud.Exponent = m;
  if (sampler->GetControlVariate() && m > 0)
  {
    cloud.Control = ControlImage(sorted.BinImages, sorted.BinDifferences, binMeans,
      order.BinOffsets, integral, sorted.BinGeometry, cloud.ControlVariance);
    cloud.ControlView = sorted.BinGeometry;
  }
  const int pointType =
    sampler->GetOutputPointsPrecision() == vtkAlgorithm::DOUBLE_PRECISION ? VTK_DOUBLE : VTK_FLOAT;
  const vtkIdType count = static_cast<vtkIdType>(mcx::SampleCount(m));
  cloud.Points = allocate(pointType, count);
  if (!cloud.Points)
  {
    return false;
  }
  cloud.Weights = vtkSmartPointer<vtkFloatArray>::New();
  cloud.Weights->SetName(vtkMCXTypes::PointWeightName());
  cloud.Weights->SetNumberOfValues(count);
  const auto kernel = static_cast<mcx::Kernel>(sampler->GetKernel());
  const bool centres = sampler->GetDeposit() == vtkMCXTypes::FOOTPRINT;
  const auto seed = static_cast<vtkTypeUInt64>(sampler->GetSeed());
  void* raw = cloud.Points->GetVoidPointer(0);
  float* w = cloud.Weights->GetPointer(0);
  completed = count == 0 ||
    (pointType == VTK_DOUBLE
        ? GenerateViewOrderedPoints(sampler, view, order, binTable, levelRatios, kernel, seed, m,
            centres, static_cast<double*>(raw), w)
        : GenerateViewOrderedPoints(sampler, view, order, binTable, levelRatios, kernel, seed, m,
            centres, static_cast<float*>(raw), w));
  return true;
}

void vtkMCXViewOrderedSampling::WriteControl(const Cloud& cloud, vtkFieldData* fd)
{
  if (cloud.Control.empty())
  {
    return;
  }
  vtkNew<vtkDoubleArray> image;
  image->SetName(vtkMCXTypes::ControlImageName());
  image->SetNumberOfValues(static_cast<vtkIdType>(cloud.Control.size()));
  std::copy(cloud.Control.begin(), cloud.Control.end(), image->GetPointer(0));
  fd->AddArray(image);
  vtkNew<vtkDoubleArray> controlView;
  controlView->SetName(vtkMCXTypes::ControlViewName());
  controlView->SetNumberOfValues(mcx::GeometryValueCount);
  mcx::GeometryToValues(cloud.ControlView, controlView->GetPointer(0));
  fd->AddArray(controlView);
  vtkNew<vtkDoubleArray> variance;
  variance->SetName(vtkMCXTypes::ControlVarianceName());
  variance->SetNumberOfValues(1);
  variance->SetValue(0, cloud.ControlVariance);
  fd->AddArray(variance);
  fd->AddArray(mcx::ControlPointsOf(cloud.Points));
}
bool vtkMCXViewOrderedSampling::ProjectBinsFor(
  vtkMCXPointSampler* sampler, const mcx::IndexView& view, SortedView& sorted, bool& completed)
{
  completed = true;
  // About ControlVoxelsPerPoint voxels per point of the cloud, or every
  // one: below two voxels a pick (a stride of 1, "every voxel"), the picks,
  // which take small runs twice, would cost about what every voxel does.
  const std::int64_t voxels = view.LevelOffsets[view.NumberOfLevels];
  const double points = std::max(1.0, std::ldexp(1.0, sampler->GetSampleExponent()) - 1.0);
  double stride = static_cast<double>(voxels) / (sampler->GetControlVoxelsPerPoint() * points);
  const bool sampled = stride > 2.0;
  stride = sampled ? stride : 1.0;
  // The ordering view, whatever view the order was sorted for (ReorderAngle);
  // a copy, which an observer's SetOrderingView cannot pull away.
  const mcx::ProjectionGeometry geometry = this->Ordering->Geometry;
  if (!sorted.BinImages.empty() && mcx::SameGeometry(sorted.BinGeometry, geometry) &&
    sorted.BinKernel == sampler->GetKernel() && sorted.BinStride == stride &&
    (!sampled || sorted.BinSeed == sampler->GetSeed()))
  {
    return true;
  }
  sorted.BinImages = std::vector<double>(); // not held while new ones are made
  sorted.BinDifferences = std::vector<double>();
  const double pixels = static_cast<double>(geometry.Size[0]) * geometry.Size[1];
  const double bins = static_cast<double>(sorted.BinsOf(view.WideIds));
  // The images (8 bytes a bin and pixel, 16 with the differences), the
  // threads' sums (16 a pixel) and their collection (32), and a bin's first
  // picks (8 a cell of the order, whose view may not be this one).
  if (!mcx::CheckMemory(sampler,
        pixels *
            ((sampled ? 16.0 : 8.0) * bins + 16.0 * vtkSMPTools::GetEstimatedNumberOfThreads() +
              32.0) +
          (sampled ? 8.0 * static_cast<double>(sorted.CellsOf(view.WideIds)) : 0.0),
        "The control image's " + std::to_string(static_cast<long long>(bins)) + " bin images"))
  {
    return false;
  }
  const auto kernel = static_cast<mcx::Kernel>(sampler->GetKernel());
  const auto seed = static_cast<vtkTypeUInt64>(sampler->GetSeed());
  std::vector<double> images, differences;
  completed = view.WideIds ? ProjectBins(sampler, view, sorted.Wide, geometry, kernel, stride, seed,
                               0.3, 0.55, images, differences)
                           : ProjectBins(sampler, view, sorted.Narrow, geometry, kernel, stride,
                               seed, 0.3, 0.55, images, differences);
  if (completed)
  {
    sorted.BinImages = std::move(images);
    sorted.BinDifferences = std::move(differences);
    sorted.BinGeometry = geometry;
    sorted.BinKernel = sampler->GetKernel();
    sorted.BinStride = stride;
    sorted.BinSeed = sampler->GetSeed();
  }
  return completed;
}

vtkMCXViewOrderedSampling::SortedView* vtkMCXViewOrderedSampling::ViewOrderFor(
  vtkMCXPointSampler* sampler, const mcx::IndexView& view, bool& completed)
{
  completed = true;
  const mcx::ProjectionGeometry geometry = this->Ordering->Geometry; // a copy, as above
  if (this->KeptViewOrder &&
    this->KeptViewOrder->Fits(
      view, geometry, sampler->GetNumberOfOrderingBins(), sampler->GetReorderAngle()))
  {
    return this->KeptViewOrder.get();
  }
  std::unique_ptr<SortedView> sorted(new SortedView);
  // The kept order is not held while a new one is sorted; its arrays of
  // the id width sorted now are written again (ViewOrder::Recycle).
  if (this->KeptViewOrder)
  {
    if (view.WideIds)
    {
      sorted->Wide.Recycle(std::move(this->KeptViewOrder->Wide));
    }
    else
    {
      sorted->Narrow.Recycle(std::move(this->KeptViewOrder->Narrow));
    }
    this->KeptViewOrder.reset();
  }
  const std::int64_t voxels = view.LevelOffsets[view.NumberOfLevels];
  const std::int64_t pixels = static_cast<std::int64_t>(geometry.Size[0]) * geometry.Size[1];
  const std::int64_t cells = pixels + 1; // the last: voxels off the image
  std::vector<std::int64_t> binFirstLevel = mcx::GroupLevelsIntoBins(
    view.LevelValues, view.NumberOfLevels, sampler->GetNumberOfOrderingBins());
  // The counters alone, in floating point first: their count in 64 bits
  // could wrap.
  if (!mcx::CheckMemory(sampler,
        8.0 * static_cast<double>(binFirstLevel.size() - 1) * static_cast<double>(cells),
        "The view order of " + std::to_string(voxels) + " voxels"))
  {
    return nullptr;
  }
  const std::int64_t bins = static_cast<std::int64_t>(binFirstLevel.size()) - 1;
  const std::int64_t keys = bins * cells;
  const mcx::ViewOrderDigits digits(bins, cells);
  if (!digits.Fit())
  {
    vtkErrorWithObjectMacro(sampler,
      "The view order of " << voxels << " voxels cannot sort " << bins << " bins of " << cells
                           << " cells: use fewer ordering bins or a smaller ordering view.");
    return nullptr;
  }
  const mcx::CountingSortLayout layout = mcx::MakeCountingSortLayout(voxels, digits.HighDigits);
  // The order (id, level), each entry's low digit and position, each
  // voxel's cell and position, the cursors and the keys' starts.
  if (!mcx::CheckMemory(sampler,
        static_cast<double>(voxels) *
            ((view.WideIds ? 8.0 : 4.0) + 2.0 + 4.0 + mcx::ViewOrderDigits::SlotKeyBytes(cells)) -
          sorted->RecycledBytes(voxels, cells) +
          8.0 * static_cast<double>(layout.NumberOfChunks + 1) *
            static_cast<double>(digits.HighDigits) +
          8.0 * static_cast<double>(keys + 1),
        "The view order of " + std::to_string(voxels) + " voxels"))
  {
    return nullptr;
  }
  sorted->Describe(view, geometry, sampler->GetNumberOfOrderingBins());
  double origin[3], matrix[9];
  view.SourceToWorld(origin, matrix);
  const mcx::PixelBinner binner(geometry, origin, matrix);
  const mcx::GridPixelPositions positions(
    binner, view.Dimensions[0], view.Dimensions[1], view.Dimensions[2]);
  auto progress = [sampler](double fraction)
  {
    sampler->UpdateProgress((sampler->GetControlVariate() ? 0.3 : 0.5) * fraction);
    return !sampler->GetAbortExecute();
  };
  auto sort = [&](auto& order)
  {
    using IdType = typename std::decay_t<decltype(order.Ids)>::value_type;
    const mcx::VoxelDecoder<IdType> decoder(static_cast<std::uint64_t>(view.Dimensions[0]),
      static_cast<std::uint64_t>(view.Dimensions[1]));
    auto cellOf = [&](IdType id)
    {
      std::uint64_t i, j, k;
      decoder.Decode(id, i, j, k);
      double fx, fy;
      mcx::ViewCell where;
      if (!positions.PixelPosition(i, j, k, fx, fy) || !(fx >= 0 && fx < geometry.Size[0]) ||
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

void vtkMCXViewOrderedSampling::PrintSelf(std::ostream& os, vtkIndent indent) const
{
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
     << " voxels";
  if (this->KeptViewOrder && this->Ordering)
  {
    os << ", sorted for a view turned "
       << mcx::TurnDegrees(this->KeptViewOrder->Geometry, this->Ordering->Geometry)
       << " degrees from the ordering view";
  }
  os << "\n";
}
