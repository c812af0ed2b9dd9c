// The outputs of a run of several poses: one stack (.vti or .mha: a 3D
// image, one slice per pose, as RTK stores projections) or numbered files (NAME_0000.png
// ...), and the poses' geometry as JSON (--output-geometry).
#ifndef mcxPoseOutput_h
#define mcxPoseOutput_h

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkImageData;

namespace mcxapp
{

/// True when a run of several poses writes one stack to `path` (.vti, .mha);
/// false when it writes a file per pose (.png, .pfm).
bool WritesStack(const std::string& path);

/// The file of pose `index` (from 0): NAME_0000.EXT for NAME.EXT.
std::string NumberedOutput(const std::string& path, int index);

/// What --output-geometry writes of a pose: its image's ProjectionMatrix
/// field, size and spacing.
struct PoseRecord
{
  double Matrix[12];
  int Size[2];
  double Spacing[2];
};
PoseRecord RecordOf(vtkImageData* image);

/// A stack of `count` poses' 2D images (the same size and spacing) for the
/// file `path`, filled slice by slice: slice k of the scalars is pose k's,
/// and in a .vti (MetaImage holds the scalars alone) of every other point
/// array too (LineIntegral
/// beside a radiograph's Intensity, the channels) while they fit the
/// memory budget (else Warning() says they were left out); each one-tuple
/// field of an image (ProjectionMatrix, SampleCount,
/// EstimatedRelativeError, ...) holds a tuple per pose. Fails, before any
/// work, when the scalars alone do not fit the budget.
class PoseStack
{
public:
  PoseStack(int count, const int size[2], const std::string& path);
  void Add(int k, vtkImageData* image);
  vtkImageData* GetImage() const;
  const std::string& Warning() const { return this->LeftOut; }

private:
  void AllocateLike(vtkImageData* image); // the arrays of the first pose's image
  vtkSmartPointer<vtkImageData> Image;
  int Count;
  bool EveryArray;
  std::string LeftOut;
};

/// Writes the poses' geometry as JSON to path, all or nothing: per pose the
/// detector size in pixels, the spacing, the 3x4 matrix P and, for a
/// perspective view, K, R, t and the source. False with the reason on
/// failure.
bool WritePoseGeometry(
  const std::vector<PoseRecord>& poses, const std::string& path, std::string& error);

} // namespace mcxapp

#endif
