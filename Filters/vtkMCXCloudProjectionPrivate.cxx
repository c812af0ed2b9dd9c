#include "vtkMCXCloudProjectionPrivate.h"

#include "vtkMCXBatchedForPrivate.h"
#include "vtkMCXCloudDeposit.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXMemoryCheck.h"
#include "vtkMCXProjectionPrivate.h"
#include "vtkMCXTypes.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <cstdint>
#include <vector>

namespace
{
double FieldValue(vtkFieldData* fd, const char* name, double fallback)
{
  vtkDataArray* array = fd ? fd->GetArray(name) : nullptr;
  return array && array->GetNumberOfTuples() > 0 ? array->GetTuple1(0) : fallback;
}

// Deposits the `count` points (each `weights` times, null: once), in
// parallel on the accumulator; false when aborted.
bool DepositPoints(vtkAlgorithm* self, mcx::Accumulator& accumulator, vtkPoints* points,
  vtkDataArray* weights, std::uint64_t count)
{
  auto deposit = [&](const auto* coordinates)
  {
    return mcx::WithPointWeights(weights,
      [&](const auto* pointWeights)
      {
        return mcx::BatchedFor(self, count, 0.0, 1.0,
          [&](std::uint64_t b, std::uint64_t e)
          { accumulator.DepositRange(coordinates, b, e, pointWeights); });
      });
  };
  return points->GetDataType() == VTK_FLOAT
    ? deposit(static_cast<const float*>(points->GetVoidPointer(0)))
    : deposit(static_cast<const double*>(points->GetVoidPointer(0)));
}

// The weight the points carry, all of them and the first half's (below
// firstHalf), and the sample weight that makes them carry the integral.
void CountCarriedWeight(vtkDataArray* weights, std::uint64_t firstHalf, mcx::Projection& projection)
{
  projection.CarriedWeight = static_cast<double>(projection.Count);
  projection.FirstHalfWeight = static_cast<double>(firstHalf);
  if (weights)
  {
    // Weighted points carry the integral together, whatever their mean
    // weight (as the mapper's prefixes do). Fixed-point sums of consecutive
    // ranges add up exactly: the first half's weight is summed once.
    auto carried = [&](std::uint64_t begin, std::uint64_t end)
    {
      return mcx::WithPointWeights(weights,
        [&](const auto* values)
        { return mcx::PointWeightSum(mcx::SMPExecutor(), values, begin, end); });
    };
    const mcx::FixedSum first = carried(0, firstHalf);
    projection.CarriedWeight =
      mcx::ToDouble(first + carried(firstHalf, projection.Count)) / mcx::FixedOne;
    projection.FirstHalfWeight = mcx::ToDouble(first) / mcx::FixedOne;
    projection.SampleWeight =
      projection.CarriedWeight > 0 ? projection.Integral / projection.CarriedWeight : 0.0;
  }
}
}

namespace mcx
{
bool ProjectCloud(vtkAlgorithm* self, vtkPolyData* cloud, const mcx::ProjectionGeometry& geometry,
  double footprintReach, Projection& projection)
{
  vtkFieldData* fd = cloud->GetFieldData();
  if (!fd || !fd->GetArray(vtkMCXTypes::SampleWeightName()))
  {
    vtkErrorWithObjectMacro(
      self, "The point cloud carries no SampleWeight (make it with vtkMCXPointSampler).");
    return false;
  }
  vtkPoints* points = cloud->GetPoints();
  if (!mcx::CheckPointType(self, points))
  {
    return false;
  }
  bool weightsValid = true;
  vtkDataArray* weights = mcx::CloudPointWeights(self, cloud, weightsValid);
  if (!weightsValid)
  {
    return false;
  }
  projection.SampleWeight = FieldValue(fd, vtkMCXTypes::SampleWeightName(), 0.0);
  projection.Integral = FieldValue(fd, vtkMCXTypes::IntegralName(), 0.0);
  projection.Count = points ? static_cast<std::uint64_t>(points->GetNumberOfPoints()) : 0;

  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  mcx::DepositSettings settings =
    mcx::CloudDepositSettings(cloud, geometry, origin, identity, footprintReach);
  settings.TableMemory = mcx::MemoryBudget(); // beyond: the projector's "Cannot project" error
  Accumulator accumulator;
  accumulator.Reset(geometry, origin, identity, std::vector<double>(), settings);
  projection.FallsAsInverseM = accumulator.ErrorFallsAsInverseM();
  projection.RandomParts = RandomPartsOf(accumulator, settings, footprintReach);
  projection.EveryVoxel = mcx::IsEveryVoxelCloud(cloud);
  projection.Control = mcx::CloudControlImage(cloud, geometry, projection.ControlVariance);
  projection.PixelArea = geometry.BeamCrossSection();
  // The control's two more sums per thread (16 bytes a pixel) and their
  // collection (32), and the control image (8).
  if (!projection.Control.empty() &&
    !mcx::CheckMemory(self,
      static_cast<double>(projection.Control.size()) *
        (16.0 * vtkSMPTools::GetEstimatedNumberOfThreads() + 40.0),
      "The control image's sums"))
  {
    return false;
  }
  accumulator.SetControlled(!projection.Control.empty());
  const std::uint64_t firstHalf = mcx::FirstHalfSize(projection.Count);
  accumulator.SetSplit(firstHalf);
  if (projection.Count > 0)
  {
    projection.Completed = DepositPoints(self, accumulator, points, weights, projection.Count);
  }
  CountCarriedWeight(weights, firstHalf, projection);
  CollectSums(accumulator, projection);
  return true;
}
}
