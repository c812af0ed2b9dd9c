// A view as a 3x4 projection matrix, and as pinhole intrinsics and
// extrinsics, in both directions.
//
// P maps a world point (x, y, z, 1) to (u w, v w, w): u is the column, 0 at
// the centre of the leftmost pixel; v the row, 0 at the centre of the top
// row as the image is shown (the last row j = rows - 1 of a vtkImageData,
// whose row 0 is at the bottom); w > 0 in front of the source. This is
// OpenCV's and plastimatch's layout: K = [fx 0 cx; 0 fy cy; 0 0 1] in
// pixels, [R | t] world to camera with the camera's x to the right, y down
// and z forward. A parallel view's P is affine: its last row is 0 0 0 1.
#ifndef mcxProjectionMatrix_h
#define mcxProjectionMatrix_h

#include "mcxProjectionGeometry.h"

#include <string>

namespace mcx
{

/// A perspective view in OpenCV's terms: focal lengths and principal point
/// in pixels, R row-major (rows: the camera's x, y, z in world
/// coordinates), t = -R source.
struct PinholeCamera
{
  double Fx = 1.0;
  double Fy = 1.0;
  double Cx = 0.0;
  double Cy = 0.0;
  double R[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  double T[3] = { 0, 0, 0 };

  /// The source (the eye): -R^T t.
  void Source(double source[3]) const;
};

/// P = K [R | t], row-major.
void MatrixFromPinhole(const PinholeCamera& camera, double P[12]);

/// K, R and t of a perspective P (any nonzero scale, either sign): the
/// decomposition with fx, fy > 0 and det R = +1, so that w > 0 in front of
/// the source. Returns why P is no pinhole camera, or "": not finite, rank
/// below 3 (the source undetermined or at infinity, as in an affine P), or
/// a skew beyond 1e-6 fx (pixels that are no rectangles).
std::string PinholeFromMatrix(const double P[12], PinholeCamera& camera);

/// The geometry of a detector of size[0] columns and size[1] rows seen by
/// `camera`, its pixel grid laid on the focal plane at `focalDistance`
/// world units in front of the source (the output image's spacing is the
/// pixels' size there). Returns why not, or "".
std::string GeometryFromPinhole(const PinholeCamera& camera, const int size[2],
  double focalDistance, ProjectionGeometry& geometry);

/// Whether P is a parallel view's: finite, its last row 0 0 0 c with c not 0.
bool IsAffineMatrix(const double P[12]);

/// The parallel geometry of an affine P (any nonzero scale) for a detector
/// of size[0] columns and size[1] rows: MatrixFromGeometry gives P back up
/// to scale (divided by its last entry), to rounding. P fixes the rays and each pixel's beam, not
/// the detector's plane: the plane taken is perpendicular to the rays where P's pixels are
/// rectangles across them, else the one tilted just enough that they are
/// (an oblique view's). Returns why not, or "": rows that are not
/// independent (no direction for the rays).
std::string GeometryFromAffineMatrix(
  const double P[12], const int size[2], ProjectionGeometry& geometry);

/// Why P is no camera (PinholeFromMatrix's and GeometryFromAffineMatrix's
/// reasons), or "": the check of a matrix given before any image size.
std::string ProjectionMatrixProblem(const double P[12]);

/// The pinhole camera of a perspective geometry.
PinholeCamera PinholeFromGeometry(const ProjectionGeometry& geometry);

/// The projection matrix of a geometry: K [R | t] for a perspective view, an
/// affine matrix (last row 0 0 0 1) for a parallel one.
void MatrixFromGeometry(const ProjectionGeometry& geometry, double P[12]);

/// Where P puts a world point: (u, v) as above; false when the point is not
/// in front of the source (w <= 0) or P is not finite there.
bool ProjectPoint(const double P[12], const double x[3], double& u, double& v);

} // namespace mcx

#endif
