// The index input of vtkMCXProjector: samples generated from a density
// index and deposited as they come, never stored (or every voxel once),
// under a controller of several processes each from its piece of the index;
// with the target controls, a pilot run and the larger runs it asks for.
// Apart from the cloud input (vtkMCXCloudProjectionPrivate), with which it
// shares only the accumulator and the Projection (vtkMCXProjectionPrivate.h).
#ifndef vtkMCXIndexProjectionPrivate_h
#define vtkMCXIndexProjectionPrivate_h

class vtkImageData;
class vtkMCXProjector;

namespace mcx
{
struct Projection;
struct ProjectionGeometry;

/// Stage 1b: the samples of `self`'s settings from `index` (whose whole
/// extent is `wholeExtent`) projected in `geometry`; false (reported on
/// `self`, on every process when distributed) when there is no image to
/// make. Throws std::runtime_error when a process of several failed.
bool ProjectIndex(vtkMCXProjector* self, vtkImageData* index, const int wholeExtent[6],
  const mcx::ProjectionGeometry& geometry, Projection& projection);
}

#endif
