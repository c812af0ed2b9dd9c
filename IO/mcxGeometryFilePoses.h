// The one place a geometry file becomes poses: RTK's circular geometry XML
// (mcxRTKGeometryFile, mcxRTKView), a beam of a DICOM RT Plan
// (mcxRTPlanFile, mcxIECBeamView) and a file of projection matrices
// (mcxMatrixFile: the JSON of mcxray's --output-geometry, or text), each as
// 3x4 projection matrices on a detector's pixel grid
// (Core/mcxProjectionMatrix.h's convention). mcxray's --rtk-geometry,
// --rtplan and --projection-matrices and vtkMCXProjectionGeometryReader (so
// Python's mcxray.drr) call these functions; messages name the caller's
// settings as the caller passes them.
#ifndef mcxGeometryFilePoses_h
#define mcxGeometryFilePoses_h

#include <cstddef>
#include <string>
#include <vector>

namespace mcxio
{

/// The most projections a geometry file may give (a run's pose limit).
const std::size_t MaximumGeometryFilePoses = 100000;

/// One view: its projection matrix and the distance from the source of the
/// plane the image's pixels are measured on (the output's spacing there).
struct GeometryFilePose
{
  double Matrix[12] = { 0 };
  double FocalDistance = 0.0; // 0: through the volume's centre
  int Size[2] = { 0, 0 };     // the detector's pixels, columns and rows
};

/// The detector and the distances a file does not give.
struct GeometryFileDetector
{
  int Pixels[2] = { 512, 512 };   // columns, rows
  double Pitch[2] = { 0.8, 0.8 }; // mm, along the columns and the rows
  bool HasOrigin = false;         // RTK: the first pixel's centre (mm) given
  double Origin[2] = { 0, 0 };    // else centred, as RTK's tools place it
  double SourceToImage = 1500.0;  // RT Plan
  double SourceToAxis = 1000.0;   // RT Plan, for a beam that gives none
  std::string SourceToAxisOption; // how the caller named a distance it gave, or ""
};

enum class GeometryFileKind
{
  RTKGeometry,
  RTPlan,
  ProjectionMatrices
};

/// The kind of the file at path by its content (DICOM's "DICM" after the
/// preamble, XML's '<', JSON's '{', or text starting with a number or a '#'
/// comment). Returns "" or one line saying why not.
std::string GeometryFileKindOf(const std::string& path, GeometryFileKind& kind);

/// Every projection of RTK's file, at most limit of them; its Matrix,
/// where written, must agree with its parameters as RTK's reader demands.
/// Returns "" or one line saying why not.
std::string RTKGeometryPoses(const std::string& path, std::size_t limit,
  const GeometryFileDetector& detector, std::vector<GeometryFilePose>& poses);

/// The pose of the plan's beam (ReadRTPlanBeam's choice of beam), by IEC
/// 61217 for a head first supine patient; a beam giving its own
/// SourceAxisDistance refuses detector.SourceToAxisOption's. Returns "" or
/// one line saying why not (always, in a build without vtk-dicom).
std::string RTPlanPose(const std::string& path, const std::string& beam,
  const GeometryFileDetector& detector, GeometryFilePose& pose);

/// The poses of a file of projection matrices, at most limit of them: each
/// a pinhole camera or an affine matrix (a parallel view), its size the
/// JSON's or else the detector's. Returns ""
/// or one line saying why not.
std::string MatrixFilePoses(const std::string& path, std::size_t limit,
  const GeometryFileDetector& detector, std::vector<GeometryFilePose>& poses);

} // namespace mcxio

#endif
