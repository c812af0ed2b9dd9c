// How a stored cloud asks to be deposited, read from its field data: shared
// by the off-line projector and the mapper so that both deposit a cloud alike.
#ifndef vtkMCXCloudDeposit_h
#define vtkMCXCloudDeposit_h

#include "MonteCarloXRayFiltersModule.h" // for the export macro
#include "mcxProjectionGeometry.h"
#include "mcxSampleAccumulator.h"
#include "vtkDataArray.h"    // for WithPointWeights
#include "vtkSmartPointer.h" // for ControlPointsOf

#include <vector>

class vtkDataObject;
class vtkDoubleArray;
class vtkObject;
class vtkPoints;
class vtkPolyData;

namespace mcx
{

/// The deposit of a vtkMCXPointSampler cloud (field data Deposit, Kernel,
/// Seed, Strategy, VoxelAxes; a cloud without them is a point cloud of positions) for
/// a view whose source frame takes cloud coordinates to world by origin and
/// matrix (row-major 3x3): in perspective views the depth range is that of
/// the sampler's support (field SupportCorners), else of the points' bounds
/// grown by the kernel's reach. footprintReach is the projecting class's
/// FootprintReach (see vtkMCXProjector::SetFootprintReach): the split of a
/// large kernel is made when the cloud is deposited, so a cloud's reach is
/// its consumer's. (Exported: the Rendering module's mapper deposits clouds too.)
MONTECARLOXRAYFILTERS_EXPORT DepositSettings CloudDepositSettings(vtkPolyData* cloud,
  const ProjectionGeometry& geometry, const double origin[3], const double matrix[9],
  double footprintReach);

/// True for a vtkMCXPointSampler EVERY_VOXEL cloud (field Strategy): each
/// voxel once, weighted, so the halves of its points are no two estimates
/// of one image and its error is not estimated (NaN).
MONTECARLOXRAYFILTERS_EXPORT bool IsEveryVoxelCloud(vtkPolyData* cloud);

/// The control image (vtkMCXTypes::ControlImageName(), line
/// integrals) that a view-ordered cloud carries for `geometry`: empty
/// unless its ControlView is this geometry, bit for bit, its ControlPoints
/// is the cloud's first point (ControlPointsOf), and it holds one finite
/// value per pixel, and its variance (vtkMCXTypes::ControlVarianceName(),
/// 0 without it) is one finite value of at least 0, which goes to
/// `variance`. Only for images of the cloud's own frame (no prop matrix)
/// with nothing hiding any sample.
MONTECARLOXRAYFILTERS_EXPORT std::vector<double> CloudControlImage(
  vtkPolyData* cloud, const ProjectionGeometry& geometry, double& variance);

/// The 8 corners (x, y, z each, in the cloud's coordinates: world for a
/// sampler's cloud) of the data's field SupportCorners (the box where a
/// vtkMCXPointSampler cloud's samples lie), 24 values in any layout; false
/// without them.
MONTECARLOXRAYFILTERS_EXPORT bool CloudSupportCorners(vtkDataObject* data, double corners[24]);

/// The depths along `geometry`'s view (from its Eye along W) of the nearest
/// and the farthest corner of the cloud's SupportCorners (world
/// coordinates), the box where its samples lie; false without them.
MONTECARLOXRAYFILTERS_EXPORT bool CloudSupportDepths(
  vtkPolyData* cloud, const ProjectionGeometry& geometry, double depths[2]);

/// The field array vtkMCXTypes::ControlPointsName() of `points`.
MONTECARLOXRAYFILTERS_EXPORT vtkSmartPointer<vtkDoubleArray> ControlPointsOf(vtkPoints* points);

/// The cloud's point weights (point-data array
/// vtkMCXTypes::PointWeightName()): null without them; valid false
/// (and reported on `self`) when the array is not one float or double
/// component per point, each finite and in [0, MaximumPointWeight].
MONTECARLOXRAYFILTERS_EXPORT vtkDataArray* CloudPointWeights(
  vtkObject* self, vtkPolyData* cloud, bool& valid);

/// Calls deposit(weights) with the array's values as a float or double
/// pointer, or a null float pointer for no array (as CloudPointWeights
/// returns it: checked).
template <typename Deposit>
auto WithPointWeights(vtkDataArray* weights, const Deposit& deposit)
{
  if (!weights)
  {
    return deposit(static_cast<const float*>(nullptr));
  }
  return weights->GetDataType() == VTK_FLOAT
    ? deposit(static_cast<const float*>(weights->GetVoidPointer(0)))
    : deposit(static_cast<const double*>(weights->GetVoidPointer(0)));
}
} // namespace mcx

#endif
