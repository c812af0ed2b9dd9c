// A projection of RTK's circular geometry (rtk::ThreeDCircularProjectionGeometry,
// the parameters of its XML file) as RTK builds its matrix, and that matrix
// on a projection image's pixel grid in mcxProjectionMatrix.h's layout.
//
// RTK's fixed system is the volume's physical space as ITK reads it (LPS,
// as ours), the isocentre at its origin. Its matrix (RTK's GetMatrices) is
//   [1 0 sx-px; 0 1 sy-py; 0 0 1] [-sdd 0 0 0; 0 -sdd 0 0; 0 0 1 -sid]
//   [1 0 0 -sx; 0 1 0 -sy; 0 0 1 0] Rz(-in-plane) Rx(-out-of-plane) Ry(-gantry)
// (ITK's Euler3DTransform rotations, ZXY order): world mm to detector mm
// (u, v) along the rotated x and y axes, w < 0 in front of the source. A
// projection image of origin (ox, oy) and spacing (su, sv), identity
// direction, puts detector (u, v) at index ((u - ox) / su, (v - oy) / sv);
// its row index j is a vtkImageData's row j (row 0 at the bottom), the top
// row counted from in our layout is j = rows - 1.
#ifndef mcxRTKView_h
#define mcxRTKView_h

#include <string>

namespace mcx
{

/// RTK's nine parameters of one projection (mm and degrees, as its XML
/// file holds them).
struct RTKProjection
{
  double SourceToIsocenterDistance = 0.0;
  double SourceToDetectorDistance = 0.0;
  double GantryAngle = 0.0;
  double ProjectionOffsetX = 0.0;
  double ProjectionOffsetY = 0.0;
  double OutOfPlaneAngle = 0.0;
  double InPlaneAngle = 0.0;
  double SourceOffsetX = 0.0;
  double SourceOffsetY = 0.0;
};

/// RTK's own 3x4 matrix of the projection (row-major, detector mm).
void RTKMatrix(const RTKProjection& projection, double M[12]);

/// The projection's matrix on a detector of pixels[0] columns and
/// pixels[1] rows with RTK's projection origin and spacing (mm), in
/// mcxProjectionMatrix.h's layout (w > 0 in front of the source). Returns
/// why not, or "": a value not finite, a distance not positive (RTK's
/// parallel geometry, SourceToDetectorDistance 0, is none of ours), a
/// spacing not positive.
std::string RTKPixelMatrix(const RTKProjection& projection, const int pixels[2],
  const double origin[2], const double spacing[2], double P[12]);

} // namespace mcx

#endif
