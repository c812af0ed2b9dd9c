#include "mcxRenderCommand.h"

#include "mcxBundledVolume.h"
#include "mcxCameraSpec.h"
#include "mcxContainedReader.h"
#include "mcxErrorCapture.h"
#include "mcxFail.h"
#include "mcxImageOutput.h"
#include "mcxOptionTable.h"
#include "mcxPartialFileGuard.h"
#include "mcxPolychromaticStage.h"
#include "mcxPoseOutput.h"
#include "mcxPreflight.h"
#include "mcxProcesses.h"
#include "mcxProgressBar.h"
#include "mcxRenderChecks.h"
#include "mcxSamplingMethod.h"
#include "mcxSettings.h"
#include "mcxTransferFunctionSpec.h"
#include "vtkMCXDistributed.h"
#include "vtkMCXMemoryCheck.h"

#include "vtkAlgorithmOutput.h"
#include "vtkCamera.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPatientSpace.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"
#include "vtkMCXRadiograph.h"
#include "vtkMCXReferenceProjector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace mcxapp
{

namespace
{

const long long DefaultSamples = (1LL << vtkMCXTypes::DefaultSampleExponent) - 1;

double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// The camera of --camera, or else the detector axes of the --view axis,
// checked before the volume is read. (A radiograph geometry's camera needs
// the volume: it comes once that is read.)
struct ViewChoice
{
  vtkSmartPointer<vtkCamera> Camera;
  double DetectorU[3] = { 0, 0, 0 };
  double DetectorV[3] = { 0, 0, 0 };
};

// A camera given in RAS, taken to patient space (LPS): x and y of its
// position, focal point and view-up negated.
void FlipCameraRightAnterior(vtkCamera* camera)
{
  double position[3], focal[3], up[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  camera->GetViewUp(up);
  for (double* point : { position, focal, up })
  {
    vtkMCXPatientSpace::FlipRightAnterior(point);
  }
  camera->SetPosition(position);
  camera->SetFocalPoint(focal);
  camera->SetViewUp(up);
}

ViewChoice ChooseView(const Settings& settings)
{
  ViewChoice view;
  if (!settings.Camera.empty())
  {
    view.Camera = ParseCamera(settings.Camera);
    if (settings.RASCoordinates)
    {
      FlipCameraRightAnterior(view.Camera);
    }
  }
  else
  {
    AxisViewDetector(settings.View, view.DetectorU, view.DetectorV);
  }
  return view;
}

// "" when line was written to stdout (or --quiet); else why not.
std::string TryLog(const Settings& settings, const std::string& line)
{
  if (settings.Quiet)
  {
    return std::string();
  }
  errno = 0;
  std::cout << line << std::endl;
  if (std::cout)
  {
    return std::string();
  }
  // A closed pipe (mcxray render ... | true): SIGPIPE is ignored
  // (mcxPartialFileGuard), so the write fails and the run stops.
  const int cause = errno;
  std::cout.clear();
  return "cannot write to standard output" +
    (cause != 0 ? ": " + std::string(std::strerror(cause)) : std::string());
}

void Log(const Settings& settings, const std::string& line)
{
  const std::string problem = TryLog(settings, line);
  if (!problem.empty())
  {
    Fail(problem);
  }
}

vtkSmartPointer<vtkImageData> ReadInput(const Settings& settings)
{
  const std::string input = settings.Input.empty() ? BundledVolumePath() : settings.Input;
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  vtkSmartPointer<vtkImageData> volume =
    mcxio::ReadVolumeContained(input, ReadOptionsOf(settings), ReadLimitsOf(settings), error);
  if (!volume)
  {
    if (!IsFirstProcess())
    {
      // Each process reads for itself: a file that one of them cannot read
      // (another node's copy) is said by that one.
      std::cerr << "mcxray: error (process " << ProcessRank() << " of " << NumberOfProcesses()
                << "): " << error << std::endl;
    }
    Fail(error);
  }
  int dims[3];
  volume->GetDimensions(dims);
  std::ostringstream line;
  line << "input:       " << input << " (" << dims[0] << "x" << dims[1] << "x" << dims[2] << ", "
       << volume->GetPointData()->GetScalars()->GetDataTypeAsString() << ")  read "
       << Seconds(start) << " s";
  Log(settings, line.str());
  return volume;
}

// The render of a volume, stage by stage: index, (sample,) project,
// radiograph physics, write. Each stage logs a line unless --quiet; an
// error from a watched algorithm, or else from VTK itself, ends the run.
class RenderPipeline
{
public:
  RenderPipeline(const Settings& settings, ErrorCapture& capture, const ViewChoice& view)
    : Options(settings)
    , Capture(capture)
    , View(view)
    , Polychromatic(settings)
  {
  }

  int Run(vtkImageData* volume)
  {
    std::vector<Pose> poses;
    if (this->Options.Radiograph.Geometry)
    {
      poses = this->Options.Radiograph.Poses(volume);
    }
    this->BuildIndex(volume);
    std::string error;
    vtkSmartPointer<vtkPiecewiseFunction> tf = this->Polychromatic.Active()
      ? vtkSmartPointer<vtkPiecewiseFunction>(this->Polychromatic.Density())
      : MakeTransferFunction(this->Options.TF, this->DataRange(), error);
    if (!tf)
    {
      Fail(error);
    }
    this->WarnOfUnphysicalUnits();
    // One read and one index (and with --stored-points one cloud): every
    // pose from them, each image written (or kept in the stack) as it is
    // made. Without --stored-points each pose samples as it projects, as it
    // would alone: a stored cloud's footprints round differently, so only
    // the fused path gives each pose's image of a run of that pose alone.
    const int count = static_cast<int>(std::max<std::size_t>(1, poses.size()));
    this->SetUpProjector(tf);
    std::unique_ptr<PoseStack> stack;
    if (count > 1 && WritesStack(this->Options.Output) && IsFirstProcess())
    {
      stack.reset(new PoseStack(count, poses[0].Size, this->Options.Output));
    }
    std::vector<PoseRecord> records;
    // Every pose's image (or their stack) and the geometry file, or none.
    HoldOutputs(static_cast<std::size_t>(count) + 2);
    for (int k = 0; k < count; ++k)
    {
      const Pose* pose = poses.empty() ? nullptr : &poses[k];
      vtkImageData* image = this->Project(pose, k, count);
      if (!IsFirstProcess())
      {
        continue; // the image is the first process's: it logs, applies the physics and writes
      }
      image = this->Polychromatic.Active() ? this->PolychromaticRadiograph(image, k)
                                           : this->ApplyRadiograph(image, k);
      records.push_back(RecordOf(image));
      if (stack)
      {
        stack->Add(k, image);
      }
      else
      {
        this->Write(
          image, count > 1 ? NumberedOutput(this->Options.Output, k) : this->Options.Output);
      }
    }
    if (!IsFirstProcess())
    {
      return 0;
    }
    if (stack)
    {
      this->Write(stack->GetImage(), this->Options.Output);
      if (!stack->Warning().empty())
      {
        this->Warnings.push_back(stack->Warning());
      }
    }
    this->WriteGeometry(records);
    if (!CommitHeldOutputs(error))
    {
      Fail(error);
    }
    // Warnings only once the run has succeeded: a failing run says one line.
    for (const std::string& warning : this->Warnings)
    {
      std::cerr << "mcxray: warning: " << warning << std::endl;
    }
    return 0;
  }

private:
  // A radiograph takes attenuation, and mu and the materials take CT in
  // HU: a radiograph of raw values, and values with no air (none at or
  // below -500), which are read as HU all the same as the formula says (a
  // water phantom's image stays exact), are said to be.
  void WarnOfUnphysicalUnits()
  {
    const std::string& tf = this->Options.TF;
    const RadiographSettings& physics = this->Options.Radiograph;
    const double* range = this->DataRange();
    // Values already in attenuation per mm (or per cm) span far less than
    // 100: raw, value - minimum, is then their line integral.
    if (tf == "raw" && !this->Polychromatic.Active() && range[1] - range[0] > 100.0 &&
      (physics.BeerLambert || physics.Photons > 0 || physics.NegativeLog))
    {
      std::ostringstream text;
      text << "the radiograph takes line integrals of attenuation per mm (--tf mu): --tf raw "
              "weighs the values "
           << range[0] << " .. " << range[1]
           << " as they are, so exp(-those) is near 0 in tissue, a silhouette";
      this->Warnings.push_back(text.str());
    }
    const std::string note = NoAirNote(range);
    if (note.empty())
    {
      return;
    }
    if (this->Polychromatic.Active())
    {
      this->Warnings.push_back(
        "--spectrum's materials take CT in HU, but " + note + ": read as HU all the same");
    }
    else if (IsAttenuationSpec(tf))
    {
      this->Warnings.push_back(
        "--tf " + tf + " takes CT in HU, but " + note + ": read as HU all the same");
    }
  }

  void Log(const std::string& line) const { mcxapp::Log(this->Options, line); }

  void BuildIndex(vtkImageData* volume)
  {
    this->Index->SetInputData(volume);
    this->Capture.Watch(this->Index);
    this->Watch(this->Index);
    this->Progress.Begin("index");
    const auto start = std::chrono::steady_clock::now();
    vtkMultiProcessController* controller = DistributedController();
    if (controller)
    {
      // This process's z-slab, as the projector will ask for it.
      int whole[6], slab[6];
      volume->GetExtent(whole);
      mcx::ZSlabExtent(
        whole, controller->GetLocalProcessId(), controller->GetNumberOfProcesses(), slab);
      this->Index->UpdateExtent(slab);
    }
    else
    {
      this->Index->Update();
    }
    this->Progress.End();
    this->Capture.FailOnAnyError();
    const double seconds = Seconds(start);
    int dims[3];
    this->Index->GetOutput()->GetDimensions(dims);
    std::ostringstream line;
    line << "index:       " << seconds << " s (" << this->Levels()->GetNumberOfTuples()
         << " density levels, " << static_cast<double>(dims[0]) * dims[1] * dims[2] / seconds / 1e6
         << " M voxels/s"
         << (controller ? "; the first of " + std::to_string(NumberOfProcesses()) +
                  " processes' z-slabs: " + std::to_string(dims[2]) + " slices"
                        : std::string())
         << ")";
    this->Log(line.str());
  }

  // Progress bars on the first process only.
  void Watch(vtkAlgorithm* algorithm)
  {
    if (IsFirstProcess())
    {
      this->Progress.Watch(algorithm);
    }
  }

  vtkDataArray* Levels() const
  {
    return this->Index->GetOutput()->GetFieldData()->GetArray(
      vtkMCXTypes::LevelValuesName());
  }

  // The lowest and highest density level (what the raw TF spans), over
  // every process's slab.
  const double* DataRange()
  {
    vtkDataArray* levels = this->Levels();
    const double inf = std::numeric_limits<double>::infinity();
    double range[2] = { inf, -inf };
    if (levels->GetNumberOfTuples() > 0)
    {
      range[0] = levels->GetTuple1(0);
      range[1] = levels->GetTuple1(levels->GetNumberOfTuples() - 1);
    }
    if (vtkMultiProcessController* controller = DistributedController())
    {
      double all[2];
      controller->AllReduce(&range[0], &all[0], 1, vtkCommunicator::MIN_OP);
      controller->AllReduce(&range[1], &all[1], 1, vtkCommunicator::MAX_OP);
      range[0] = all[0];
      range[1] = all[1];
    }
    if (range[0] <= range[1])
    {
      this->Range[0] = range[0];
      this->Range[1] = range[1];
    }
    return this->Range;
  }

  vtkSmartPointer<vtkMCXProjectorBase> MakeProjector() const
  {
    if (this->Options.Method == "reference")
    {
      auto reference = vtkSmartPointer<vtkMCXReferenceProjector>::New();
      reference->SetRelativeTolerance(this->Options.Tolerance);
      return reference;
    }
    auto monteCarlo = vtkSmartPointer<vtkMCXProjector>::New();
    monteCarlo->SetNumberOfSamples(this->Options.Samples);
    monteCarlo->SetStrategy(StrategyOf(this->Options.Method));
    monteCarlo->SetSeed(this->Options.Seed);
    monteCarlo->SetDeposit(DepositOf(this->Options.Deposit));
    monteCarlo->SetTargetRelativeError(this->Options.TargetError);
    monteCarlo->SetTargetQuantizationLevels(this->Options.QuantizationLevels);
    monteCarlo->SetChooseDepositForTarget(!this->Options.DepositGiven);
    return monteCarlo;
  }

  // --stored-points: the point cloud an interactive view would hold, timed
  // apart from its projection.
  vtkAlgorithmOutput* SampleStoredPoints(vtkPiecewiseFunction* tf)
  {
    this->Sampler = vtkSmartPointer<vtkMCXPointSampler>::New();
    vtkMCXPointSampler* sampler = this->Sampler;
    sampler->SetInputConnection(this->Index->GetOutputPort());
    sampler->SetTransferFunction(tf);
    sampler->SetNumberOfSamples(this->Options.Samples);
    sampler->SetStrategy(StrategyOf(this->Options.Method));
    sampler->SetKernel(KernelOf(this->Options.Kernel));
    sampler->SetDeposit(DepositOf(this->Options.Deposit));
    sampler->SetSeed(this->Options.Seed);
    this->Capture.Watch(sampler);
    this->Watch(sampler);
    this->Progress.Begin("sampling");
    const auto start = std::chrono::steady_clock::now();
    sampler->Update();
    this->Progress.End();
    this->Capture.FailOnAnyError();
    const double seconds = Seconds(start);
    std::ostringstream line;
    line << "sampling:    " << seconds << " s (" << sampler->GetOutput()->GetNumberOfPoints()
         << " stored points, " << sampler->GetOutput()->GetNumberOfPoints() / seconds / 1e6
         << " M points/s)";
    this->Log(line.str());
    return sampler->GetOutputPort();
  }

  void SetUpProjector(vtkPiecewiseFunction* tf)
  {
    this->Projector = this->MakeProjector();
    vtkMCXProjectorBase* projector = this->Projector;
    projector->SetInputConnection(this->Index->GetOutputPort());
    if (this->Options.StoredPoints)
    {
      projector->SetInputConnection(this->SampleStoredPoints(tf));
    }
    if (this->Polychromatic.Active())
    {
      this->Log(this->Polychromatic.Describe());
      this->Polychromatic.SplitIntoChannels(vtkMCXProjector::SafeDownCast(projector));
    }
    projector->SetTransferFunction(tf);
    projector->SetKernel(KernelOf(this->Options.Kernel));
    projector->SetImageSize(this->Options.Size[0], this->Options.Size[1]);
    projector->SetPixelSpacing(this->Options.PixelSpacing);
    projector->SetCamera(this->View.Camera);
    projector->SetDetectorAxisU(this->View.DetectorU);
    projector->SetDetectorAxisV(this->View.DetectorV);
    this->Capture.Watch(projector);
    this->Watch(projector);
  }

  // The polychromatic radiograph of pose k's projection, split into the
  // materials' channels: the spectrum's model per pixel.
  vtkImageData* PolychromaticRadiograph(vtkImageData* channels, int k)
  {
    std::string line;
    vtkImageData* image = this->Polychromatic.Radiograph(channels, this->Options, k, line);
    this->Log(line);
    return image;
  }

  // The image of pose k of count (null: the view of --view or --camera).
  vtkImageData* Project(const Pose* pose, int k, int count)
  {
    vtkMCXProjectorBase* projector = this->Projector;
    if (pose)
    {
      projector->SetUseProjectionMatrix(true);
      projector->SetProjectionMatrix(pose->Matrix);
      projector->SetImageSize(pose->Size[0], pose->Size[1]);
      projector->SetFocalPlaneDistance(pose->FocalDistance);
    }
    std::string stage = this->Options.Method == "reference" ? "reference" : "projection";
    if (count > 1)
    {
      stage += " " + std::to_string(k + 1) + "/" + std::to_string(count);
    }
    this->Progress.Begin(stage, k, count);
    const auto start = std::chrono::steady_clock::now();
    projector->Update();
    this->Progress.End();
    this->Capture.FailOnAnyError();
    bool noisy = false; // an every-voxel image with random parts (the projector's warning)
    for (const std::string& warning : this->Capture.Warnings())
    {
      noisy = noisy || warning.find("not without noise") != std::string::npos;
      this->Warnings.push_back(warning);
    }
    const double seconds = Seconds(start);
    vtkImageData* image = projector->GetOutput();
    if (IsFirstProcess())
    {
      this->WarnWhenTheViewMissesTheVolume(image);
      this->LogProjection(image, seconds, noisy);
    }
    return image;
  }

  // An empty image of a volume that holds something: most often a point
  // given in the wrong world (RAS for LPS), said before the image is written.
  void WarnWhenTheViewMissesTheVolume(vtkImageData* image)
  {
    vtkDataArray* values = image->GetPointData()->GetScalars();
    vtkDataArray* integral = image->GetFieldData()->GetArray(vtkMCXTypes::IntegralName());
    if (values && integral && integral->GetTuple1(0) > 0 && values->GetRange()[1] == 0)
    {
      this->Warnings.emplace_back("the image holds none of the volume: the view misses it "
                                  "(check --camera, --isocenter and --coordinates)");
    }
  }

  void LogProjection(vtkImageData* image, double seconds, bool noisy) const
  {
    vtkFieldData* fields = image->GetFieldData();
    std::ostringstream line;
    if (this->Options.Method == "reference")
    {
      line << "reference:   " << seconds << " s (exact line integrals, "
           << fields->GetArray("RaysPerPixelAxis")->GetTuple1(0)
           << "^2 rays per pixel, estimated relative error "
           << fields->GetArray(vtkMCXTypes::EstimatedRelativeErrorName())->GetTuple1(0)
           << ")";
    }
    else
    {
      const double samples = fields->GetArray(vtkMCXTypes::SampleCountName())->GetTuple1(0);
      // The target's choice, when it made one (an index input's: its field data say so).
      const bool chosen = this->Projector->IsA("vtkMCXProjector") &&
        static_cast<vtkMCXProjector*>(this->Projector.Get())->GetChooseDepositForTarget() &&
        (this->Options.TargetError > 0 || this->Options.QuantizationLevels > 0) &&
        fields->GetArray(vtkMCXTypes::DepositName());
      const bool everyVoxel = fields->GetArray(vtkMCXTypes::StrategyName())
        ? fields->GetArray(vtkMCXTypes::StrategyName())->GetTuple1(0) == vtkMCXTypes::EVERY_VOXEL
        : this->Options.Method == "every-voxel";
      line << (this->Options.StoredPoints ? "projection:  "
                                          : "sampling + projection (off-line, fused): ")
           << seconds << " s (";
      if (chosen) // the target's choice, by a pilot of each deposit
      {
        line << "chose "
             << (everyVoxel ? "every voxel once"
                            : std::string(vtkMCXTypes::DepositCommandName(static_cast<int>(
                                fields->GetArray(vtkMCXTypes::DepositName())->GetTuple1(0)))) +
                      " deposit")
             << " by measured error per second; ";
      }
      line << static_cast<long long>(samples);
      if (everyVoxel)
      {
        line << (noisy ? " voxels, each once, with random parts: their noise is not estimated)"
                       : " voxels, each once: no sampling error to estimate)");
      }
      else
      {
        line << " samples, " << samples / seconds / 1e6
             << " M samples/s, estimated relative RMS error "
             << fields->GetArray(vtkMCXTypes::EstimatedRelativeErrorName())->GetTuple1(0)
             << ")";
      }
    }
    this->Log(line.str());
    int size[3];
    image->GetDimensions(size);
    const double* range = image->GetPointData()->GetScalars()->GetRange();
    std::ostringstream geometry;
    geometry << "image:       " << size[0] << "x" << size[1] << " pixels of "
             << image->GetSpacing()[0] << " x " << image->GetSpacing()[1] << ", LineIntegral range "
             << range[0] << " .. " << range[1] << " (TF units x length)";
    this->Log(geometry.str());
  }

  // The physics after accumulation, only what was asked for.
  // Pose k's noise has the seed --noise-seed + k: the poses of a sweep are
  // independent exposures (as the Python API's), and pose k alone with
  // --noise-seed N + k is the same image.
  vtkImageData* ApplyRadiograph(vtkImageData* image, int k)
  {
    const RadiographSettings& physics = this->Options.Radiograph;
    this->Radiograph = vtkSmartPointer<vtkMCXRadiograph>::New();
    physics.Configure(this->Radiograph.GetPointer());
    this->Radiograph->SetNoiseSeed(physics.NoiseSeed + k);
    if (!this->Radiograph->HasEffects())
    {
      return image;
    }
    this->Radiograph->SetInputData(image);
    const auto start = std::chrono::steady_clock::now();
    this->Radiograph->Update();
    vtkImageData* result = this->Radiograph->GetOutput();
    const double* range = result->GetPointData()->GetScalars()->GetRange();
    std::ostringstream line;
    line << "radiograph:  " << Seconds(start) << " s ("
         << (physics.NegativeLog ? "-ln(I/I0)" : "I = I0 exp(-line integral)")
         << (physics.Photons > 0
                ? ", Poisson noise of " + std::to_string(physics.Photons) + " photons per pixel"
                : "")
         << "), range " << range[0] << " .. " << range[1];
    this->Log(line.str());
    return result;
  }

  void WriteGeometry(const std::vector<PoseRecord>& poses) const
  {
    const std::string& geometry = this->Options.OutputGeometry;
    std::string error;
    if (geometry.empty())
    {
      return;
    }
    if (!WritePoseGeometry(poses, geometry, error))
    {
      Fail(error);
    }
    this->Log("geometry:    " + geometry + " (" + std::to_string(poses.size()) +
      (poses.size() == 1 ? " pose)" : " poses)"));
  }

  void Write(vtkImageData* image, const std::string& path) const
  {
    const auto start = std::chrono::steady_clock::now();
    std::string error;
    // The last line before the rename: a closed stdout leaves no image.
    const auto logLine = [&]
    {
      return TryLog(this->Options,
        "output:      " + path + "  written " + std::to_string(Seconds(start)) + " s");
    };
    if (!WriteImage(image, path, this->Options.Window, error, logLine))
    {
      Fail(error);
    }
  }

  Settings Options; // a copy: the radiograph geometry sets the size and spacing
  ErrorCapture& Capture;
  ViewChoice View;
  ProgressBar Progress;
  double Range[2] = { 0, 0 };
  std::vector<std::string> Warnings; // said after the image is written
  vtkNew<vtkMCXDensityIndex> Index;
  vtkSmartPointer<vtkMCXPointSampler> Sampler;
  vtkSmartPointer<vtkMCXProjectorBase> Projector;
  vtkSmartPointer<vtkMCXRadiograph> Radiograph;
  PolychromaticStage Polychromatic;
};
}

int RunRender(int argc, char* argv[])
{
  Settings settings;
  settings.Samples = DefaultSamples;
  if (!ParseArguments(argc, argv, Command::Render, settings))
  {
    if (IsFirstProcess())
    {
      PrintRenderUsage();
    }
    return 0;
  }
  // Under MPI the first process alone prints and writes.
  settings.Quiet = settings.Quiet || !IsFirstProcess();
  CheckCombinations(settings);
  ErrorCapture capture;
  if (settings.Threads > 0)
  {
    vtkSMPTools::Initialize(settings.Threads);
  }
  mcx::SetMemoryBudget(settings.MemoryLimit);
  CheckOutputs(settings);
  CheckTransferFunction(settings.TF);
  {
    PolychromaticStage check(settings); // its options' errors before any output
  }
  const ViewChoice view = ChooseView(settings);
  WarnOfLongRuns(settings);
  vtkSmartPointer<vtkImageData> volume = ReadInput(settings);
  RenderPipeline pipeline(settings, capture, view);
  return pipeline.Run(volume);
}

} // namespace mcxapp
