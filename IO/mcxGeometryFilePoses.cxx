#include "mcxGeometryFilePoses.h"

#include "mcxIECBeamView.h"
#include "mcxMatrixFile.h"
#include "mcxProjectionMatrix.h"
#include "mcxRTKGeometryFile.h"
#include "mcxRTKView.h"
#ifdef MCXRAY_IO_DICOM
#include "mcxRTPlanFile.h"
#endif

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace mcxio
{

namespace
{
// RTK's matrices are compared with the file's as RTK's reader compares
// them (an absolute difference of 0.001 in any element).
const double RTKMatrixTolerance = 0.001;

std::string Shown(double value)
{
  std::ostringstream text;
  text.precision(15);
  text << value;
  return text.str();
}
}

std::string GeometryFileKindOf(const std::string& path, GeometryFileKind& kind)
{
  const std::string named = "geometry file '" + path + "': ";
  if (!vtksys::SystemTools::FileExists(path, true))
  {
    return named + "no such file";
  }
  std::ifstream file(path, std::ios::binary);
  char head[132] = { 0 };
  file.read(head, sizeof(head));
  const std::size_t length = static_cast<std::size_t>(file.gcount());
  if (!file && length == 0)
  {
    return named + "cannot be read";
  }
  // DICOM Part 10 after its preamble, or a bare data set starting with
  // group 0008 (little endian), which vtk-dicom reads too.
  if ((length >= 132 && std::memcmp(head + 128, "DICM", 4) == 0) ||
    (length >= 2 && head[0] == 0x08 && head[1] == 0x00))
  {
    kind = GeometryFileKind::RTPlan;
    return std::string();
  }
  std::size_t first = length >= 3 && std::memcmp(head, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
  while (first < length && std::strchr(" \t\r\n", head[first]) && head[first] != '\0')
  {
    ++first;
  }
  if (first < length && head[first] == '<')
  {
    kind = GeometryFileKind::RTKGeometry;
    return std::string();
  }
  if (first < length && std::strchr("{#+-.0123456789", head[first]) && head[first] != '\0')
  {
    kind = GeometryFileKind::ProjectionMatrices;
    return std::string();
  }
  return named + "neither RTK's geometry XML, a DICOM RT Plan nor a file of projection matrices";
}

std::string RTKGeometryPoses(const std::string& path, std::size_t limit,
  const GeometryFileDetector& detector, std::vector<GeometryFilePose>& poses)
{
  poses.clear();
  std::vector<RTKGeometryProjection> projections;
  const std::string problem = ReadRTKGeometry(path, limit, projections);
  if (!problem.empty())
  {
    return problem;
  }
  double origin[2];
  for (int k = 0; k < 2; ++k)
  {
    // RTK's tools centre a projection on the detector's origin by default.
    origin[k] =
      detector.HasOrigin ? detector.Origin[k] : -0.5 * (detector.Pixels[k] - 1) * detector.Pitch[k];
  }
  GeometryFilePose pose;
  for (std::size_t k = 0; k < projections.size(); ++k)
  {
    const RTKGeometryProjection& projection = projections[k];
    const std::string which = "RTK geometry '" + path + "', projection " + std::to_string(k) + ": ";
    const std::string why = mcx::RTKPixelMatrix(
      projection.Parameters, detector.Pixels, origin, detector.Pitch, pose.Matrix);
    if (!why.empty())
    {
      poses.clear();
      return which + why;
    }
    if (projection.HasMatrix)
    {
      double M[12];
      mcx::RTKMatrix(projection.Parameters, M);
      for (int e = 0; e < 12; ++e)
      {
        if (!(std::abs(M[e] - projection.Matrix[e]) <= RTKMatrixTolerance))
        {
          poses.clear();
          return which + "its Matrix and its parameters disagree (element " + std::to_string(e) +
            ": " + Shown(projection.Matrix[e]) + " written, " + Shown(M[e]) +
            " from the parameters), as RTK refuses them";
        }
      }
    }
    pose.FocalDistance = projection.Parameters.SourceToDetectorDistance;
    std::copy(detector.Pixels, detector.Pixels + 2, pose.Size);
    poses.push_back(pose);
  }
  return std::string();
}

std::string RTPlanPose(const std::string& path, const std::string& beamName,
  const GeometryFileDetector& detector, GeometryFilePose& pose)
{
#ifdef MCXRAY_IO_DICOM
  RTPlanBeam beam;
  const std::string problem = ReadRTPlanBeam(path, beamName, beam);
  if (!problem.empty())
  {
    return problem;
  }
  if (beam.HasSourceAxisDistance && !detector.SourceToAxisOption.empty())
  {
    return "beam " + std::to_string(beam.Number) + " of '" + path +
      "' gives its SourceAxisDistance (" + Shown(beam.SourceAxisDistance) + " mm): leave out " +
      detector.SourceToAxisOption;
  }
  mcx::IECBeamView view;
  view.GantryDegrees = beam.GantryAngle;
  view.CollimatorDegrees = beam.BeamLimitingDeviceAngle;
  view.CouchDegrees = beam.PatientSupportAngle;
  view.SourceToAxis = beam.HasSourceAxisDistance ? beam.SourceAxisDistance : detector.SourceToAxis;
  view.SourceToImage = detector.SourceToImage;
  std::copy(beam.IsocenterPosition, beam.IsocenterPosition + 3, view.Isocenter);
  std::copy(detector.Pixels, detector.Pixels + 2, view.Pixels);
  std::copy(detector.Pitch, detector.Pitch + 2, view.Pitch);
  mcx::PinholeCamera camera;
  const std::string why = view.Camera(camera);
  if (!why.empty())
  {
    return "beam " + std::to_string(beam.Number) + " of '" + path + "': " + why;
  }
  mcx::MatrixFromPinhole(camera, pose.Matrix);
  pose.FocalDistance = view.SourceToAxis; // pixels measured at the isocentre, as --gantry's
  std::copy(detector.Pixels, detector.Pixels + 2, pose.Size);
  return std::string();
#else
  (void)beamName;
  (void)detector;
  (void)pose;
  return "RT plan '" + path + "': this build reads no DICOM (vtk-dicom was not found)";
#endif
}

std::string MatrixFilePoses(const std::string& path, std::size_t limit,
  const GeometryFileDetector& detector, std::vector<GeometryFilePose>& poses)
{
  poses.clear();
  std::vector<MatrixPose> matrices;
  const std::string problem = ReadProjectionMatrices(path, limit, matrices);
  if (!problem.empty())
  {
    return problem;
  }
  for (std::size_t k = 0; k < matrices.size(); ++k)
  {
    const std::string why = mcx::ProjectionMatrixProblem(matrices[k].Matrix);
    if (!why.empty())
    {
      poses.clear();
      return "projection matrices '" + path + "', pose " + std::to_string(k) + ": " + why;
    }
    GeometryFilePose pose;
    std::copy(matrices[k].Matrix, matrices[k].Matrix + 12, pose.Matrix);
    // The JSON of --output-geometry says each pose's pixels; text takes the detector's.
    for (int a = 0; a < 2; ++a)
    {
      pose.Size[a] = matrices[k].HasSize ? matrices[k].Size[a] : detector.Pixels[a];
    }
    poses.push_back(pose);
  }
  return std::string();
}

} // namespace mcxio
