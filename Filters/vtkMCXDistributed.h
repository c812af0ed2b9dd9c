// What the filters exchange when a volume is cut into pieces, one per process
// of a vtkMultiProcessController (MPI under mpirun, pvbatch or pvserver):
// z-slabs of the volume in rank order, the global density levels, exact
// image sums, and agreement on failure so that no process waits for one that
// gave up. Only O(levels) numbers per index and the image sums per
// projection cross the network; everything else stays with its piece.
#ifndef vtkMCXDistributed_h
#define vtkMCXDistributed_h

#include "MonteCarloXRayFiltersModule.h" // for the export macro
#include "mcxFixedPoint.h"

#include <cstdint>
#include <string>
#include <vector>

class vtkImageData;
class vtkInformation;
class vtkMultiProcessController;

namespace mcx
{

struct IndexView;

/// True when the controller runs more than one process.
/// (Exported, as FirstErrorOfAll: ParaView's representation agrees too.)
MONTECARLOXRAYFILTERS_EXPORT bool IsDistributed(vtkMultiProcessController* controller);

/// The z-slab of `whole` that process `piece` of `pieces` holds: whole
/// slices, as evenly as they divide, in rank order (so that the global order
/// of voxel ids within a level is the rank order); an empty extent (z range
/// reversed) when there are fewer slices than processes.
/// (Exported: mcxray asks its index for the slab the projector will.)
MONTECARLOXRAYFILTERS_EXPORT void ZSlabExtent(
  const int whole[6], int piece, int pieces, int slab[6]);

/// Asks the input (`inInfo`) for this process's z-slab of its whole
/// extent, whatever the consumer asked; false (nothing set) with one
/// process or an input without a whole extent.
bool RequestZSlab(vtkMultiProcessController* controller, vtkInformation* inInfo);

/// Empties `output` on a process that holds no part of a result kept on
/// process 0, and tells the pipeline that this empty output meets any
/// request within the whole extent (`outInfo`'s): else VTK would run the
/// filter again at every later update on this process alone, which would
/// then wait for the others forever.
void EmptyOutputElsewhere(vtkImageData* output, vtkInformation* outInfo);

/// True when a reader delivered no voxels of the non-empty extent asked of
/// it (`inInfo`'s update extent): it failed. A failed reader's empty output
/// comes again, as if current, at the next update, without a failure the
/// executive could report; distributed, the process must still say so
/// (the index and the representation ask only then).
/// (Exported: ParaView's representation asks too.)
MONTECARLOXRAYFILTERS_EXPORT bool NothingRead(vtkImageData* input, vtkInformation* inInfo);

/// True when a reader described no voxels (`inInfo` has no whole extent, or
/// an empty one). Distributed, the processes' volumes must agree: ParaView's
/// reader of a file missing on one process describes nothing there without
/// failing.
MONTECARLOXRAYFILTERS_EXPORT bool NothingDescribed(vtkInformation* inInfo);

/// Agreement on success: every process passes its own error ("" when it
/// has none) and gets the first failing process's, prefixed with its rank
/// ("process 2 of 3: ..."), or "" when all succeeded; the same error from
/// every process comes back as it is. Collective.
MONTECARLOXRAYFILTERS_EXPORT std::string FirstErrorOfAll(
  vtkMultiProcessController* controller, const std::string& error);

/// Sums each value over the processes, exactly (the sums of a projection:
/// integers, so the result is the same for any number of processes and any
/// order of addition). Collective; every process gets the sums.
void SumExactly(vtkMultiProcessController* controller, std::vector<FixedSum>& values);

/// The levels of an index cut into pieces, seen whole.
struct DistributedLevels
{
  std::vector<double> LevelValues;          ///< the union of the pieces' levels, ascending
  std::vector<std::int64_t> LevelOffsets;   ///< the whole volume's, levels + 1 entries
  std::vector<std::int64_t> PieceOffsets;   ///< this piece's ids per global level, levels + 1
  std::vector<std::int64_t> PieceFirstRank; ///< the global rank of its first voxel per level
};

/// Turns `view` (this process's piece of an index, `wholeExtent` the
/// volume's) into a view of the whole volume's levels backed by `levels`:
/// global level values and offsets, with the piece's ids, offsets per
/// global level, first ranks and start in the whole extent. Collective.
/// Returns the first error of any process, or "".
std::string GatherLevels(vtkMultiProcessController* controller, const int wholeExtent[6],
  IndexView& view, DistributedLevels& levels);

} // namespace mcx

#endif
