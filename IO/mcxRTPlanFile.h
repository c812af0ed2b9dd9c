// A beam of a DICOM RT Plan (SOP class 1.2.840.10008.5.1.4.1.1.481.5), read
// with vtk-dicom: BeamSequence's BeamNumber, BeamName and
// SourceAxisDistance, and its first control point's GantryAngle,
// BeamLimitingDeviceAngle, PatientSupportAngle and IsocenterPosition (the
// first control point holds them all: DICOM's type 1C). What the geometry
// of mcxIECBeamView.h does not describe is refused: a patient position other
// than head first supine (PatientSetupSequence), a table top eccentric,
// pitch or roll angle other than 0, an angle outside [0, 360). The file is
// parsed in a forked child (ParseInChild), as series files are.
#ifndef mcxRTPlanFile_h
#define mcxRTPlanFile_h

#include <string>

namespace mcxio
{

struct RTPlanBeam
{
  int Number = 0;
  std::string Name;
  double GantryAngle = 0.0;
  double BeamLimitingDeviceAngle = 0.0;
  double PatientSupportAngle = 0.0;
  bool HasSourceAxisDistance = false;
  double SourceAxisDistance = 0.0;
  double IsocenterPosition[3] = { 0, 0, 0 };
};

/// The beam of the plan at path whose BeamNumber is beam or, failing
/// that, whose BeamName is beam; with beam empty, the plan's only beam.
/// Returns "" or one line saying why not (naming the plan's beams where
/// the beam is missing).
std::string ReadRTPlanBeam(const std::string& path, const std::string& beam, RTPlanBeam& out);

} // namespace mcxio

#endif
