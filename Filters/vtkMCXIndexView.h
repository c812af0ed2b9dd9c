// Read access to the output of vtkMCXDensityIndex for the samplers and
// projectors, plus the transfer function evaluated per level.
#ifndef vtkMCXIndexView_h
#define vtkMCXIndexView_h

#include "MonteCarloXRayFiltersModule.h" // for the export macro
#include "mcxSampleGenerator.h"
#include "mcxTransferTable.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkMultiProcessController;
class vtkDataArray;
class vtkFieldData;
class vtkImageData;
class vtkInformation;
class vtkObject;
class vtkPoints;
class vtkPiecewiseFunction;

namespace mcx
{
struct DistributedLevels;

struct IndexView
{
  int Extent[6] = { 0, -1, 0, -1, 0, -1 };
  int Dimensions[3] = { 0, 0, 0 };
  double Origin[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const double* LevelValues = nullptr;
  const std::int64_t* LevelOffsets = nullptr;
  std::int64_t NumberOfLevels = 0;
  vtkDataArray* Ids = nullptr;
  bool WideIds = false;
  /// A piece of a distributed index (see GatherLevels): Extent is then the
  /// whole volume's and Dimensions the piece's; null offsets: the whole.
  const std::int64_t* PieceOffsets = nullptr;
  const std::int64_t* PieceFirstRank = nullptr;
  std::uint64_t PieceStart[3] = { 0, 0, 0 };

  /// Reads the index arrays; returns an empty string or the reason it cannot.
  std::string Read(vtkImageData* index);

  /// World = SourceOrigin + SourceMatrix * p for voxel coordinates p counted
  /// from the first voxel of the extent.
  void SourceToWorld(double sourceOrigin[3], double sourceMatrix[9]) const;

  /// |det(direction * diag(spacing))|: the integral of one voxel's kernel.
  double VoxelVolume() const;

  /// TF value at each level (vtkPiecewiseFunction, clamped at its ends);
  /// without a TF, the level value itself.
  std::vector<double> EvaluateTransferFunction(vtkPiecewiseFunction* tf) const;

  /// Each level's TF weight as the table takes it (`weights`, from
  /// EvaluateTransferFunction: negative and NaN become 0), whether an
  /// every-voxel image keeps the level's voxels (a non-zero weight, voxels
  /// in the level), and how many voxels it keeps in the whole volume.
  std::int64_t KeepLevels(std::vector<double>& weights, std::vector<char>& kept) const;

  /// Evaluates the TF into the sampling table and the integral of g (TF
  /// units times world volume). Returns why no image can be made, or "";
  /// warning tells about values replaced by zero or an all-zero TF.
  std::string MakeTransferTable(
    vtkPiecewiseFunction* tf, TransferTable& table, double& integral, std::string& warning) const;

  /// Fills the voxel-independent part of a sample source.
  template <typename IdType>
  SampleSource<IdType> MakeSource(const TransferTable& table) const
  {
    SampleSource<IdType> source;
    source.SortedIds = this->IdPointer<IdType>();
    source.LevelOffsets = this->LevelOffsets;
    source.SetTable(table);
    source.NumberOfLevels = this->NumberOfLevels;
    source.Decoder = VoxelDecoder<IdType>(static_cast<std::uint64_t>(this->Dimensions[0]),
      static_cast<std::uint64_t>(this->Dimensions[1]));
    source.PieceOffsets = this->PieceOffsets;
    source.PieceFirstRank = this->PieceFirstRank;
    std::copy(this->PieceStart, this->PieceStart + 3, source.PieceStart);
    return source;
  }

  template <typename IdType>
  const IdType* IdPointer() const;
};

/// Reads the index and evaluates the TF for an algorithm: errors and
/// warnings are reported on the algorithm ("Cannot <action>: ..."). Returns
/// false when no output can be made.
bool PrepareSampling(vtkAlgorithm* algorithm, const char* action, vtkImageData* index,
  vtkPiecewiseFunction* tf, IndexView& view, TransferTable& table, double& integral);

/// PrepareSampling for this process's piece of an index cut into pieces
/// (`wholeExtent` the volume's): every process of the controller calls it,
/// and all fail, with the first process's error, if any does. The view then
/// sees the whole volume's levels (backed by `levels`), so the table is a
/// single process's.
bool PrepareDistributedSampling(vtkAlgorithm* algorithm, const char* action, vtkImageData* index,
  vtkPiecewiseFunction* tf, vtkMultiProcessController* controller, const int wholeExtent[6],
  DistributedLevels& levels, IndexView& view, TransferTable& table, double& integral);

/// Adds a one-value array to field data (the metadata that travels with outputs).
/// (Exported: the Rendering module's mapper writes its image's field data too.)
MONTECARLOXRAYFILTERS_EXPORT void AddFieldValue(vtkFieldData* fd, const char* name, double value);
MONTECARLOXRAYFILTERS_EXPORT void AddFieldValue(
  vtkFieldData* fd, const char* name, long long value);

/// True when a cloud's points (null: none) are float or double, the types
/// the projector and the mapper read; else an error on `reporter`.
/// (Exported: the Rendering module's mapper checks its input too.)
MONTECARLOXRAYFILTERS_EXPORT bool CheckPointType(vtkObject* reporter, vtkPoints* points);

/// Support corners (see ComputeSupportCorners) from the pipeline information
/// of an image (WHOLE_EXTENT, ORIGIN, SPACING and DIRECTION when present).
bool SupportCornersFromInformation(vtkInformation* info, double kernelRadius, double corners[24]);

/// Human-readable warnings for levels whose TF value had to be replaced by 0,
/// and for a TF that is zero everywhere; empty when there is nothing to say.
std::string DescribeTransferTableProblems(const TransferTable& table);

} // namespace mcx

#endif
