#include "vtkMCXAggregateIndex.h"

#include "vtkMCXDensityIndex.h"
#include "vtkMCXDistributed.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXMemoryCheck.h"

#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt64Array.h"
#include "vtkTypeUInt32Array.h"
#include "vtkTypeUInt64Array.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMCXAggregateIndex);
vtkCxxSetObjectMacro(vtkMCXAggregateIndex, Controller, vtkMultiProcessController);

namespace
{
// Ids travel in messages of this many values (MPI counts are ints; 256 or
// 512 KB, so that the bundled CT's slabs already take several).
constexpr vtkIdType MessageValues = vtkIdType(1) << 16;
constexpr int IdsTag = 52641;

// Where one piece's ids go in the whole index: level by level, after the
// ids of the same level held by the processes before it (lower slabs, so the
// ids of a level stay ascending).
struct PiecePlacement
{
  const long long* PieceOffsets;        // the piece's ids per global level, levels + 1
  const std::int64_t* LevelOffsets;     // the whole index's
  const std::vector<long long>* Before; // ids of each level held by earlier pieces
  std::size_t Level = 0;                // where the next id goes
  long long InLevel = 0;

  // Stores `count` ids that follow the ones stored so far.
  template <typename Transfer, typename Stored>
  void Store(const Transfer* ids, vtkIdType count, Stored* out)
  {
    while (count > 0)
    {
      const long long levelSize = this->PieceOffsets[this->Level + 1] - this->PieceOffsets[this->Level];
      if (this->InLevel == levelSize)
      {
        ++this->Level;
        this->InLevel = 0;
        continue;
      }
      const vtkIdType run = static_cast<vtkIdType>(std::min<long long>(levelSize - this->InLevel, count));
      Stored* target =
        out + this->LevelOffsets[this->Level] + (*this->Before)[this->Level] + this->InLevel;
      std::copy(ids, ids + run, target);
      ids += run;
      count -= run;
      this->InLevel += run;
    }
  }
};

// This process's ids from `first` on, `count` of them, in the whole
// volume's numbering: a z-slab's ids move by the slices below it.
template <typename Local, typename Transfer>
void ToWholeIds(const Local* ids, vtkIdType first, vtkIdType count, std::uint64_t shift,
  std::vector<Transfer>& out)
{
  out.resize(static_cast<std::size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    out[static_cast<std::size_t>(i)] = static_cast<Transfer>(ids[first + i] + shift);
  }
}

// Sends this process's `count` ids to process 0, or (on process 0) stores
// every process's where they belong (`allPieceOffsets`: every process's
// offsets per level, one after the other). Collective.
template <typename Local, typename Transfer, typename Stored>
void TransferIds(vtkMultiProcessController* controller, const Local* ids, vtkIdType count,
  std::uint64_t shift, const std::vector<long long>& allPieceOffsets,
  const std::int64_t* levelOffsets, std::size_t levels, Stored* out)
{
  const int processes = controller->GetNumberOfProcesses();
  const int rank = controller->GetLocalProcessId();
  std::vector<Transfer> buffer;
  if (rank != 0)
  {
    for (vtkIdType first = 0; first < count; first += MessageValues)
    {
      const vtkIdType n = std::min(MessageValues, count - first);
      ToWholeIds(ids, first, n, shift, buffer);
      controller->Send(buffer.data(), n, 0, IdsTag);
    }
    return;
  }
  // Sized after construction: GCC 12 takes the sized constructor here for a
  // delete of a non-heap pointer (a false -Wfree-nonheap-object).
  std::vector<long long> before;
  before.resize(levels, 0);
  for (int p = 0; p < processes; ++p)
  {
    const long long* pieceOffsets = allPieceOffsets.data() + static_cast<std::size_t>(p) * (levels + 1);
    PiecePlacement placement{ pieceOffsets, levelOffsets, &before };
    const vtkIdType pieceCount = static_cast<vtkIdType>(pieceOffsets[levels]);
    for (vtkIdType first = 0; first < pieceCount; first += MessageValues)
    {
      const vtkIdType n = std::min(MessageValues, pieceCount - first);
      if (p == 0)
      {
        ToWholeIds(ids, first, n, shift, buffer);
      }
      else
      {
        buffer.resize(static_cast<std::size_t>(n));
        controller->Receive(buffer.data(), n, p, IdsTag);
      }
      placement.Store(buffer.data(), n, out);
    }
    for (std::size_t l = 0; l < levels; ++l)
    {
      before[l] += pieceOffsets[l + 1] - pieceOffsets[l];
    }
  }
}

long long FieldInteger(vtkImageData* index, const char* name)
{
  vtkDataArray* array = vtkDataArray::SafeDownCast(index->GetFieldData()->GetAbstractArray(name));
  return array && array->GetNumberOfTuples() > 0 ? static_cast<long long>(array->GetTuple1(0)) : 0;
}

double FieldDouble(vtkImageData* index, const char* name)
{
  vtkDataArray* array = vtkDataArray::SafeDownCast(index->GetFieldData()->GetAbstractArray(name));
  return array && array->GetNumberOfTuples() > 0 ? array->GetTuple1(0) : 0.0;
}
}

vtkMCXAggregateIndex::vtkMCXAggregateIndex()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkMCXAggregateIndex::~vtkMCXAggregateIndex()
{
  this->SetController(nullptr);
}

int vtkMCXAggregateIndex::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Under several processes, this process's z-slab of the index.
  if (mcx::RequestZSlab(this->Controller, inputVector[0]->GetInformationObject(0)))
  {
    return 1;
  }
  return this->Superclass::RequestUpdateExtent(request, inputVector, outputVector);
}

int vtkMCXAggregateIndex::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("Missing input or output image data.");
    return 0;
  }
  if (!mcx::IsDistributed(this->Controller))
  {
    output->ShallowCopy(input);
    return 1;
  }
  output->Initialize();
  vtkMultiProcessController* controller = this->Controller;
  const int rank = controller->GetLocalProcessId();
  int whole[6];
  inputVector[0]->GetInformationObject(0)->Get(
    vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);

  // The levels of all slabs, and where each slab's ids go.
  mcx::IndexView view;
  mcx::DistributedLevels levels;
  std::string problem = mcx::FirstErrorOfAll(controller, view.Read(input));
  if (problem.empty())
  {
    problem = mcx::FirstErrorOfAll(controller, mcx::GatherLevels(controller, whole, view, levels));
  }
  if (!problem.empty())
  {
    vtkErrorMacro("Cannot aggregate the index: " << problem << ".");
    return 0;
  }
  const std::size_t levelCount = levels.LevelValues.size();
  std::vector<long long> pieceOffsets(levels.PieceOffsets.begin(), levels.PieceOffsets.end());
  std::vector<long long> allPieceOffsets(
    rank == 0 ? pieceOffsets.size() * controller->GetNumberOfProcesses() : 0);
  controller->Gather(pieceOffsets.data(), allPieceOffsets.data(),
    static_cast<vtkIdType>(pieceOffsets.size()), 0);

  // 64-bit ids when a slab has them or the whole volume needs them, as one
  // process's index of the whole volume would.
  const long long voxels = static_cast<long long>(whole[1] - whole[0] + 1) *
    (whole[3] - whole[2] + 1) * (whole[5] - whole[4] + 1);
  const int wideHere = view.WideIds ? 1 : 0;
  int wideAnywhere = 0;
  controller->AllReduce(&wideHere, &wideAnywhere, 1, vtkCommunicator::MAX_OP);
  const bool wide = wideAnywhere != 0 || vtkMCXDensityIndex::NeedsWideIds(voxels);

  // Process 0 makes room for the whole index first; all agree on it.
  const long long total = levels.LevelOffsets.back();
  vtkSmartPointer<vtkDataArray> ids;
  if (rank == 0)
  {
    problem = mcx::MemoryProblem(static_cast<double>(total) * (wide ? 8 : 4),
      "The whole index of " + std::to_string(total) + " voxels");
    if (problem.empty())
    {
      ids = wide ? vtkSmartPointer<vtkDataArray>(vtkSmartPointer<vtkTypeUInt64Array>::New())
                 : vtkSmartPointer<vtkDataArray>(vtkSmartPointer<vtkTypeUInt32Array>::New());
      ids->SetName(vtkMCXTypes::SortedVoxelIdsName());
      if (!ids->SetNumberOfValues(static_cast<vtkIdType>(total)))
      {
        problem = "Out of memory for the whole index of " + std::to_string(total) + " voxels";
      }
    }
  }
  problem = mcx::FirstErrorOfAll(controller, problem);
  if (!problem.empty())
  {
    vtkErrorMacro("Cannot aggregate the index: " << problem << ".");
    return 0;
  }

  this->UpdateProgress(0.1);
  const std::uint64_t shift = view.PieceStart[2] * static_cast<std::uint64_t>(view.Dimensions[0]) *
    static_cast<std::uint64_t>(view.Dimensions[1]);
  const std::int64_t* levelOffsets = levels.LevelOffsets.data();
  const vtkIdType count = static_cast<vtkIdType>(pieceOffsets.back());
  auto transfer = [&](auto* stored, auto transferType)
  {
    using Transfer = decltype(transferType);
    if (view.WideIds)
    {
      TransferIds<std::uint64_t, Transfer>(controller, view.IdPointer<std::uint64_t>(), count, shift,
        allPieceOffsets, levelOffsets, levelCount, stored);
    }
    else
    {
      TransferIds<std::uint32_t, Transfer>(controller, view.IdPointer<std::uint32_t>(), count, shift,
        allPieceOffsets, levelOffsets, levelCount, stored);
    }
  };
  if (wide)
  {
    auto* stored = rank == 0 ? vtkTypeUInt64Array::SafeDownCast(ids)->GetPointer(0) : nullptr;
    transfer(stored, static_cast<unsigned long long>(0));
  }
  else
  {
    auto* stored = rank == 0 ? vtkTypeUInt32Array::SafeDownCast(ids)->GetPointer(0) : nullptr;
    transfer(stored, static_cast<unsigned int>(0));
  }

  // The counts of left-out voxels add; the bin width is the same everywhere.
  const long long nonFinite = FieldInteger(input, vtkMCXTypes::NonFiniteVoxelCountName());
  long long nonFiniteTotal = 0;
  controller->Reduce(&nonFinite, &nonFiniteTotal, 1, vtkCommunicator::SUM_OP, 0);
  const double binWidth = FieldDouble(input, vtkMCXTypes::LevelBinWidthName());
  double widestBin = 0.0;
  controller->Reduce(&binWidth, &widestBin, 1, vtkCommunicator::MAX_OP, 0);
  if (rank != 0)
  {
    mcx::EmptyOutputElsewhere(output, outputVector->GetInformationObject(0));
    this->UpdateProgress(1.0);
    return 1;
  }

  output->CopyStructure(input);
  output->SetExtent(whole);
  vtkFieldData* fd = output->GetFieldData();
  vtkNew<vtkDoubleArray> levelValues;
  levelValues->SetName(vtkMCXTypes::LevelValuesName());
  levelValues->SetNumberOfValues(static_cast<vtkIdType>(levelCount));
  std::copy(levels.LevelValues.begin(), levels.LevelValues.end(), levelValues->GetPointer(0));
  vtkNew<vtkTypeInt64Array> wholeOffsets;
  wholeOffsets->SetName(vtkMCXTypes::LevelOffsetsName());
  wholeOffsets->SetNumberOfValues(static_cast<vtkIdType>(levelCount + 1));
  std::copy(levels.LevelOffsets.begin(), levels.LevelOffsets.end(), wholeOffsets->GetPointer(0));
  fd->AddArray(levelValues);
  fd->AddArray(wholeOffsets);
  fd->AddArray(ids);
  mcx::AddFieldValue(fd, vtkMCXTypes::NonFiniteVoxelCountName(), nonFiniteTotal);
  mcx::AddFieldValue(fd, vtkMCXTypes::LevelBinWidthName(), widestBin);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkMCXAggregateIndex::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
}
