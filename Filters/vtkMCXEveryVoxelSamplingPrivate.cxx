#include "vtkMCXEveryVoxelSamplingPrivate.h"

#include "mcxEveryVoxelOrder.h"
#include "mcxEveryVoxelSource.h"
#include "vtkMCXBatchedForPrivate.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXMemoryCheck.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXSMPExecutor.h"
#include "vtkMCXSampledCloudPrivate.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace
{
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
        mcx::StoreInWorld(origin, matrix, p, points + 3 * k);
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
}

struct vtkMCXEveryVoxelSampling::Cloud
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
    vtkMCXPointSampler* sampler, int pointType)
  {
    this->Ids = view.Ids;
    this->IdsTime = view.Ids->GetMTime();
    view.SourceToWorld(this->World, this->World + 3);
    this->Kept = kept;
    this->PointType = pointType;
    this->Deposit = sampler->GetDeposit();
    this->Kernel = sampler->GetKernel();
    this->Seed = sampler->GetSeed();
  }

  bool Fits(const mcx::IndexView& view, const std::vector<char>& kept, vtkMCXPointSampler* sampler,
    int pointType) const
  {
    Cloud wanted;
    wanted.Describe(view, kept, sampler, pointType);
    return this->Ids == wanted.Ids && this->IdsTime == wanted.IdsTime &&
      std::equal(this->World, this->World + 12, wanted.World) && this->Kept == wanted.Kept &&
      this->PointType == wanted.PointType && this->Deposit == wanted.Deposit &&
      this->Kernel == wanted.Kernel && this->Seed == wanted.Seed;
  }
};

vtkMCXEveryVoxelSampling::vtkMCXEveryVoxelSampling() = default;

vtkMCXEveryVoxelSampling::~vtkMCXEveryVoxelSampling() = default;

void vtkMCXEveryVoxelSampling::Forget()
{
  this->Kept.reset();
}

vtkIdType vtkMCXEveryVoxelSampling::KeptPointCount() const
{
  return this->Kept ? static_cast<vtkIdType>(this->Kept->Levels.size()) : 0;
}

int vtkMCXEveryVoxelSampling::RequestData(
  vtkMCXPointSampler* sampler, vtkImageData* input, vtkPolyData* output)
{
  std::unique_ptr<Cloud> cloud = std::move(this->Kept);
  mcx::IndexView view;
  mcx::TransferTable table;
  double integral = 0.0;
  if (!mcx::PrepareSampling(
        sampler, "sample", input, sampler->GetTransferFunction(), view, table, integral))
  {
    output->Initialize(); // no stale cloud of an earlier request
    return 0;
  }
  std::vector<double> weights = view.EvaluateTransferFunction(sampler->GetTransferFunction());
  std::vector<char> kept;
  const vtkIdType count = static_cast<vtkIdType>(view.KeepLevels(weights, kept));
  const vtkIdType largest = (vtkIdType(1) << vtkMCXTypes::MaximumPointCloudExponent) - 1;
  if (count > largest)
  {
    vtkErrorWithObjectMacro(sampler,
      "Every voxel: " << count << " voxels of non-zero weight exceed the " << largest
                      << " points of the largest cloud; sample them instead.");
    output->Initialize();
    return 0;
  }
  const int pointType =
    sampler->GetOutputPointsPrecision() == vtkAlgorithm::DOUBLE_PRECISION ? VTK_DOUBLE : VTK_FLOAT;
  if (!cloud || !cloud->Fits(view, kept, sampler, pointType))
  {
    cloud.reset(); // not held while a new one is made
    const int made = this->MakeCloud(sampler, view, kept, count, pointType, cloud);
    if (made != 1)
    {
      output->Initialize();
      return made == 0 ? 0 : 1; // an error, or aborted
    }
  }

  output->SetPoints(cloud->Points);
  output->GetPointData()->AddArray(PointWeights(cloud->Levels, weights, table.WeightSum()));
  mcx::WriteCloudFields(sampler, view, integral, count, -1, output->GetFieldData());
  if (sampler->GetReusePoints())
  {
    this->Kept = std::move(cloud);
  }
  return 1;
}

int vtkMCXEveryVoxelSampling::MakeCloud(vtkMCXPointSampler* sampler, const mcx::IndexView& view,
  const std::vector<char>& kept, vtkIdType count, int pointType, std::unique_ptr<Cloud>& cloud)
{
  const double voxels =
    static_cast<double>(view.Dimensions[0]) * view.Dimensions[1] * view.Dimensions[2];
  const double idBytes = view.WideIds ? 8.0 : 4.0;
  if (!mcx::CheckMemory(sampler,
        static_cast<double>(count) *
            (3.0 * (pointType == VTK_DOUBLE ? 8 : 4) + 4 + 4 + 2 * idBytes) +
          4.0 * voxels,
        "A cloud of every voxel's " + std::to_string(count) + " points"))
  {
    return 0;
  }
  cloud.reset(new Cloud);
  cloud->Describe(view, kept, sampler, pointType);
  bool completed = true;
  if (!this->MakePoints(sampler, view, kept, *cloud, completed))
  {
    vtkErrorWithObjectMacro(sampler,
      "Cannot sample every voxel: the index's sorted ids are not distinct voxel ids of its "
      "volume (a damaged index).");
    return 0;
  }
  return completed ? 1 : -1;
}

bool vtkMCXEveryVoxelSampling::MakePoints(vtkMCXPointSampler* sampler, const mcx::IndexView& view,
  const std::vector<char>& kept, Cloud& cloud, bool& completed)
{
  const std::int64_t voxels =
    static_cast<std::int64_t>(view.Dimensions[0]) * view.Dimensions[1] * view.Dimensions[2];
  const auto kernel = static_cast<mcx::Kernel>(sampler->GetKernel());
  const bool centres = sampler->GetDeposit() == vtkMCXTypes::FOOTPRINT;
  const auto seed = static_cast<vtkTypeUInt64>(sampler->GetSeed());
  auto make = [&](auto id)
  {
    using IdType = decltype(id);
    mcx::EveryVoxelOrder<IdType> order;
    if (!order.Build(mcx::SMPExecutor(), view.IdPointer<IdType>(), view.LevelOffsets,
          view.NumberOfLevels, kept, voxels))
    {
      return false;
    }
    sampler->UpdateProgress(0.5);
    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataType(cloud.PointType);
    points->SetNumberOfPoints(static_cast<vtkIdType>(order.Size()));
    void* raw = points->GetVoidPointer(0);
    completed = cloud.PointType == VTK_DOUBLE ? EveryVoxelPositions(sampler, view, order.Ids,
                                                  kernel, centres, seed, static_cast<double*>(raw))
                                              : EveryVoxelPositions(sampler, view, order.Ids,
                                                  kernel, centres, seed, static_cast<float*>(raw));
    cloud.Points = points;
    cloud.Levels = std::move(order.Levels);
    return true;
  };
  return view.WideIds ? make(std::uint64_t(0)) : make(std::uint32_t(0));
}
