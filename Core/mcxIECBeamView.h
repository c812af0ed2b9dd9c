// The beam's eye view of a radiotherapy field by IEC 61217, for a patient
// lying head first supine (HFS), in patient space (LPS). The fixed system:
// X to the right of one who stands at the couch's foot facing the gantry
// (the patient's left, +x), Y towards the gantry (the head, +z), Z up
// (anterior, -y).
//   gantry angle      about Y, clockwise seen from the isocentre towards
//                     the gantry: the source anterior at 0, at the
//                     patient's left at 90, posterior at 180, right at 270;
//   collimator angle  the detector about the beam axis, counterclockwise
//                     seen from the source;
//   couch angle       the patient about the vertical axis through the
//                     isocentre, counterclockwise seen from above.
// The image is seen from the source, its columns along the collimator's X
// and its rows down its -Y: at gantry, collimator and couch 0 the head at
// the top and the patient's left on the right; pixels on a detector
// SourceToImage from the source, centred on the isocentre's ray.
#ifndef mcxIECBeamView_h
#define mcxIECBeamView_h

#include "mcxProjectionMatrix.h"

#include <string>

namespace mcx
{

struct IECBeamView
{
  double GantryDegrees = 0.0;
  double CollimatorDegrees = 0.0;
  double CouchDegrees = 0.0;
  double SourceToAxis = 1000.0;
  double SourceToImage = 1500.0;
  double Isocenter[3] = { 0, 0, 0 };
  int Pixels[2] = { 512, 512 };
  double Pitch[2] = { 0.8, 0.8 };

  /// The pinhole camera of the field; "" or why none (a distance or pitch
  /// not positive and finite, an angle or the isocentre not finite).
  std::string Camera(PinholeCamera& camera) const;
};

} // namespace mcx

#endif
