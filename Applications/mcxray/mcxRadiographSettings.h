// The radiograph options that render and view share: the view as
// radiographers, registration and radiotherapy tools give it (plastimatch
// drr's options, a projection matrix, pinhole intrinsics and extrinsics,
// one pose or a gantry sweep, RTK's geometry file, a beam of a DICOM RT
// Plan), and the physics applied after accumulation. Each is off unless
// asked for.
#ifndef mcxRadiographSettings_h
#define mcxRadiographSettings_h

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkCamera;
class vtkImageData;
class vtkMCXRadiograph;
class vtkMCXXRayMapper;

namespace mcxapp
{

/// One view of a run: its 3x4 projection matrix (mcxProjectionMatrix.h's
/// layout), detector pixels, and the distance from the source of the plane
/// the output's pixels are measured on (0: through the volume's centre).
struct Pose
{
  double Matrix[12];
  int Size[2];
  double FocalDistance;
};

struct RadiographSettings
{
  bool Geometry = false; // any option of the cone-beam geometry, a matrix or K, R, t
  double SourceToAxis = 1000.0;
  double SourceToImage = 1500.0;
  int Detector[2] = { 512, 512 };
  bool PitchGiven = false;
  double Pitch = 0.8;
  bool DetectorSizeGiven = false; // -z: the pitch is size / pixels
  double DetectorSize[2] = { 0, 0 };
  double Gantry = 0.0;
  bool GantryGiven = false;       // --gantry, -y
  std::vector<double> GantryList; // --gantry START:STOP:COUNT or -a/-N: several poses
  int AngleCount = 1;             // -a
  double AngleStep = 0.0;         // -N
  bool HasNormal = false;
  double Normal[3] = { 1, 0, 0 };
  double Up[3] = { 0, 0, 1 };
  bool UpGiven = false;
  bool HasImageCenter = false;
  double ImageCenter[2] = { 0, 0 };
  bool HasIsocenter = false;
  double Isocenter[3] = { 0, 0, 0 };
  bool SourceToAxisGiven = false;  // --sad
  bool SourceToImageGiven = false; // --sid
  std::string RTKGeometry;         // --rtk-geometry: every projection of RTK's file
  bool HasDetectorOrigin = false;  // --detector-origin: RTK's projection origin (mm)
  double DetectorOrigin[2] = { 0, 0 };
  std::string RTPlan; // --rtplan, with --beam
  std::string MatrixFile; // --projection-matrices: a pose per matrix of the file
  std::string Beam;
  bool HasMatrix = false; // --projection-matrix
  double Matrix[12] = { 0 };
  bool HasIntrinsics = false; // --intrinsics with --extrinsics
  double Intrinsics[4] = { 0 };
  bool HasExtrinsics = false;
  double Extrinsics[12] = { 0 };
  bool BeerLambert = false;
  double IncidentIntensity = 1.0;
  bool IncidentIntensityGiven = false; // --i0: with --beer-lambert or --photons alone
  double Photons = 0.0;
  long long NoiseSeed = 0;
  bool NegativeLog = false;

  /// Fails on options that contradict each other (a matrix and a gantry
  /// angle, --pitch and -z, a geometry file and --gantry, ...).
  void CheckCombinations() const;

  /// How many poses the run renders (known before the volume is read).
  int PoseCount() const;

  /// Every pose of the run, in order (isocentre: the volume's centre unless
  /// given). Fails on an impossible geometry.
  std::vector<Pose> Poses(vtkImageData* volume) const;

  /// The poses of --rtk-geometry's projections, --rtplan's beam or
  /// --projection-matrices, as IO's mcxGeometryFilePoses makes them for
  /// every caller. Fails on a file that does not give them.
  std::vector<Pose> GeometryFilePoses() const;

  /// The poses of the geometry file given, read once (before the volume, so
  /// that a bad file fails at once); empty without one.
  const std::vector<Pose>& FilePoses() const;
  mutable bool FilePosesRead = false;
  mutable std::vector<Pose> FilePoseList;

  /// The camera of the cone-beam geometry (one pose, square pixels centred
  /// on the isocentre's ray: what a renderer can show); sets the image size
  /// and the pixel spacing to the detector's. Fails on an impossible
  /// geometry.
  vtkSmartPointer<vtkCamera> MakeCamera(vtkImageData* volume, int size[2], double& spacing) const;

  /// Gives the physics to the off-line filter (vtkMCXRadiograph), or to the
  /// on-screen mapper (vtkMCXXRayMapper): the same five properties.
  template <typename Physics>
  void Configure(Physics* physics) const;
};

} // namespace mcxapp

#endif
