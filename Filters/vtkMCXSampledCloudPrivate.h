// What every strategy of vtkMCXPointSampler writes the same way: a point in
// voxel coordinates stored in world coordinates, and the field data that
// tells a cloud's consumers how it was made. Apart from the sampler so that
// the strategies' own files (vtkMCXEveryVoxelSamplingPrivate,
// vtkMCXViewOrderedSamplingPrivate) share them.
#ifndef vtkMCXSampledCloudPrivate_h
#define vtkMCXSampledCloudPrivate_h

#include "vtkType.h" // for vtkIdType

class vtkFieldData;
class vtkMCXPointSampler;

namespace mcx
{
struct IndexView;

/// x = origin + matrix p: a point in voxel coordinates stored in world
/// coordinates (IndexView::SourceToWorld).
template <typename Real>
void StoreInWorld(const double origin[3], const double matrix[9], const double p[3], Real* x)
{
  for (int r = 0; r < 3; ++r)
  {
    x[r] = static_cast<Real>(
      origin[r] + matrix[3 * r] * p[0] + matrix[3 * r + 1] * p[1] + matrix[3 * r + 2] * p[2]);
  }
}

/// What every cloud's consumers read (the pipeline passes the input's field
/// data on: only these, not the index's arrays; SortedVoxelIds alone is 4
/// bytes per voxel). exponent < 0: no SampleExponent (an every-voxel cloud).
void WriteCloudFields(vtkMCXPointSampler* self, const mcx::IndexView& view, double integral,
  vtkIdType count, int exponent, vtkFieldData* fd);
}

#endif
