#include "vtkMCXDensityIndex.h"

#include "mcxCountingSort.h"
#include "vtkMCXIndexViewPrivate.h"
#include "vtkMCXMemoryCheckPrivate.h"
#include "vtkMCXSMPExecutorPrivate.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
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
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkMCXDensityIndex);

namespace
{
// Integer data with a value range up to this size is binned directly;
// wider ranges are binned through the sorted list of distinct values.
constexpr long long DenseIntegerBinLimit = 1LL << 24;

struct IndexResult
{
  std::vector<double> LevelValues;
  std::vector<std::int64_t> LevelOffsets;
  vtkSmartPointer<vtkDataArray> SortedIds;
  std::int64_t NonFinite = 0;
  double BinWidth = 0.0;
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

template <typename IdType, typename BinFunction>
void SortIntoLevels(std::int64_t n, std::int64_t numberOfBins, std::int64_t numberKept,
  const BinFunction& binOf, const std::function<double(std::int64_t)>& binValue,
  IndexResult& result)
{
  using ArrayType = typename std::conditional<std::is_same<IdType, std::uint32_t>::value,
    vtkTypeUInt32Array, vtkTypeUInt64Array>::type;
  vtkNew<ArrayType> ids;
  ids->SetName(vtkMCXDensityIndex::SortedVoxelIdsName());
  ids->SetNumberOfValues(numberKept);
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
      result.LevelOffsets.push_back(binOffsets[static_cast<std::size_t>(b + 1)]);
    }
  }
}

template <typename IdType, typename T>
void BuildIndex(const T* values, std::int64_t n, int floatLevels, IndexResult& result)
{
  const ValueRange<T> range = ComputeRange(values, n);
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
      n, static_cast<std::int64_t>(static_cast<double>(range.Max) - minimum) + 1, range.Finite,
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
    SortIntoLevels<IdType>(
      n, floatLevels, range.Finite,
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
    // A level stands for the mean of its voxels' values: exact when they are all equal.
    const IdType* ids = static_cast<const IdType*>(result.SortedIds->GetVoidPointer(0));
    const std::int64_t levels = static_cast<std::int64_t>(result.LevelValues.size());
    vtkSMPTools::For(0, levels,
      [&](std::int64_t l0, std::int64_t l1)
      {
        for (std::int64_t l = l0; l < l1; ++l)
        {
          const std::int64_t begin = result.LevelOffsets[static_cast<std::size_t>(l)];
          const std::int64_t end = result.LevelOffsets[static_cast<std::size_t>(l + 1)];
          double sum = 0.0;
          for (std::int64_t i = begin; i < end; ++i)
          {
            sum += 0.5 * static_cast<double>(values[ids[i]]);
          }
          const double mean = 2.0 * (sum / static_cast<double>(end - begin));
          result.LevelValues[static_cast<std::size_t>(l)] = std::min(
            static_cast<double>(range.Max), std::max(static_cast<double>(range.Min), mean));
        }
      });
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
}

bool vtkMCXDensityIndex::NeedsWideIds(long long numberOfVoxels)
{
  return numberOfVoxels > static_cast<long long>(std::numeric_limits<std::uint32_t>::max());
}

int vtkMCXDensityIndex::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
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
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The index always covers the whole volume.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  return 1;
}

int vtkMCXDensityIndex::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("Missing input or output image data.");
    return 0;
  }
  output->Initialize(); // a failure below leaves no stale index of an earlier input
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector);
  if (!scalars)
  {
    vtkErrorMacro("The input image has no point scalars to index.");
    return 0;
  }
  if (scalars->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("The input scalars '" << (scalars->GetName() ? scalars->GetName() : "")
                                        << "' have " << scalars->GetNumberOfComponents()
                                        << " components; the index needs one.");
    return 0;
  }
  const vtkIdType n = input->GetNumberOfPoints();
  if (scalars->GetNumberOfTuples() != n || n <= 0)
  {
    vtkErrorMacro("The input scalars do not cover the image's " << n << " points.");
    return 0;
  }

  this->UpdateProgress(0.0);
  IndexResult result;
  const bool wide = this->AlwaysUseWideIds || vtkMCXDensityIndex::NeedsWideIds(n);
  // The sorted ids, the sort's copy of them and a level per voxel.
  const double bytesPerVoxel = 2.0 * (wide ? 8 : 4) + 4;
  if (!mcx::CheckMemory(this, bytesPerVoxel * static_cast<double>(n),
        "An index of " + std::to_string(n) + " voxels"))
  {
    return 0;
  }
  try
  {
    switch (scalars->GetDataType())
    {
      vtkTemplateMacro({
        const VTK_TT* values = static_cast<const VTK_TT*>(scalars->GetVoidPointer(0));
        if (wide)
        {
          BuildIndex<std::uint64_t>(values, n, this->NumberOfFloatLevels, result);
        }
        else
        {
          BuildIndex<std::uint32_t>(values, n, this->NumberOfFloatLevels, result);
        }
      });
      default:
        vtkErrorMacro("Unsupported scalar type " << scalars->GetDataTypeAsString() << ".");
        return 0;
    }
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro("Out of memory indexing " << n << " voxels.");
    return 0;
  }
  this->UpdateProgress(0.9);

  output->CopyStructure(input);
  output->GetPointData()->Initialize();
  output->GetCellData()->Initialize();
  vtkFieldData* fd = output->GetFieldData();
  fd->Initialize();

  vtkNew<vtkDoubleArray> levelValues;
  levelValues->SetName(LevelValuesName());
  levelValues->SetNumberOfValues(static_cast<vtkIdType>(result.LevelValues.size()));
  std::copy(result.LevelValues.begin(), result.LevelValues.end(), levelValues->GetPointer(0));
  vtkNew<vtkTypeInt64Array> levelOffsets;
  levelOffsets->SetName(LevelOffsetsName());
  levelOffsets->SetNumberOfValues(static_cast<vtkIdType>(result.LevelOffsets.size()));
  std::copy(result.LevelOffsets.begin(), result.LevelOffsets.end(), levelOffsets->GetPointer(0));
  fd->AddArray(levelValues);
  fd->AddArray(levelOffsets);
  fd->AddArray(result.SortedIds);
  mcx::AddFieldValue(fd, NonFiniteVoxelCountName(), static_cast<long long>(result.NonFinite));
  mcx::AddFieldValue(fd, LevelBinWidthName(), result.BinWidth);

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
}
