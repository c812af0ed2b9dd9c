/**
 * @class   vtkMCXDensityIndex
 * @brief   Sorts the voxel ids of a volume by density level (the preprocessing
 *          of hybrid Monte Carlo volume rendering).
 *
 * The input is vtkImageData with one-component point scalars of any type:
 * the array SetInputArrayToProcess names, by default (or named "") the
 * active point scalars.
 * Integer data gets one level per distinct value (exact), and so does
 * floating-point data whose finite values are all whole numbers. Other
 * floating-point data gets NumberOfFloatLevels equal-width bins over its
 * finite range; each non-empty bin is a level whose value is the mean of its
 * voxels' values (exact when they are all equal). NaN and infinite voxels are
 * left out and counted.
 *
 * The output is vtkImageData with the input's geometry (extent, origin,
 * spacing, direction) and no point data; the index travels in its field data:
 * - "LevelValues" (double, one per non-empty level, ascending),
 * - "LevelOffsets" (vtkTypeInt64Array, levels + 1 entries): the ids of level l
 *   are SortedVoxelIds[LevelOffsets[l] .. LevelOffsets[l+1]),
 * - "SortedVoxelIds" (vtkTypeUInt32Array below 2^32 voxels, else
 *   vtkTypeUInt64Array): raster ids (x fastest) counted from the first voxel of
 *   the extent, ascending within a level,
 * - "NonFiniteVoxelCount" (vtkTypeInt64Array, 1 value),
 * - "LevelBinWidth" (double, 1 value): 0 for exact levels, else the bin width.
 *
 * The sort runs in parallel with vtkSMPTools and its output is identical for
 * any number of threads.
 *
 * The output holds the extent asked of it (its update extent; the whole
 * volume unless a consumer asks for less), and the index of that part.
 * vtkMCXProjector under several processes asks each for its z-slab: each
 * process then reads and indexes only its slab, and the processes agree on
 * the data's range (Controller) so that floating-point data is binned alike
 * everywhere and a level's value is the whole volume's mean, the same for
 * any number of processes. A process beyond the slices gets an empty index.
 * A process whose reader fails (its information or its data) still meets
 * the others, and the index fails on every process with that process's
 * message, so that none waits for it (the index's own executive lets the
 * failure through, and so do the plugin's executives for ParaView's X-Ray
 * Density Index filter and the "Monte Carlo X-Ray" representation; a
 * pipeline that gives the index another executive stops at the failing
 * reader as usual).
 */
#ifndef vtkMCXDensityIndex_h
#define vtkMCXDensityIndex_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkMCXTypes.h" // for the array names and constants
#include "vtkImageAlgorithm.h"

class vtkMultiProcessController;

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXDensityIndex : public vtkImageAlgorithm
{
public:
  static vtkMCXDensityIndex* New();
  vtkTypeMacro(vtkMCXDensityIndex, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of equal-width levels for floating-point data (default 4096).
   * Integer data always gets one level per distinct value.
   */
  vtkSetClampMacro(NumberOfFloatLevels, int, 1, 1 << 24);
  vtkGetMacro(NumberOfFloatLevels, int);
  ///@}

  ///@{
  /**
   * Use 64-bit voxel ids even below 2^32 voxels (default off). The output is
   * then the one a volume of more than 2^32 voxels gets, which lets that path
   * be exercised on small data.
   */
  vtkSetMacro(AlwaysUseWideIds, bool);
  vtkGetMacro(AlwaysUseWideIds, bool);
  vtkBooleanMacro(AlwaysUseWideIds, bool);
  ///@}

  ///@{
  /**
   * The processes that hold the volume's pieces (default: the global
   * controller). Under more than one, a problem on any process fails the
   * index on all of them, with that process's message.
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  /**
   * True when volumes of this many voxels need 64-bit ids.
   */
  static bool NeedsWideIds(long long numberOfVoxels);

protected:
  vtkMCXDensityIndex();
  ~vtkMCXDensityIndex() override;

  vtkExecutive* CreateDefaultExecutive() override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int NumberOfFloatLevels = 4096;
  bool AlwaysUseWideIds = false;
  vtkMultiProcessController* Controller = nullptr;

private:
  vtkMCXDensityIndex(const vtkMCXDensityIndex&) = delete;
  void operator=(const vtkMCXDensityIndex&) = delete;
};

#endif
