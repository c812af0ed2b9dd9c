// The cone-beam view that plastimatch drr's options describe (version
// 1.9.4, checked against the matrices it writes beside its images):
//   --sad, --sid        source to isocentre, source to detector (mm);
//   -o/--isocenter      the isocentre;
//   gantry angle a      the source at isocentre + SAD (cos a, -sin a, 0):
//                       +x at 0, -y at 90 degrees;
//   -n/--nrm            instead of the angle, the direction from the
//                       isocentre to the source;
//   --vup               towards the detector's top row (default +z);
//   -r/--dim            pixels, columns then rows (its help says "row col",
//                       its images are that many columns wide);
//   -z/--detector-size  mm, width then height;
//   -c/--image-center   the pixel (column, row) where the ray through the
//                       isocentre lands; default the detector's centre.
// Columns run along vup x nrm, rows downwards: P is in the layout of
// mcxProjectionMatrix.h, which is plastimatch's own with the image centre
// folded in.
#ifndef mcxPlastimatchView_h
#define mcxPlastimatchView_h

#include "mcxProjectionMatrix.h"

#include <string>

namespace mcx
{

struct PlastimatchView
{
  double SourceToAxis = 1000.0;
  double SourceToImage = 1500.0;
  double Isocenter[3] = { 0, 0, 0 };
  double GantryDegrees = 0.0;
  bool HasNormal = false;
  double Normal[3] = { 1, 0, 0 };
  double Up[3] = { 0, 0, 1 };
  int Pixels[2] = { 128, 128 };
  double DetectorSize[2] = { 600.0, 600.0 };
  bool HasImageCenter = false;
  double ImageCenter[2] = { 0, 0 };

  /// The pinhole camera of this view; "" or why the options describe none
  /// (a distance or size that is not positive and finite, so also a source
  /// in the detector's plane; vup along the normal).
  std::string Camera(PinholeCamera& camera) const;
};

} // namespace mcx

#endif
