#include "vtkMCXDensityIndex.h"

#include "mcxCountingSort.h"
#include "mcxFixedPoint.h"
#include "mcxHugePageAllocator.h"
#include "vtkMCXAgreeingExecutive.h"
#include "vtkMCXDistributed.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXMemoryCheck.h"
#include "vtkMCXSMPExecutor.h"

#include "vtkCellData.h"
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
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt64Array.h"
#include "vtkTypeUInt32Array.h"
#include "vtkTypeUInt64Array.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <new>
#include <string>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkMCXDensityIndex);
vtkCxxSetObjectMacro(vtkMCXDensityIndex, Controller, vtkMultiProcessController);

namespace
{
// Integer data with a value range up to this size is binned directly;
// wider ranges are binned through the sorted list of distinct values.
constexpr long long DenseIntegerBinLimit = 1LL << 24;
// A voxel's offset from its float bin's start in fixed point: 2^50 steps per
// bin width (within a few units of the double's own resolution), biased by
// 2^52 (offsets down to minus 4 widths, from rounding at the bin's edges,
// stay positive; the biased value is below 2^53, an exact integer), so that
// sums of up to 2^74 voxels stay exact in 128 bits.
constexpr double FloatLevelFraction = 1125899906842624.0;
constexpr double FloatLevelBias = 4.0 * FloatLevelFraction;

struct IndexResult
{
  std::vector<double> LevelValues;
  std::vector<std::int64_t> LevelBins; // the bin each level came from
  std::vector<std::int64_t> LevelOffsets;
  vtkSmartPointer<vtkDataArray> SortedIds;
  std::int64_t NonFinite = 0;
  double BinWidth = 0.0;
  std::string Error; // why the index could not be made (agreed among processes), or ""
};

template <typename T>
struct ValueRange
{
  T Min;
  T Max;
  std::int64_t Finite = 0;
  bool AllIntegers = true; // every finite value is a whole number
};

template <typename T>
bool IsFiniteValue(T v)
{
  if (std::is_floating_point<T>::value)
  {
    return std::isfinite(static_cast<double>(v));
  }
  return true;
}

// Deterministic chunked min/max of the finite values.
template <typename T>
ValueRange<T> ComputeRange(const T* values, std::int64_t n)
{
  const std::int64_t chunk = 1 << 18;
  const std::int64_t chunks = std::max<std::int64_t>(1, (n + chunk - 1) / chunk);
  std::vector<ValueRange<T>> parts(static_cast<std::size_t>(chunks),
    ValueRange<T>{ std::numeric_limits<T>::max(), std::numeric_limits<T>::lowest(), 0, true });
  vtkSMPTools::For(0, chunks, 1,
    [&](std::int64_t c0, std::int64_t c1)
    {
      for (std::int64_t c = c0; c < c1; ++c)
      {
        ValueRange<T>& r = parts[static_cast<std::size_t>(c)];
        const std::int64_t end = std::min(n, (c + 1) * chunk);
        for (std::int64_t i = c * chunk; i < end; ++i)
        {
          const T v = values[i];
          if (IsFiniteValue(v))
          {
            r.Min = std::min(r.Min, v);
            r.Max = std::max(r.Max, v);
            ++r.Finite;
            if (std::is_floating_point<T>::value)
            {
              r.AllIntegers =
                r.AllIntegers && std::floor(static_cast<double>(v)) == static_cast<double>(v);
            }
          }
        }
      }
    });
  ValueRange<T> total = parts[0];
  for (std::size_t c = 1; c < parts.size(); ++c)
  {
    total.Min = std::min(total.Min, parts[c].Min);
    total.Max = std::max(total.Max, parts[c].Max);
    total.Finite += parts[c].Finite;
    total.AllIntegers = total.AllIntegers && parts[c].AllIntegers;
  }
  return total;
}

// The range of the whole volume when it is cut into pieces (one per process):
// every piece bins alike, so a level is the same value everywhere.
template <typename T>
void AgreeOnRange(vtkMultiProcessController* controller, ValueRange<T>& range)
{
  if (!mcx::IsDistributed(controller))
  {
    return;
  }
  // Reduced in a type that holds every value of T exactly: double for
  // floating-point data, 64-bit integers of T's signedness otherwise. An
  // empty piece offers the type's extremes, which lose every comparison.
  using Wide = typename std::conditional<std::is_floating_point<T>::value, double,
    typename std::conditional<std::is_signed<T>::value, long long, unsigned long long>::type>::type;
  const Wide low =
    range.Finite > 0 ? static_cast<Wide>(range.Min) : std::numeric_limits<Wide>::max();
  const Wide high =
    range.Finite > 0 ? static_cast<Wide>(range.Max) : std::numeric_limits<Wide>::lowest();
  const long long finite = range.Finite;
  const int integers = range.AllIntegers ? 1 : 0;
  Wide lowest = 0, highest = 0;
  long long finiteTotal = 0;
  int allIntegers = 0;
  controller->AllReduce(&low, &lowest, 1, vtkCommunicator::MIN_OP);
  controller->AllReduce(&high, &highest, 1, vtkCommunicator::MAX_OP);
  controller->AllReduce(&finite, &finiteTotal, 1, vtkCommunicator::SUM_OP);
  controller->AllReduce(&integers, &allIntegers, 1, vtkCommunicator::MIN_OP);
  range.Finite = finiteTotal;
  range.AllIntegers = allIntegers == 1;
  if (finiteTotal > 0)
  {
    range.Min = static_cast<T>(lowest);
    range.Max = static_cast<T>(highest);
  }
}

// The sorted ids of a large volume on huge pages where the system offers
// them (mcxHugePageAllocator.h): the sort writes them through a cursor per
// level and the samples read them far apart, one 4 KiB page each under
// 2^24 samples of a 400 M-voxel CT; their page faults were a fifth of the
// index's time there.
template <typename IdType, typename ArrayType>
void AllocateOnHugePages(ArrayType* ids, std::int64_t count)
{
#if defined(__linux__)
  using Allocator = mcx::HugePageAllocator<IdType>;
  const std::size_t n = static_cast<std::size_t>(count);
  if (n >= Allocator::HugeFrom / sizeof(IdType))
  {
    // The allocator takes arrays of this size from posix_memalign: free() releases them.
    ids->SetArray(reinterpret_cast<typename ArrayType::ValueType*>(Allocator().allocate(n)), count,
      0, ArrayType::VTK_DATA_ARRAY_FREE);
    return;
  }
#endif
  ids->SetNumberOfValues(count);
}

template <typename IdType, typename BinFunction>
void SortIntoLevels(std::int64_t n, std::int64_t numberOfBins, std::int64_t numberKept,
  const BinFunction& binOf, const std::function<double(std::int64_t)>& binValue,
  IndexResult& result)
{
  using ArrayType = typename std::conditional<std::is_same<IdType, std::uint32_t>::value,
    vtkTypeUInt32Array, vtkTypeUInt64Array>::type;
  vtkNew<ArrayType> ids;
  ids->SetName(vtkMCXTypes::SortedVoxelIdsName());
  AllocateOnHugePages<IdType>(ids.GetPointer(), numberKept);
  std::vector<std::int64_t> binOffsets;
  result.NonFinite = mcx::CountingSortByBin<IdType>(mcx::SMPExecutor(), n, numberOfBins, binOf,
    binOffsets, reinterpret_cast<IdType*>(ids->GetPointer(0)));
  result.SortedIds = ids;
  // Keep the non-empty bins only.
  result.LevelOffsets.push_back(0);
  for (std::int64_t b = 0; b < numberOfBins; ++b)
  {
    if (binOffsets[static_cast<std::size_t>(b + 1)] > binOffsets[static_cast<std::size_t>(b)])
    {
      result.LevelValues.push_back(binValue(b));
      result.LevelBins.push_back(b);
      result.LevelOffsets.push_back(binOffsets[static_cast<std::size_t>(b + 1)]);
    }
  }
}

template <typename IdType, typename T>
void BuildIndex(const T* values, std::int64_t n, int floatLevels,
  vtkMultiProcessController* controller, IndexResult& result)
{
  ValueRange<T> range = ComputeRange(values, n);
  const std::int64_t finiteHere = range.Finite;
  AgreeOnRange(controller, range);
  if (range.Finite == 0)
  {
    SortIntoLevels<IdType>(
      n, 0, 0, [](std::int64_t) { return std::int64_t(-1); }, [](std::int64_t) { return 0.0; },
      result);
    return;
  }
  const bool wholeNumbers = range.AllIntegers &&
    static_cast<double>(range.Max) - static_cast<double>(range.Min) < DenseIntegerBinLimit;
  if (std::is_floating_point<T>::value && wholeNumbers)
  {
    // Floating-point data holding whole numbers (CT stored as float) is exact.
    const double minimum = static_cast<double>(range.Min);
    SortIntoLevels<IdType>(
      n, static_cast<std::int64_t>(static_cast<double>(range.Max) - minimum) + 1, finiteHere,
      [=](std::int64_t id) -> std::int64_t
      {
        const double v = static_cast<double>(values[id]);
        return std::isfinite(v) ? static_cast<std::int64_t>(v - minimum) : -1;
      },
      [=](std::int64_t b) { return minimum + static_cast<double>(b); }, result);
    return;
  }
  if (std::is_floating_point<T>::value)
  {
    // Halved operands keep the range finite even for data near the double limits.
    const double lo = 0.5 * static_cast<double>(range.Min);
    const double hi = 0.5 * static_cast<double>(range.Max);
    const double scale = hi > lo ? floatLevels / (hi - lo) : 0.0;
    const std::int64_t last = floatLevels - 1;
    result.BinWidth = hi > lo ? 2.0 * (hi - lo) / floatLevels : 0.0;
    // A level stands for the mean of its voxels' values, from exact
    // fixed-point sums of their offsets from the bin's start (so that pieces
    // of the volume add up to the same mean), and is their value when they
    // are all equal.
    std::vector<mcx::FixedSum> sums;
    std::vector<long long> counts;
    std::vector<double> lowest, highest;
    try
    {
      SortIntoLevels<IdType>(
        n, floatLevels, finiteHere,
        [=](std::int64_t id) -> std::int64_t
        {
          const double v = static_cast<double>(values[id]);
          if (!std::isfinite(v))
          {
            return -1;
          }
          const std::int64_t b = static_cast<std::int64_t>((0.5 * v - lo) * scale);
          return std::min(b, last);
        },
        [](std::int64_t) { return 0.0; }, result);
      sums.assign(static_cast<std::size_t>(floatLevels), mcx::FixedSum(0));
      counts.assign(static_cast<std::size_t>(floatLevels), 0);
      lowest.assign(static_cast<std::size_t>(floatLevels), range.Max);
      highest.assign(static_cast<std::size_t>(floatLevels), range.Min);
    }
    catch (const std::bad_alloc&)
    {
      result.Error = "Out of memory indexing " + std::to_string(n) + " voxels";
    }
    // Before the sums are exchanged: all go on, or all stop.
    result.Error = mcx::FirstErrorOfAll(controller, result.Error);
    if (!result.Error.empty())
    {
      return;
    }
    const double width = result.BinWidth;
    auto binStart = [=](std::int64_t bin) { return 2.0 * (lo + static_cast<double>(bin) / scale); };
    const IdType* ids = static_cast<const IdType*>(result.SortedIds->GetVoidPointer(0));
    const std::int64_t levels = static_cast<std::int64_t>(result.LevelValues.size());
    vtkSMPTools::For(0, levels,
      [&](std::int64_t l0, std::int64_t l1)
      {
        for (std::int64_t l = l0; l < l1; ++l)
        {
          const std::int64_t bin = result.LevelBins[static_cast<std::size_t>(l)];
          const std::int64_t begin = result.LevelOffsets[static_cast<std::size_t>(l)];
          const std::int64_t end = result.LevelOffsets[static_cast<std::size_t>(l + 1)];
          mcx::FixedSum sum = 0;
          double& low = lowest[static_cast<std::size_t>(bin)];
          double& high = highest[static_cast<std::size_t>(bin)];
          for (std::int64_t i = begin; i < end; ++i)
          {
            const double v = static_cast<double>(values[ids[i]]);
            low = std::min(low, v);
            high = std::max(high, v);
            const double offset = (v - binStart(bin)) / width * FloatLevelFraction + FloatLevelBias;
            sum += mcx::FixedSum(static_cast<std::uint64_t>(
              std::llround(std::min(2.0 * FloatLevelBias, std::max(0.0, offset)))));
          }
          sums[static_cast<std::size_t>(bin)] = sum;
          counts[static_cast<std::size_t>(bin)] = end - begin;
        }
      });
    if (mcx::IsDistributed(controller))
    {
      mcx::SumExactly(controller, sums);
      std::vector<long long> total(counts.size());
      controller->AllReduce(counts.data(), total.data(), static_cast<vtkIdType>(counts.size()),
        vtkCommunicator::SUM_OP);
      counts.swap(total);
      std::vector<double> reduced(lowest.size());
      controller->AllReduce(lowest.data(), reduced.data(), static_cast<vtkIdType>(lowest.size()),
        vtkCommunicator::MIN_OP);
      lowest.swap(reduced);
      controller->AllReduce(highest.data(), reduced.data(), static_cast<vtkIdType>(highest.size()),
        vtkCommunicator::MAX_OP);
      highest.swap(reduced);
    }
    for (std::int64_t l = 0; l < levels; ++l)
    {
      const std::size_t bin =
        static_cast<std::size_t>(result.LevelBins[static_cast<std::size_t>(l)]);
      const double offset =
        (mcx::ToDouble(sums[bin]) / static_cast<double>(counts[bin]) - FloatLevelBias) /
        FloatLevelFraction * width;
      const double mean = lowest[bin] == highest[bin]
        ? lowest[bin]
        : binStart(static_cast<std::int64_t>(bin)) + offset;
      result.LevelValues[static_cast<std::size_t>(l)] =
        std::min(highest[bin], std::max(lowest[bin], mean));
    }
    return;
  }
  // Differences of integers in [Min, Max] fit 64 unsigned bits exactly
  // (modular arithmetic), whatever T is.
  const std::uint64_t minimum = static_cast<std::uint64_t>(range.Min);
  const std::uint64_t span = static_cast<std::uint64_t>(range.Max) - minimum;
  if (span < static_cast<std::uint64_t>(DenseIntegerBinLimit))
  {
    SortIntoLevels<IdType>(
      n, static_cast<std::int64_t>(span) + 1, n,
      [=](std::int64_t id)
      { return static_cast<std::int64_t>(static_cast<std::uint64_t>(values[id]) - minimum); },
      [=](std::int64_t b)
      { return static_cast<double>(static_cast<T>(minimum + static_cast<std::uint64_t>(b))); },
      result);
    return;
  }
  // Sparse integer values: one bin per distinct value, found by binary search.
  std::vector<T> distinct(values, values + n);
  vtkSMPTools::Sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  const T* first = distinct.data();
  const T* last = distinct.data() + distinct.size();
  SortIntoLevels<IdType>(
    n, static_cast<std::int64_t>(distinct.size()), n,
    [=](std::int64_t id)
    { return static_cast<std::int64_t>(std::lower_bound(first, last, values[id]) - first); },
    [=](std::int64_t b) { return static_cast<double>(first[b]); }, result);
}
} // namespace

vtkMCXDensityIndex::vtkMCXDensityIndex()
{
  this->SetProgressText("X-Ray Density Index"); // what progress bars show (ParaView's label)
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkMCXDensityIndex::~vtkMCXDensityIndex()
{
  this->SetController(nullptr);
}

bool vtkMCXDensityIndex::NeedsWideIds(long long numberOfVoxels)
{
  return numberOfVoxels > static_cast<long long>(std::numeric_limits<std::uint32_t>::max());
}

namespace
{
constexpr const char* UnreadablePiece =
  "The volume's piece could not be read (see the reader's error in that process's output)";
}

vtkExecutive* vtkMCXDensityIndex::CreateDefaultExecutive()
{
  return vtkMCXAgreeingExecutive::New();
}

int vtkMCXDensityIndex::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Distributed under an agreeing executive (the index's own, or the
  // plugin's in ParaView), which marks the request, a reader that failed to
  // describe this process's piece (or described no voxels: ParaView's file
  // series reader of a missing file) fails the index on every process, here,
  // before anything downstream meets the others with what it cannot know.
  if (request->Has(vtkMCXAgreeingExecutive::UPSTREAM_FAILED()) &&
    mcx::IsDistributed(this->Controller))
  {
    const bool unreadable = vtkMCXAgreeingExecutive::UpstreamFailed(request) ||
      mcx::NothingDescribed(inputVector[0]->GetInformationObject(0));
    const std::string problem =
      mcx::FirstErrorOfAll(this->Controller, unreadable ? UnreadablePiece : "");
    if (!problem.empty())
    {
      // The same (empty) volume on every process, whatever each one's input
      // said: a later request then goes the same way everywhere.
      const int empty[6] = { 0, -1, 0, -1, 0, -1 };
      outputVector->GetInformationObject(0)->Set(
        vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
      vtkErrorMacro(<< problem << ".");
      return 0;
    }
  }
  if (!this->Superclass::RequestInformation(request, inputVector, outputVector))
  {
    return 0;
  }
  // VTK 9.1 passes extent, origin and spacing downstream but not the
  // direction; projectors frame their image with all four.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (inInfo->Has(vtkDataObject::DIRECTION()))
  {
    outInfo->CopyEntry(inInfo, vtkDataObject::DIRECTION());
  }
  return 1;
}

int vtkMCXDensityIndex::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // The extent asked of the index (a process's z-slab of a distributed
  // volume), else the whole volume. An empty slab (more processes than
  // slices) asks the input for one slice, the least it can deliver.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    return 1; // an input that failed to describe itself; RequestData says so
  }
  int extent[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    int asked[6];
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), asked);
    if (asked[1] >= asked[0] && asked[3] >= asked[2] && asked[5] >= asked[4])
    {
      std::copy(asked, asked + 6, extent);
    }
    else
    {
      extent[5] = extent[4];
    }
  }
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent, 6);
  // The extent is the request: a piece request passed down with it (ParaView
  // asks every filter for piece r of N) would make the reader deliver its
  // own block of the volume instead.
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  return 1;
}

namespace
{
// The part of the input the output was asked for (its update extent): the
// input itself when it is exactly that, else a copy of that part's scalars
// (empty for an empty extent); null when the input does not hold it.
vtkSmartPointer<vtkImageData> PieceOf(
  vtkImageData* input, vtkDataArray*& scalars, vtkInformation* outInfo)
{
  int extent[6];
  input->GetExtent(extent);
  if (!outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    return input;
  }
  int asked[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), asked);
  if (std::equal(asked, asked + 6, extent))
  {
    return input;
  }
  auto piece = vtkSmartPointer<vtkImageData>::New();
  piece->CopyStructure(input);
  piece->SetExtent(asked);
  auto values = vtkSmartPointer<vtkDataArray>::Take(scalars->NewInstance());
  values->SetName(scalars->GetName());
  const bool empty = asked[1] < asked[0] || asked[3] < asked[2] || asked[5] < asked[4];
  if (!empty)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (asked[2 * a] < extent[2 * a] || asked[2 * a + 1] > extent[2 * a + 1])
      {
        return nullptr; // the input does not hold the piece
      }
    }
    // The piece's rows, copied out of the input's.
    const vtkIdType row = asked[1] - asked[0] + 1;
    values->SetNumberOfTuples(row * (asked[3] - asked[2] + 1) * (asked[5] - asked[4] + 1));
    vtkIdType target = 0;
    for (int z = asked[4]; z <= asked[5]; ++z)
    {
      for (int y = asked[2]; y <= asked[3]; ++y)
      {
        int ijk[3] = { asked[0], y, z };
        const vtkIdType source = input->ComputePointId(ijk);
        values->InsertTuples(target, row, source, scalars);
        target += row;
      }
    }
  }
  piece->GetPointData()->SetScalars(values);
  scalars = values;
  return piece;
}
}

namespace
{
// Why the scalars cannot be indexed, or "".
std::string ScalarsProblem(vtkDataArray* scalars, vtkIdType points)
{
  if (!scalars)
  {
    return "The input image has no point scalars to index";
  }
  if (scalars->GetNumberOfComponents() != 1)
  {
    return std::string("The input scalars '") + (scalars->GetName() ? scalars->GetName() : "") +
      "' have " + std::to_string(scalars->GetNumberOfComponents()) +
      " components; the index needs one";
  }
  if (scalars->GetNumberOfTuples() != points)
  {
    return "The input scalars do not cover the image's " + std::to_string(points) + " points";
  }
  switch (scalars->GetDataType())
  {
    vtkTemplateMacro(return std::string());
    default:
      return std::string("Unsupported scalar type ") + scalars->GetDataTypeAsString();
  }
}
}

int vtkMCXDensityIndex::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkMultiProcessController* controller =
    mcx::IsDistributed(this->Controller) ? this->Controller : nullptr;
  const bool inputFailed = vtkMCXAgreeingExecutive::UpstreamFailed(request);
  if (!output || (!input && !controller))
  {
    vtkErrorMacro("Missing input or output image data.");
    return 0;
  }
  output->Initialize(); // a failure below leaves no stale index of an earlier input

  // Checks first; distributed, all processes fail together on the first
  // process's problem (none waits for one that gave up).
  std::string problem;
  vtkDataArray* scalars = nullptr;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inputFailed || !input ||
    (controller && (mcx::NothingRead(input, inInfo) || mcx::NothingDescribed(inInfo))))
  {
    problem = UnreadablePiece;
  }
  else
  {
    // An empty array name (ParaView's Density before the input has data to
    // choose from, as in pvpython) means the active point scalars.
    vtkInformation* chosen = this->GetInputArrayInformation(0);
    const bool unnamed = chosen && chosen->Has(vtkDataObject::FIELD_NAME()) &&
      !*chosen->Get(vtkDataObject::FIELD_NAME());
    scalars =
      unnamed ? input->GetPointData()->GetScalars() : this->GetInputArrayToProcess(0, inputVector);
    problem = ScalarsProblem(scalars, input->GetNumberOfPoints());
  }
  vtkSmartPointer<vtkImageData> piece;
  if (problem.empty())
  {
    piece = PieceOf(input, scalars, outputVector->GetInformationObject(0));
    problem = piece ? std::string() : "The input does not hold the extent asked of the index";
  }
  const vtkIdType n = piece ? piece->GetNumberOfPoints() : 0;
  if (problem.empty() && n <= 0 && !controller)
  {
    problem = "The input image has no voxels";
  }
  const bool wide = this->AlwaysUseWideIds || vtkMCXDensityIndex::NeedsWideIds(n);
  if (problem.empty())
  {
    // The sorted ids, the sort's copy of them and a level per voxel.
    const double bytesPerVoxel = 2.0 * (wide ? 8 : 4) + 4;
    problem = mcx::MemoryProblem(
      bytesPerVoxel * static_cast<double>(n), "An index of " + std::to_string(n) + " voxels");
  }
  problem = mcx::FirstErrorOfAll(controller, problem);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem << ".");
    return 0;
  }

  this->UpdateProgress(0.0);
  IndexResult result;
  try
  {
    switch (scalars->GetDataType())
    {
      vtkTemplateMacro({
        const VTK_TT* values = static_cast<const VTK_TT*>(scalars->GetVoidPointer(0));
        if (wide)
        {
          BuildIndex<std::uint64_t>(values, n, this->NumberOfFloatLevels, controller, result);
        }
        else
        {
          BuildIndex<std::uint32_t>(values, n, this->NumberOfFloatLevels, controller, result);
        }
      });
    }
  }
  catch (const std::bad_alloc&)
  {
    result.Error = "Out of memory indexing " + std::to_string(n) + " voxels";
  }
  // Every process reaches this point, with or without an index.
  result.Error = mcx::FirstErrorOfAll(controller, result.Error);
  if (!result.Error.empty())
  {
    vtkErrorMacro(<< result.Error << ".");
    return 0;
  }
  this->UpdateProgress(0.9);

  output->CopyStructure(piece);
  output->GetPointData()->Initialize();
  output->GetCellData()->Initialize();
  vtkFieldData* fd = output->GetFieldData();
  fd->Initialize();

  vtkNew<vtkDoubleArray> levelValues;
  levelValues->SetName(vtkMCXTypes::LevelValuesName());
  levelValues->SetNumberOfValues(static_cast<vtkIdType>(result.LevelValues.size()));
  std::copy(result.LevelValues.begin(), result.LevelValues.end(), levelValues->GetPointer(0));
  vtkNew<vtkTypeInt64Array> levelOffsets;
  levelOffsets->SetName(vtkMCXTypes::LevelOffsetsName());
  levelOffsets->SetNumberOfValues(static_cast<vtkIdType>(result.LevelOffsets.size()));
  std::copy(result.LevelOffsets.begin(), result.LevelOffsets.end(), levelOffsets->GetPointer(0));
  fd->AddArray(levelValues);
  fd->AddArray(levelOffsets);
  fd->AddArray(result.SortedIds);
  mcx::AddFieldValue(fd, vtkMCXTypes::NonFiniteVoxelCountName(), static_cast<long long>(result.NonFinite));
  mcx::AddFieldValue(fd, vtkMCXTypes::LevelBinWidthName(), result.BinWidth);

  if (result.NonFinite > 0)
  {
    vtkWarningMacro(<< result.NonFinite << " NaN or infinite voxels were left out of the index.");
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkMCXDensityIndex::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfFloatLevels: " << this->NumberOfFloatLevels << "\n";
  os << indent << "AlwaysUseWideIds: " << this->AlwaysUseWideIds << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
}
