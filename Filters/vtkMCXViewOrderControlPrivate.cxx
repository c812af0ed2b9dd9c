#include "vtkMCXViewOrderControlPrivate.h"

#include "mcxControlImage.h"
#include "mcxPixelBinner.h"
#include "mcxRandom.h"
#include "mcxSampleAccumulator.h"
#include "vtkMCXBatchedForPrivate.h"
#include "vtkMCXCloudDeposit.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXSMPExecutor.h"

#include "vtkAlgorithm.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

namespace vtkMCXViewOrderControl
{
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
  // The order's cells: the pixels of the view it was sorted for, and one
  // off its image (not those of `geometry`, when the view has turned since).
  const std::int64_t cells =
    (static_cast<std::int64_t>(order.KeyStarts.size()) - 1) / std::max<std::int64_t>(bins, 1);
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

template bool ProjectBins<std::uint32_t>(vtkAlgorithm*, const mcx::IndexView&,
  const mcx::ViewOrder<std::uint32_t>&, const mcx::ProjectionGeometry&, mcx::Kernel, double,
  vtkTypeUInt64, double, double, std::vector<double>&, std::vector<double>&);
template bool ProjectBins<std::uint64_t>(vtkAlgorithm*, const mcx::IndexView&,
  const mcx::ViewOrder<std::uint64_t>&, const mcx::ProjectionGeometry&, mcx::Kernel, double,
  vtkTypeUInt64, double, double, std::vector<double>&, std::vector<double>&);
}
