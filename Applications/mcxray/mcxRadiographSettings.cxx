#include "mcxRadiographSettings.h"

#include "mcxErrorCapture.h"
#include "mcxFail.h"
#include "mcxGeometryFilePoses.h"
#include "mcxProjectionMatrix.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkMCXRadiograph.h"
#include "vtkMCXRadiographGeometry.h"
#include "vtkMCXXRayMapper.h"
#include "vtkNew.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace mcxapp
{

namespace
{
// The most poses one run renders (a file each, or a slice of one stack).
const int MaximumPoses = 100000;

// The geometry's error, said as one line of mcxray's.
class GeometryErrors
{
public:
  explicit GeometryErrors(vtkObject* geometry)
  {
    this->Command->SetClientData(&this->Text);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long, void* text, void* message)
      {
        std::string& kept = *static_cast<std::string*>(text);
        if (kept.empty() && message)
        {
          kept = ErrorCapture::Clean(static_cast<const char*>(message));
        }
      });
    geometry->AddObserver(vtkCommand::ErrorEvent, this->Command);
  }
  [[noreturn]] void Fail() const
  {
    mcxapp::Fail(this->Text.empty() ? std::string("bad radiograph geometry") : this->Text);
  }

private:
  std::string Text;
  vtkNew<vtkCallbackCommand> Command;
};

void Centre(vtkImageData* volume, double centre[3])
{
  double bounds[6];
  volume->GetBounds(bounds);
  for (int a = 0; a < 3; ++a)
  {
    centre[a] = (bounds[2 * a] + bounds[2 * a + 1]) / 2;
  }
}

// The detector pitch: --pitch, or -z over the pixels.
void DetectorPitch(const RadiographSettings& settings, double pitch[2])
{
  for (int k = 0; k < 2; ++k)
  {
    pitch[k] =
      settings.DetectorSizeGiven ? settings.DetectorSize[k] / settings.Detector[k] : settings.Pitch;
  }
}
}

// The geometry file's poses, as IO turns a file into poses for every caller.
std::vector<Pose> RadiographSettings::GeometryFilePoses() const
{
  mcxio::GeometryFileDetector detector;
  std::copy(this->Detector, this->Detector + 2, detector.Pixels);
  DetectorPitch(*this, detector.Pitch);
  detector.HasOrigin = this->HasDetectorOrigin;
  std::copy(this->DetectorOrigin, this->DetectorOrigin + 2, detector.Origin);
  detector.SourceToImage = this->SourceToImage;
  detector.SourceToAxis = this->SourceToAxis;
  detector.SourceToAxisOption = this->SourceToAxisGiven ? "--sad" : "";
  std::vector<mcxio::GeometryFilePose> found(1);
  std::string problem;
  if (!this->RTKGeometry.empty())
  {
    problem = mcxio::RTKGeometryPoses(this->RTKGeometry, MaximumPoses, detector, found);
  }
  else if (!this->RTPlan.empty())
  {
    problem = mcxio::RTPlanPose(this->RTPlan, this->Beam, detector, found[0]);
  }
  else
  {
    problem = mcxio::MatrixFilePoses(this->MatrixFile, MaximumPoses, detector, found);
  }
  if (!problem.empty())
  {
    Fail(problem);
  }
  std::vector<Pose> poses(found.size());
  for (std::size_t k = 0; k < found.size(); ++k)
  {
    std::copy(found[k].Matrix, found[k].Matrix + 12, poses[k].Matrix);
    std::copy(found[k].Size, found[k].Size + 2, poses[k].Size);
    poses[k].FocalDistance = found[k].FocalDistance;
  }
  return poses;
}

namespace
{
// A geometry file's options against the others; "" or why not.
std::string FileCombinations(const RadiographSettings& r)
{
  const bool rtk = !r.RTKGeometry.empty(), plan = !r.RTPlan.empty(),
             matrices = !r.MatrixFile.empty();
  if (int(rtk) + int(plan) + int(matrices) > 1)
  {
    return "give one of --rtk-geometry, --rtplan and --projection-matrices";
  }
  if (r.HasDetectorOrigin && !rtk)
  {
    return "--detector-origin places RTK's projections: it goes with --rtk-geometry";
  }
  if (!r.Beam.empty() && !plan)
  {
    return "--beam chooses a beam of --rtplan";
  }
  if (!rtk && !plan && !matrices)
  {
    return std::string();
  }
  const char* file = rtk ? "--rtk-geometry" : (plan ? "--rtplan" : "--projection-matrices");
  if (r.GantryGiven || !r.GantryList.empty() || r.AngleCount > 1 || r.AngleStep != 0 ||
    r.HasNormal || r.UpGiven || r.HasImageCenter || r.HasIsocenter || r.HasMatrix ||
    r.HasIntrinsics || r.HasExtrinsics)
  {
    return std::string(file) +
      " gives the whole view: it replaces --gantry, -a, -N, --nrm, --vup, --image-center, "
      "--isocenter, --projection-matrix and --intrinsics/--extrinsics";
  }
  if ((rtk || matrices) && (r.SourceToAxisGiven || r.SourceToImageGiven))
  {
    return std::string(file) + " gives the distances of each projection: leave out --sad and --sid";
  }
  if (matrices && (r.PitchGiven || r.DetectorSizeGiven))
  {
    return "--projection-matrices gives each pose's pixels: leave out --pitch and -z";
  }
  return std::string();
}
}

void RadiographSettings::CheckCombinations() const
{
  const std::string files = FileCombinations(*this);
  if (!files.empty())
  {
    Fail(files);
  }
  const bool sweep = !this->GantryList.empty() || this->AngleCount > 1;
  if ((this->HasMatrix || this->HasIntrinsics) &&
    (sweep || this->HasNormal || this->HasImageCenter))
  {
    Fail("--projection-matrix and --intrinsics give the whole view: they replace --gantry, -a, "
         "--nrm and --image-center");
  }
  if (this->HasMatrix && (this->HasIntrinsics || this->HasExtrinsics))
  {
    Fail("give either --projection-matrix or --intrinsics with --extrinsics, not both");
  }
  if (this->HasIntrinsics != this->HasExtrinsics)
  {
    Fail("--intrinsics and --extrinsics go together");
  }
  if (this->PitchGiven && this->DetectorSizeGiven)
  {
    Fail("give either --pitch or --detector-size (-z), not both");
  }
  if (!this->GantryList.empty() && (this->AngleCount > 1 || this->AngleStep != 0))
  {
    Fail("give either --gantry START:STOP:COUNT or -a/-N, not both");
  }
  if (this->HasNormal && sweep)
  {
    Fail("--nrm fixes the direction of the source: it cannot be swept (-a, --gantry "
         "START:STOP:COUNT)");
  }
  if (static_cast<long long>(this->AngleCount) * std::max<std::size_t>(1, this->GantryList.size()) >
    MaximumPoses)
  {
    Fail("at most " + std::to_string(MaximumPoses) + " poses per run");
  }
}

const std::vector<Pose>& RadiographSettings::FilePoses() const
{
  if (!this->FilePosesRead)
  {
    this->FilePosesRead = true;
    if (!this->RTKGeometry.empty() || !this->RTPlan.empty() || !this->MatrixFile.empty())
    {
      this->FilePoseList = this->GeometryFilePoses();
    }
  }
  return this->FilePoseList;
}

int RadiographSettings::PoseCount() const
{
  if (!this->RTKGeometry.empty() || !this->RTPlan.empty() || !this->MatrixFile.empty())
  {
    return static_cast<int>(this->FilePoses().size());
  }
  if (this->HasMatrix || this->HasIntrinsics)
  {
    return 1;
  }
  return this->GantryList.empty() ? this->AngleCount : static_cast<int>(this->GantryList.size());
}

std::vector<Pose> RadiographSettings::Poses(vtkImageData* volume) const
{
  if (!this->RTKGeometry.empty() || !this->RTPlan.empty() || !this->MatrixFile.empty())
  {
    return this->FilePoses();
  }
  std::vector<Pose> poses;
  Pose pose;
  pose.Size[0] = this->Detector[0];
  pose.Size[1] = this->Detector[1];
  if (this->HasMatrix || this->HasIntrinsics)
  {
    mcx::PinholeCamera camera;
    if (this->HasMatrix)
    {
      const std::string problem = mcx::ProjectionMatrixProblem(this->Matrix);
      if (!problem.empty())
      {
        Fail("bad --projection-matrix: " + problem);
      }
      std::copy(this->Matrix, this->Matrix + 12, pose.Matrix);
    }
    else
    {
      camera.Fx = this->Intrinsics[0];
      camera.Fy = this->Intrinsics[1];
      camera.Cx = this->Intrinsics[2];
      camera.Cy = this->Intrinsics[3];
      std::copy(this->Extrinsics, this->Extrinsics + 9, camera.R);
      std::copy(this->Extrinsics + 9, this->Extrinsics + 12, camera.T);
      mcx::MatrixFromPinhole(camera, pose.Matrix);
      mcx::PinholeCamera back;
      const std::string problem = mcx::PinholeFromMatrix(pose.Matrix, back);
      if (!problem.empty() || !(camera.Fx > 0 && camera.Fy > 0))
      {
        Fail("bad --intrinsics/--extrinsics: " +
          (problem.empty() ? std::string("fx and fy must be positive") : problem));
      }
      // R must be a rotation: K [R | t] decomposes back to the same R.
      for (int k = 0; k < 9; ++k)
      {
        if (!(std::abs(back.R[k] - camera.R[k]) <= 1e-6))
        {
          Fail("bad --extrinsics: R is not a rotation (orthonormal rows, determinant +1)");
        }
      }
    }
    pose.FocalDistance = 0.0;
    poses.push_back(pose);
    return poses;
  }
  vtkNew<vtkMCXRadiographGeometry> radiograph;
  radiograph->SetSourceToAxisDistance(this->SourceToAxis);
  radiograph->SetSourceToImageDistance(this->SourceToImage);
  radiograph->SetDetectorPixels(this->Detector[0], this->Detector[1]);
  if (this->DetectorSizeGiven)
  {
    radiograph->SetPixelPitch(
      this->DetectorSize[0] / this->Detector[0], this->DetectorSize[1] / this->Detector[1]);
  }
  else
  {
    radiograph->SetPixelPitch(this->Pitch);
  }
  radiograph->SetUseDetectorNormal(this->HasNormal);
  radiograph->SetDetectorNormal(const_cast<double*>(this->Normal));
  radiograph->SetViewUp(const_cast<double*>(this->Up));
  radiograph->SetUseImageCenter(this->HasImageCenter);
  radiograph->SetImageCenter(const_cast<double*>(this->ImageCenter));
  double centre[3];
  Centre(volume, centre);
  radiograph->SetIsocenter(this->HasIsocenter ? this->Isocenter : centre);
  std::vector<double> angles = this->GantryList;
  if (angles.empty())
  {
    for (int k = 0; k < this->AngleCount; ++k)
    {
      angles.push_back(this->Gantry + k * this->AngleStep);
    }
  }
  pose.FocalDistance = this->SourceToAxis;
  const GeometryErrors errors(radiograph);
  for (double angle : angles)
  {
    radiograph->SetGantryAngle(angle);
    if (!radiograph->GetProjectionMatrix(pose.Matrix))
    {
      errors.Fail();
    }
    poses.push_back(pose);
  }
  return poses;
}

vtkSmartPointer<vtkCamera> RadiographSettings::MakeCamera(
  vtkImageData* volume, int size[2], double& spacing) const
{
  if (this->HasMatrix || this->HasIntrinsics || this->DetectorSizeGiven || this->HasImageCenter ||
    this->AngleCount > 1 || !this->GantryList.empty())
  {
    Fail("the viewer shows one cone-beam view of square pixels: --projection-matrix, "
         "--intrinsics, -z, --image-center and sweeps are for mcxray render");
  }
  vtkNew<vtkMCXRadiographGeometry> radiograph;
  radiograph->SetSourceToAxisDistance(this->SourceToAxis);
  radiograph->SetSourceToImageDistance(this->SourceToImage);
  radiograph->SetDetectorPixels(this->Detector[0], this->Detector[1]);
  radiograph->SetPixelPitch(this->Pitch);
  radiograph->SetGantryAngle(this->Gantry);
  radiograph->SetUseDetectorNormal(this->HasNormal);
  radiograph->SetDetectorNormal(const_cast<double*>(this->Normal));
  radiograph->SetViewUp(const_cast<double*>(this->Up));
  double centre[3];
  Centre(volume, centre);
  radiograph->SetIsocenter(this->HasIsocenter ? this->Isocenter : centre);
  auto camera = vtkSmartPointer<vtkCamera>::New();
  const GeometryErrors errors(radiograph);
  if (!radiograph->ConfigureCamera(camera))
  {
    errors.Fail();
  }
  size[0] = this->Detector[0];
  size[1] = this->Detector[1];
  spacing = radiograph->GetPixelSpacingAtIsocenter();
  return camera;
}

// vtkMCXRadiograph and the mapper share the five physics properties.
template <typename Physics>
void RadiographSettings::Configure(Physics* physics) const
{
  physics->SetBeerLambert(this->BeerLambert);
  physics->SetIncidentIntensity(this->IncidentIntensity);
  physics->SetPhotonsPerPixel(this->Photons);
  physics->SetNoiseSeed(this->NoiseSeed);
  physics->SetNegativeLog(this->NegativeLog);
}
template void RadiographSettings::Configure(vtkMCXRadiograph*) const;
template void RadiographSettings::Configure(vtkMCXXRayMapper*) const;

} // namespace mcxapp
