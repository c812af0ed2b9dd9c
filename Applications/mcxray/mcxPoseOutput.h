// The outputs of a run of several poses: one stack (.vti: a 3D image, one
// slice per pose, as RTK stores projections) or numbered files (NAME_0000.png
// ...), and the poses' geometry as JSON (--output-geometry).
#ifndef mcxPoseOutput_h
#define mcxPoseOutput_h

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkImageData;

namespace mcxapp
{

/// True when a run of several poses writes one stack to `path` (.vti);
/// false when it writes a file per pose (.png, .pfm).
bool WritesStack(const std::string& path);

/// The file of pose `index` (from 0): NAME_0000.EXT for NAME.EXT.
std::string NumberedOutput(const std::string& path, int index);

/// The 2D images of the poses (the same size and spacing) as one 3D image,
/// slice k the image of pose k; its ProjectionMatrix field holds a tuple of
/// 12 per pose.
vtkSmartPointer<vtkImageData> StackImages(const std::vector<vtkSmartPointer<vtkImageData>>& images);

/// Writes the poses' geometry, read from each image's ProjectionMatrix
/// field, as JSON to path, all or nothing: per pose the detector size in
/// pixels, the 3x4 matrix P and, for a perspective view, K, R, t and the
/// source. False with the reason on failure.
bool WritePoseGeometry(const std::vector<vtkSmartPointer<vtkImageData>>& images,
  const std::string& path, std::string& error);

} // namespace mcxapp

#endif
