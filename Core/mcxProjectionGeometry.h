// Detector geometry shared by the Monte Carlo and the exact projectors.
//
// Image pixel (i, j) is centred at detector-plane coordinates
// (Origin[0] + i * Spacing[0], Origin[1] + j * Spacing[1]) and covers a
// Spacing[0] x Spacing[1] rectangle around that centre.
//   Parallel:    rays run along R = W + Obliquity[0] U + Obliquity[1] V (along
//                W unless a sheared or off-axis camera tilts them); a point x
//                has plane coordinates (x . U - Obliquity[0] x . W,
//                x . V - Obliquity[1] x . W), those of the point where its
//                ray crosses the plane x . W = 0.
//   Perspective: rays leave the eye E; a point x has plane coordinates
//                D * ((x - E) . U, (x - E) . V) / z with depth z = (x - E) . W,
//                i.e. coordinates on the plane at distance D from the eye
//                (the focal plane), measured from the principal point.
//                Only depths z >= NearDistance are seen; NearDistance must be
//                at least 1e-6 FocalDistance, which bounds a sample's weight.
// A pixel's value is (1 / pixel area) times the integral over the pixel of
// the line integral of g along the ray, in TF units times world length; in a
// parallel view that is the mass of g in the pixel's beam divided by the
// beam's cross-section (BeamCrossSection).
#ifndef mcxProjectionGeometry_h
#define mcxProjectionGeometry_h

#include <string>

namespace mcx
{

struct ProjectionGeometry
{
  bool Perspective = false;
  double Eye[3] = { 0, 0, 0 };
  double U[3] = { 1, 0, 0 };
  double V[3] = { 0, 1, 0 };
  double W[3] = { 0, 0, 1 };
  double FocalDistance = 1.0;
  double NearDistance = 0.0;
  int Size[2] = { 0, 0 };
  double Spacing[2] = { 1, 1 };
  double Origin[2] = { 0, 0 };
  /// Parallel views: the rays' shear per unit depth along U and V (as
  /// vtkCamera::SetViewShear's dx/dz, dy/dz); 0 for rays along W. Perspective
  /// views: unused, must be 0.
  double Obliquity[2] = { 0, 0 };

  double PixelArea() const { return this->Spacing[0] * this->Spacing[1]; }

  /// World length of a ray per unit of depth along W: 1 / cos of the rays'
  /// angle to W (1 in perspective views, whose weights carry the angle).
  double RayLengthPerDepth() const;

  /// The area across the rays of one pixel's beam: the pixel area times the
  /// cosine of the rays' angle to W (parallel views); the pixel area in
  /// perspective views. Mass in a beam over this area is the pixel's value.
  double BeamCrossSection() const { return this->PixelArea() / this->RayLengthPerDepth(); }

  /// Empty when usable, else why not (non-orthonormal axes, empty image, ...).
  std::string Validate() const;
};

/// Whether two geometries are the same, bit for bit.
bool SameGeometry(const ProjectionGeometry& a, const ProjectionGeometry& b);

/// The angle, in degrees (0 to 180), of the rotation that turns the axes
/// (U, V, W) of `a` into those of `b`: a turn of the view direction and a
/// roll about it alike; pans and zooms do not count. 180 when one image is
/// mirrored against the other (axes of opposite handedness).
double TurnDegrees(const ProjectionGeometry& a, const ProjectionGeometry& b);

/// Whether `b` frames the world point `centre` as `a` does, to within
/// `tolerance`: the same projection (parallel or perspective) and image
/// size, the point's pixel moved by at most tolerance times the image's
/// width and height, and the size of a pixel there (at the point's depth,
/// in perspective) changed by at most that fraction. Turns about the point
/// keep the framing; pans, zooms and resizes change it. False when the
/// point is not in front of either eye.
bool SameFraming(const ProjectionGeometry& a, const ProjectionGeometry& b, const double centre[3],
  double tolerance);

/// A geometry as GeometryValueCount numbers (a field array's): two
/// geometries are the same when their values are. The near distance is
/// value 14.
constexpr int GeometryValueCount = 23;
void GeometryToValues(const ProjectionGeometry& geometry, double values[GeometryValueCount]);

/// The 8 corners (x, y, z each) of the box where g can be non-zero: the
/// extent grown by the kernel radius (in voxels), mapped to world
/// coordinates by origin, spacing and direction (row-major 3x3).
void ComputeSupportCorners(const int extent[6], const double origin[3], const double spacing[3],
  const double direction[9], double kernelRadius, double corners[24]);

/// The depths (along W, from the eye) of the nearest and the farthest of
/// the 8 corners, in any view.
void CornerDepths(const ProjectionGeometry& g, const double corners[24], double depths[2]);

/// The depths (along W, from the eye) of the corners' box as seen from the
/// eye: [nearest, farthest], the nearest at least the near distance; both 0
/// in a parallel view.
void SupportDepthRange(
  const ProjectionGeometry& geometry, const double corners[24], double range[2]);

/// Plane coordinates of a world point; false when it is not in front of the
/// eye (perspective) -- then (a, b) are left unchanged.
bool ProjectToPlane(const ProjectionGeometry& geometry, const double x[3], double& a, double& b);

/// The margin, in pixels, FrameCorners leaves on each side of the corners'
/// projection: the footprint deposit rounds a sample's sub-pixel phase to one
/// of at least 8 per pixel (FootprintTable), which moves its deposit by up to
/// 1/8 pixel, so that with this margin every deposit of a parallel view lands
/// in an image framed on the support and mass is conserved exactly.
constexpr double FrameMargin = 0.125;

/// Sets Size, Spacing and Origin so that the image covers the projection of
/// the corners and FrameMargin pixels around it (perspective: the part in
/// front of the near plane is framed by its 8 corners, so corners behind the
/// eye are ignored). A requested size or spacing (> 0) is kept; with neither,
/// the longest side gets defaultLongSide pixels (the spacing grows to leave
/// the margins). A side computed from a spacing is the projection's whole
/// pixels, and two more where their slack is below the margins, so that the
/// grid keeps its place on the projection. Returns false if nothing can be
/// framed.
bool FrameCorners(ProjectionGeometry& geometry, const double corners[24],
  const int requestedSize[2], double requestedSpacing, int defaultLongSide);

/// Parallel view along a world axis (0, 1, 2): U and V are the two remaining
/// axes in x, y, z order, so the image is never mirrored.
ProjectionGeometry AxisAlignedParallel(int axis);

} // namespace mcx

#endif
