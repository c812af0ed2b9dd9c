#include "vtkMCXIndexView.h"

#include "vtkMCXDensityIndex.h"
#include "vtkMCXDistributed.h"

#include "mcxProjectionGeometry.h"
#include "vtkAlgorithm.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPoints.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt64Array.h"

#include <cctype>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace mcx
{

template <>
const std::uint32_t* IndexView::IdPointer<std::uint32_t>() const
{
  return static_cast<const std::uint32_t*>(this->Ids->GetVoidPointer(0));
}

template <>
const std::uint64_t* IndexView::IdPointer<std::uint64_t>() const
{
  return static_cast<const std::uint64_t*>(this->Ids->GetVoidPointer(0));
}

std::string IndexView::Read(vtkImageData* index)
{
  if (!index)
  {
    return "no index image";
  }
  vtkFieldData* fd = index->GetFieldData();
  auto* values = vtkDoubleArray::SafeDownCast(fd->GetAbstractArray(vtkMCXTypes::LevelValuesName()));
  auto* offsets = vtkDataArray::SafeDownCast(fd->GetAbstractArray(vtkMCXTypes::LevelOffsetsName()));
  auto* ids = vtkDataArray::SafeDownCast(fd->GetAbstractArray(vtkMCXTypes::SortedVoxelIdsName()));
  if (!values || !offsets || !ids)
  {
    return "the input is not a density index (run vtkMCXDensityIndex first)";
  }
  // Readers and ParaView's transport rebuild arrays by type (a vtkTypeInt64Array
  // may come back as a vtkLongArray), so accept them by type and size.
  const bool signedOffsets = offsets->GetDataTypeSize() == 8 &&
    (offsets->GetDataType() == VTK_LONG || offsets->GetDataType() == VTK_LONG_LONG ||
      offsets->GetDataType() == VTK_ID_TYPE);
  const bool unsignedIds = ids->GetDataType() == VTK_UNSIGNED_INT ||
    ids->GetDataType() == VTK_UNSIGNED_LONG || ids->GetDataType() == VTK_UNSIGNED_LONG_LONG;
  if (!signedOffsets || ids->GetNumberOfComponents() != 1 || offsets->GetNumberOfComponents() != 1)
  {
    return "the index's level offsets must be one-component 64-bit integers";
  }
  if (!unsignedIds || (ids->GetDataTypeSize() != 4 && ids->GetDataTypeSize() != 8))
  {
    return "the index's voxel ids must be 32- or 64-bit unsigned integers";
  }
  if (offsets->GetNumberOfTuples() != values->GetNumberOfTuples() + 1)
  {
    return "the index's level offsets do not match its levels";
  }
  index->GetExtent(this->Extent);
  index->GetDimensions(this->Dimensions);
  index->GetOrigin(this->Origin);
  index->GetSpacing(this->Spacing);
  const double* direction = index->GetDirectionMatrix()->GetData();
  std::copy(direction, direction + 9, this->Direction);
  this->LevelValues = values->GetPointer(0);
  this->LevelOffsets = static_cast<const std::int64_t*>(offsets->GetVoidPointer(0));
  this->NumberOfLevels = values->GetNumberOfValues();
  this->Ids = ids;
  this->WideIds = ids->GetDataTypeSize() == 8;
  const std::int64_t voxels =
    static_cast<std::int64_t>(this->Dimensions[0]) * this->Dimensions[1] * this->Dimensions[2];
  if (this->LevelOffsets[0] != 0 ||
    this->LevelOffsets[this->NumberOfLevels] != ids->GetNumberOfValues() ||
    ids->GetNumberOfValues() > voxels)
  {
    return "the index's ids do not match its levels and extent";
  }
  for (std::int64_t l = 0; l < this->NumberOfLevels; ++l)
  {
    if (this->LevelOffsets[l + 1] < this->LevelOffsets[l])
    {
      return "the index's level offsets decrease";
    }
  }
  if (!this->WideIds && vtkMCXDensityIndex::NeedsWideIds(voxels))
  {
    return "the index's 32-bit ids cannot address its extent";
  }
  for (int a = 0; a < 3; ++a)
  {
    if (!(this->Spacing[a] != 0.0) || !std::isfinite(this->Spacing[a]) ||
      !std::isfinite(this->Origin[a]))
    {
      return "the volume's spacing must be non-zero and finite and its origin finite";
    }
  }
  if (!(this->VoxelVolume() > 0) || !std::isfinite(this->VoxelVolume()))
  {
    return "the volume's direction matrix is singular or its voxel volume is not finite";
  }
  return std::string();
}

void IndexView::SourceToWorld(double sourceOrigin[3], double sourceMatrix[9]) const
{
  for (int r = 0; r < 3; ++r)
  {
    sourceOrigin[r] = this->Origin[r];
    for (int c = 0; c < 3; ++c)
    {
      sourceMatrix[3 * r + c] = this->Direction[3 * r + c] * this->Spacing[c];
      sourceOrigin[r] += sourceMatrix[3 * r + c] * this->Extent[2 * c];
    }
  }
}

double IndexView::VoxelVolume() const
{
  double origin[3], m[9];
  this->SourceToWorld(origin, m);
  return std::fabs(vtkMath::Determinant3x3(m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8]));
}

std::vector<double> IndexView::EvaluateTransferFunction(vtkPiecewiseFunction* tf) const
{
  std::vector<double> weights(this->LevelValues, this->LevelValues + this->NumberOfLevels);
  if (!tf)
  {
    return weights; // raw density: g = f
  }
  for (std::int64_t l = 0; l < this->NumberOfLevels; ++l)
  {
    weights[static_cast<std::size_t>(l)] = tf->GetValue(this->LevelValues[l]);
  }
  return weights;
}

std::int64_t IndexView::KeepLevels(std::vector<double>& weights, std::vector<char>& kept) const
{
  kept.assign(weights.size(), 0);
  std::int64_t count = 0;
  for (std::size_t l = 0; l < weights.size(); ++l)
  {
    weights[l] = weights[l] > 0 ? weights[l] : 0.0;
    const std::int64_t voxels = this->LevelOffsets[l + 1] - this->LevelOffsets[l];
    kept[l] = weights[l] > 0 && voxels > 0 ? 1 : 0;
    count += kept[l] ? voxels : 0;
  }
  return count;
}

namespace
{
// The table of the view's levels, then the outcome told on the algorithm:
// the error ("Cannot <action>: ...", an earlier one kept) or the warning.
bool FinishPreparation(vtkAlgorithm* algorithm, const char* action, std::string error,
  vtkPiecewiseFunction* tf, const IndexView& view, TransferTable& table, double& integral)
{
  std::string warning;
  if (error.empty())
  {
    error = view.MakeTransferTable(tf, table, integral, warning);
  }
  if (!error.empty())
  {
    vtkErrorWithObjectMacro(algorithm, "Cannot " << action << ": " << error << ".");
    return false;
  }
  if (!warning.empty())
  {
    vtkWarningWithObjectMacro(algorithm, << warning);
  }
  return true;
}
}

bool PrepareSampling(vtkAlgorithm* algorithm, const char* action, vtkImageData* index,
  vtkPiecewiseFunction* tf, IndexView& view, TransferTable& table, double& integral)
{
  return FinishPreparation(algorithm, action, view.Read(index), tf, view, table, integral);
}

bool PrepareDistributedSampling(vtkAlgorithm* algorithm, const char* action, vtkImageData* index,
  vtkPiecewiseFunction* tf, vtkMultiProcessController* controller, const int wholeExtent[6],
  DistributedLevels& levels, IndexView& view, TransferTable& table, double& integral)
{
  std::string error = FirstErrorOfAll(controller, view.Read(index));
  if (error.empty())
  {
    error = FirstErrorOfAll(controller, GatherLevels(controller, wholeExtent, view, levels));
  }
  // The same table on every process: the whole volume's levels and TF.
  return FinishPreparation(algorithm, action, error, tf, view, table, integral);
}

bool CheckPointType(vtkObject* reporter, vtkPoints* points)
{
  if (points && points->GetDataType() != VTK_FLOAT && points->GetDataType() != VTK_DOUBLE)
  {
    vtkErrorWithObjectMacro(reporter,
      "Points must be float or double, not " << points->GetData()->GetDataTypeAsString() << ".");
    return false;
  }
  return true;
}

void AddFieldValue(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->InsertNextValue(value);
  fd->AddArray(array);
}

void AddFieldValue(vtkFieldData* fd, const char* name, long long value)
{
  vtkNew<vtkTypeInt64Array> array;
  array->SetName(name);
  array->InsertNextValue(value);
  fd->AddArray(array);
}

bool SupportCornersFromInformation(vtkInformation* info, double kernelRadius, double corners[24])
{
  if (!info || !info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    return false;
  }
  int extent[6];
  double origin[3] = { 0, 0, 0 };
  double spacing[3] = { 1, 1, 1 };
  double direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  if (info->Has(vtkDataObject::ORIGIN()))
  {
    info->Get(vtkDataObject::ORIGIN(), origin);
  }
  if (info->Has(vtkDataObject::SPACING()))
  {
    info->Get(vtkDataObject::SPACING(), spacing);
  }
  if (info->Has(vtkDataObject::DIRECTION()))
  {
    info->Get(vtkDataObject::DIRECTION(), direction);
  }
  if (extent[1] < extent[0] || extent[3] < extent[2] || extent[5] < extent[4])
  {
    return false;
  }
  ComputeSupportCorners(extent, origin, spacing, direction, kernelRadius, corners);
  return true;
}

std::string IndexView::MakeTransferTable(
  vtkPiecewiseFunction* tf, TransferTable& table, double& integral, std::string& warning) const
{
  table = BuildTransferTable(
    this->EvaluateTransferFunction(tf).data(), this->LevelOffsets, this->NumberOfLevels);
  warning = DescribeTransferTableProblems(table);
  integral = table.WeightSum() * this->VoxelVolume();
  if (table.InfiniteLevels > 0 || table.NaNLevels > 0)
  {
    std::string error = warning;
    warning.clear();
    if (!error.empty() && error.back() == '.')
    {
      error.pop_back();
    }
    return error;
  }
  if (!std::isfinite(integral))
  {
    return "the integral of the transfer-function-weighted volume overflows";
  }
  return std::string();
}

std::string DescribeTransferTableProblems(const TransferTable& table)
{
  // Errors (NaN, infinite) first: a caller that fails keeps the first sentence.
  std::vector<std::string> sentences;
  if (table.NaNLevels > 0)
  {
    sentences.push_back("the transfer function is NaN at " + std::to_string(table.NaNLevels) +
      " density levels (a NaN point?); no image is defined.");
  }
  if (table.InfiniteLevels > 0)
  {
    sentences.push_back("the transfer function is infinite at " +
      std::to_string(table.InfiniteLevels) + " density levels; no finite image exists.");
  }
  if (table.NegativeLevels > 0)
  {
    sentences.push_back("the transfer function is negative at " +
      std::to_string(table.NegativeLevels) + " density levels; those were clamped to 0.");
  }
  if (table.InfiniteLevels == 0 && table.NaNLevels == 0 && table.IsEmpty())
  {
    sentences.push_back("the transfer function is zero over the whole volume; the image is empty.");
  }
  // Sentences after the first start with a capital; the first keeps its
  // case, as it follows the caller's "Cannot ...: ".
  std::string text;
  for (std::size_t s = 0; s < sentences.size(); ++s)
  {
    std::string sentence = sentences[s];
    if (s > 0)
    {
      sentence[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(sentence[0])));
      text += ' ';
    }
    text += sentence;
  }
  return text;
}

} // namespace mcx
