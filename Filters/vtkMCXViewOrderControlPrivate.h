// The control image of a view order (vtkMCXViewOrderedSamplingPrivate.h):
// each bin's voxels projected in a view, every voxel once or a systematic
// sample of them (mcx::ControlPicks), and those bins' images weighed by a
// TF's bin means into the control image and its variance. Apart from the
// sampling because it is the control's arithmetic, tested through it.
#ifndef vtkMCXViewOrderControlPrivate_h
#define vtkMCXViewOrderControlPrivate_h

#include "mcxProjectionGeometry.h" // for ProjectionGeometry
#include "mcxSampleGenerator.h"    // for Kernel
#include "mcxViewOrder.h"          // for ViewOrder
#include "vtkType.h"               // for vtkTypeUInt64

#include <cstdint>
#include <vector>

class vtkAlgorithm;

namespace mcx
{
struct IndexView;
}

namespace vtkMCXViewOrderControl
{
// Each bin's voxels of `order` projected, footprints of `kernel` in
// `geometry` (voxel coordinates, as the sort located them): bins x pixels
// sums in the accumulator's fixed-point units (2^32 a whole voxel), the
// bins' images of the control (mcxControlImage.h). Without a stride every
// voxel once, rounding at random from a stream of their own, the same for
// every seed, so a new seed keeps them, and no differences; with one (> 2)
// about one voxel in `stride` of each (bin, cell) run (mcx::ControlPicks),
// drawn and rounded from `seed`, each carrying its interval, and
// `differences` gets each bin's image of the even picks less that of the
// odd ones. The runs are the order's cells, whatever view `geometry` is.
// Progress runs from progressBegin to progressEnd; false when aborted.
template <typename IdType>
bool ProjectBins(vtkAlgorithm* self, const mcx::IndexView& view,
  const mcx::ViewOrder<IdType>& order, const mcx::ProjectionGeometry& geometry, mcx::Kernel kernel,
  double stride, vtkTypeUInt64 seed, double progressBegin, double progressEnd,
  std::vector<double>& images, std::vector<double>& differences);

// The control image (line integrals) of the TF whose weight on each bin is
// binMeans[b]: the bins' images weighed by it, scaled so that it carries
// the cloud's integral as the cloud does, and its variance summed over the
// pixels, from the bins' differences (none: 0). Empty when no bin has
// weight.
std::vector<double> ControlImage(const std::vector<double>& binImages,
  const std::vector<double>& binDifferences, const std::vector<double>& binMeans,
  const std::vector<std::int64_t>& binOffsets, double integral,
  const mcx::ProjectionGeometry& geometry, double& variance);
}

#endif
