// The EVERY_VOXEL strategy of vtkMCXPointSampler: each voxel of non-zero
// weight once, in the order of mcx::EveryVoxelOrder, weighted by its level
// (PointWeight, mean 1), and the cloud kept with ReusePoints so that a TF
// edit that keeps the same voxels rewrites only the weights. Apart from the
// sampler because it is a cloud of its own with a cache of its own; the
// sampler dispatches to it.
#ifndef vtkMCXEveryVoxelSamplingPrivate_h
#define vtkMCXEveryVoxelSamplingPrivate_h

#include "vtkType.h" // for vtkIdType

#include <memory>
#include <vector>

class vtkImageData;
class vtkMCXPointSampler;
class vtkPolyData;

namespace mcx
{
struct IndexView;
}

class vtkMCXEveryVoxelSampling
{
public:
  vtkMCXEveryVoxelSampling();
  ~vtkMCXEveryVoxelSampling();

  /// RequestData of EVERY_VOXEL for `sampler` (its settings, its progress
  /// and its errors): 1 when done or aborted (an aborted output is empty),
  /// 0 after an error.
  int RequestData(vtkMCXPointSampler* sampler, vtkImageData* input, vtkPolyData* output);

  /// Lets the kept cloud go (ReusePoints off, or another strategy runs).
  void Forget();

  /// The kept cloud's points (0: none kept).
  vtkIdType KeptPointCount() const;

private:
  /// The voxels of a cloud and what they were made for.
  struct Cloud;

  /// A new cloud of the `count` voxels of the levels `kept` (with
  /// `pointType` points): 1 made, 0 after an error, -1 aborted.
  int MakeCloud(vtkMCXPointSampler* sampler, const mcx::IndexView& view,
    const std::vector<char>& kept, vtkIdType count, int pointType, std::unique_ptr<Cloud>& cloud);
  /// The cloud's points and levels; false when the index's ids are not
  /// distinct voxel ids, `completed` false when aborted.
  bool MakePoints(vtkMCXPointSampler* sampler, const mcx::IndexView& view,
    const std::vector<char>& kept, Cloud& cloud, bool& completed);

  /// The last cloud, kept with ReusePoints while the index, the kept levels
  /// and the point settings stay the same.
  std::unique_ptr<Cloud> Kept;
};

#endif
