// The cloud input of vtkMCXProjector: a stored point cloud of
// vtkMCXPointSampler (points in Halton order, weighted or not, with or
// without a control image) deposited into a Projection. Apart from the
// index input (vtkMCXIndexProjectionPrivate), with which it shares only the
// accumulator and the Projection (vtkMCXProjectionPrivate.h).
#ifndef vtkMCXCloudProjectionPrivate_h
#define vtkMCXCloudProjectionPrivate_h

class vtkAlgorithm;
class vtkPolyData;

namespace mcx
{
struct Projection;
struct ProjectionGeometry;

/// Stage 1a: the cloud's points projected in `geometry`, footprints that
/// reach more than footprintReach pixels split; false (reported on `self`)
/// when the cloud cannot be projected.
bool ProjectCloud(vtkAlgorithm* self, vtkPolyData* cloud, const mcx::ProjectionGeometry& geometry,
  double footprintReach, Projection& projection);
}

#endif
