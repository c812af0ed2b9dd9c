#include "vtkMCXDistributed.h"

#include "vtkMCXIndexView.h"

#include "vtkCommunicator.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cstring>

namespace mcx
{

namespace
{
// 128-bit sums travel as three 48-bit limbs in 64-bit words (the top one 32
// bits): up to 2^16 processes add without a carry leaving its word, and MPI
// may cut the buffer anywhere (a plain SUM of independent words).
constexpr int LimbBits = 48;
constexpr std::uint64_t LimbMask = (std::uint64_t(1) << LimbBits) - 1;
constexpr int LimbsPerSum = 3;
}

bool IsDistributed(vtkMultiProcessController* controller)
{
  return controller && controller->GetNumberOfProcesses() > 1;
}

void ZSlabExtent(const int whole[6], int piece, int pieces, int slab[6])
{
  // Whole slices, as even as they divide; never shared between pieces (VTK's
  // extent translator splits cells, so its point extents share a slice, and
  // it turns to another axis when z has too few).
  const long long slices = static_cast<long long>(whole[5]) - whole[4] + 1;
  std::copy(whole, whole + 6, slab);
  slab[4] = static_cast<int>(whole[4] + slices * piece / pieces);
  slab[5] = static_cast<int>(whole[4] + slices * (piece + 1) / pieces - 1);
}

bool RequestZSlab(vtkMultiProcessController* controller, vtkInformation* inInfo)
{
  if (!IsDistributed(controller) || !inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    return false;
  }
  int whole[6], slab[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  ZSlabExtent(whole, controller->GetLocalProcessId(), controller->GetNumberOfProcesses(), slab);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), slab, 6);
  return true;
}

void EmptyOutputElsewhere(vtkImageData* output, vtkInformation* outInfo)
{
  output->Initialize();
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    // The extent the executive compares the next request with.
    output->GetInformation()->Set(vtkDataObject::ALL_PIECES_EXTENT(),
      outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
}

bool NothingRead(vtkImageData* input, vtkInformation* inInfo)
{
  if (input->GetNumberOfPoints() > 0 || !inInfo ||
    !inInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    return false;
  }
  int asked[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), asked);
  return asked[0] <= asked[1] && asked[2] <= asked[3] && asked[4] <= asked[5];
}

bool NothingDescribed(vtkInformation* inInfo)
{
  if (!inInfo || !inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    return true;
  }
  int whole[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  return whole[1] < whole[0] || whole[3] < whole[2] || whole[5] < whole[4];
}

std::string FirstErrorOfAll(vtkMultiProcessController* controller, const std::string& error)
{
  if (!IsDistributed(controller))
  {
    return error;
  }
  constexpr vtkIdType Width = 512; // a message is one line
  const int processes = controller->GetNumberOfProcesses();
  std::vector<char> mine(Width, 0), all(static_cast<std::size_t>(Width) * processes, 0);
  std::memcpy(mine.data(), error.data(), std::min<std::size_t>(error.size(), Width - 1));
  controller->AllGather(mine.data(), all.data(), Width);
  // The same message from every process (an error they all met, or one
  // already agreed on) is told as it is.
  bool same = true;
  for (int p = 1; p < processes && same; ++p)
  {
    same = std::equal(all.begin(), all.begin() + Width, all.begin() + p * Width);
  }
  if (same)
  {
    return std::string(all.data(), strnlen(all.data(), Width));
  }
  for (int p = 0; p < processes; ++p)
  {
    const char* text = all.data() + static_cast<std::size_t>(p) * Width;
    if (text[0] != '\0')
    {
      return "process " + std::to_string(p) + " of " + std::to_string(processes) + ": " +
        std::string(text, strnlen(text, Width));
    }
  }
  return std::string();
}

void SumExactly(vtkMultiProcessController* controller, std::vector<FixedSum>& values)
{
  if (!IsDistributed(controller))
  {
    return;
  }
  std::vector<unsigned long long> limbs(values.size() * LimbsPerSum), sums(limbs.size());
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const std::uint64_t low = LowHalf(values[i]), high = HighHalf(values[i]);
    limbs[LimbsPerSum * i] = low & LimbMask;
    limbs[LimbsPerSum * i + 1] = ((low >> LimbBits) | (high << (64 - LimbBits))) & LimbMask;
    limbs[LimbsPerSum * i + 2] = high >> (2 * LimbBits - 64);
  }
  controller->AllReduce(
    limbs.data(), sums.data(), static_cast<vtkIdType>(limbs.size()), vtkCommunicator::SUM_OP);
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    FixedSum v = 0;
    for (int l = LimbsPerSum - 1; l >= 0; --l)
    {
      v = (v << LimbBits) + FixedSum(static_cast<std::uint64_t>(sums[LimbsPerSum * i + l]));
    }
    values[i] = v;
  }
}

std::string GatherLevels(vtkMultiProcessController* controller, const int wholeExtent[6],
  IndexView& view, DistributedLevels& levels)
{
  const int processes = controller->GetNumberOfProcesses();
  const int rank = controller->GetLocalProcessId();

  // The union of the level values: every process's list, merged.
  const vtkIdType mine = static_cast<vtkIdType>(view.NumberOfLevels);
  std::vector<vtkIdType> counts(static_cast<std::size_t>(processes));
  controller->AllGather(&mine, counts.data(), 1);
  std::vector<vtkIdType> starts(static_cast<std::size_t>(processes) + 1, 0);
  for (int p = 0; p < processes; ++p)
  {
    starts[p + 1] = starts[p] + counts[p];
  }
  std::vector<double> all(static_cast<std::size_t>(starts[processes]));
  std::vector<double> own(view.LevelValues, view.LevelValues + view.NumberOfLevels);
  controller->AllGatherV(own.data(), all.data(), mine, counts.data(), starts.data());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  levels.LevelValues = all;
  const std::size_t global = all.size();

  // This piece's counts per global level; the whole volume's by a sum, its
  // rank offsets by summing the counts of the processes before it.
  std::vector<long long> local(global, 0);
  for (std::int64_t l = 0; l < view.NumberOfLevels; ++l)
  {
    const std::size_t g = static_cast<std::size_t>(
      std::lower_bound(all.begin(), all.end(), view.LevelValues[l]) - all.begin());
    local[g] = view.LevelOffsets[l + 1] - view.LevelOffsets[l];
  }
  std::vector<long long> everyone(global * static_cast<std::size_t>(processes));
  controller->AllGather(local.data(), everyone.data(), static_cast<vtkIdType>(global));
  levels.LevelOffsets.assign(global + 1, 0);
  levels.PieceOffsets.assign(global + 1, 0);
  levels.PieceFirstRank.assign(global, 0);
  for (std::size_t g = 0; g < global; ++g)
  {
    long long total = 0, before = 0;
    for (int p = 0; p < processes; ++p)
    {
      const long long n = everyone[static_cast<std::size_t>(p) * global + g];
      before += p < rank ? n : 0;
      total += n;
    }
    levels.LevelOffsets[g + 1] = levels.LevelOffsets[g] + total;
    levels.PieceOffsets[g + 1] = levels.PieceOffsets[g] + local[g];
    levels.PieceFirstRank[g] = before;
  }

  // The pieces must be the z-slabs, in rank order, for the ids of a level to
  // follow the rank order (an index given as data, not through the
  // pipeline, is the whole volume on every process).
  int slab[6];
  ZSlabExtent(wholeExtent, rank, processes, slab);
  const bool empty = slab[5] < slab[4];
  if (empty ? view.NumberOfLevels > 0 : !std::equal(slab, slab + 6, view.Extent))
  {
    return "the index is not this process's z-slab of the volume (connect the index with "
           "SetInputConnection, so that its consumer asks for the slab)";
  }
  if (processes > 65536)
  {
    return "more than 65536 processes (the image sums are exchanged in 48-bit parts)";
  }
  for (int a = 0; a < 3; ++a)
  {
    view.PieceStart[a] = empty ? 0 : static_cast<std::uint64_t>(slab[2 * a] - wholeExtent[2 * a]);
  }
  std::copy(wholeExtent, wholeExtent + 6, view.Extent);
  view.LevelValues = levels.LevelValues.data();
  view.LevelOffsets = levels.LevelOffsets.data();
  view.NumberOfLevels = static_cast<std::int64_t>(global);
  view.PieceOffsets = levels.PieceOffsets.data();
  view.PieceFirstRank = levels.PieceFirstRank.data();
  return std::string();
}

} // namespace mcx
