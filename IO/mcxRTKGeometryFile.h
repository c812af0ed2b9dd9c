// RTK's circular geometry file (rtk::ThreeDCircularProjectionGeometry's
// XML, RTKThreeDCircularGeometry versions 2 and 3), read as RTK's own
// reader reads it: elements named case-insensitively wherever they stand, a
// parameter before the first Projection holding for all projections, one
// inside a Projection for that one and the following ones (RTK keeps the
// last value read), Matrix kept for the caller to compare (RTK refuses a
// projection whose matrix differs from its parameters by more than 0.001).
// Stricter than RTK: every number whole and finite (RTK's std::stod reads
// "12abc" as 12), SourceToIsocenterDistance and SourceToDetectorDistance
// given, RadiusCylindricalDetector 0 (a cylindrical detector is none of
// ours), a bounded file. Collimation elements are read past: they bound
// RTK's reconstruction, not a projection's rays. Uses VTK's expat parser.
#ifndef mcxRTKGeometryFile_h
#define mcxRTKGeometryFile_h

#include "mcxRTKView.h" // Core: the parameters (a plain struct)

#include <cstddef>
#include <string>
#include <vector>

namespace mcxio
{

struct RTKGeometryProjection
{
  mcx::RTKProjection Parameters;
  bool HasMatrix = false;
  double Matrix[12] = { 0 }; // as the file writes it
};

/// The projections of the file at path, at most limit of them. Returns ""
/// or one line saying why not (the file, a missing or bad element, a
/// number that is not one, too many projections, XML that is not
/// well-formed).
std::string ReadRTKGeometry(
  const std::string& path, std::size_t limit, std::vector<RTKGeometryProjection>& projections);

} // namespace mcxio

#endif
