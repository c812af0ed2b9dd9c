#include "mcxRenderCommand.h"

#include "mcxBundledVolume.h"
#include "mcxCameraSpec.h"
#include "mcxContainedReader.h"
#include "mcxErrorCapture.h"
#include "mcxFail.h"
#include "mcxImageOutput.h"
#include "mcxOptionTable.h"
#include "mcxPreflight.h"
#include "mcxProcesses.h"
#include "mcxProgressBar.h"
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

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

namespace mcxapp
{

namespace
{
const char* const Usage = R"(usage: mcxray render [INPUT] [options]
       mcxray view [INPUT] [options]     (interactive; see mcxray view --help)

Renders a simulated X-ray image (a DRR): per pixel, the mean over the pixel's
area of the line integral of g = TF(density), reconstructed with the chosen
kernel, in TF units times world length (mm for medical data).

The world is DICOM patient space (LPS: x to the patient's left, y posterior,
z to the head) for every format: NIfTI (RAS), NRRD and MetaImage headers are
converted, so the same patient gives the same image from any file.

INPUT   a volume: .vti, .mha/.mhd, .nii/.nii.gz, .nrrd/.nhdr, .vtk, .slc, or a
        DICOM series directory (read with vtk-dicom: sorted by position, in
        patient space, rescaled to HU). Default: the bundled CT head (VTK's
        headsq).

options:
  --tf SPEC             transfer function: value:weight,value:weight,... in data
                        units (held constant beyond its end points), or a preset:
                        %s. Default: raw
  --samples N           number of samples, rounded up to 2^m - 1 (default 4194303)
  --target-error E      choose the sample count for a relative RMS error E (a
                        pilot run of 65535 samples measures the image; up to
                        2^30 - 1 samples); replaces --samples
  --quantization-levels L
                        choose the sample count by the paper's criterion: the
                        mean pixel deviation below one of L grey levels
  --method M            hybrid (default), mc, qmc, every-voxel (each voxel of
                        non-zero weight once, weighted by the TF: no sampling
                        noise while each voxel's footprint reaches at most 16
                        pixels, else a warning; replaces --samples; with
                        --stored-points, a cloud as large as those voxels), or
                        reference (exact, slow)
  --kernel K            tent (trilinear, default) or box (nearest neighbour)
  --deposit D           footprint (default: each sample adds its voxel's kernel
                        integrated over every pixel it reaches; about 4 to 50
                        times less error per sample) or point (the paper's: one
                        count where a random offset lands)
  --seed N              seed of the pseudo-random parts (default 0)
  --threads N           worker threads (default: all cores); results do not depend on it
  --memory-limit SIZE   memory budget (e.g. 8G; default: the machine's memory):
                        volumes, indices, images and clouds that need more are
                        refused before the stage that makes them, naming the size
  --series N            the N-th series of a DICOM folder that holds several (an
                        error lists them when N is missing)
  --read-timeout S      stop a reader that takes longer than S seconds (default
                        300; the volume is read in a child process, so a corrupt
                        file cannot crash or hang mcxray)
  --view AXIS           parallel view along +x, -x, +y, -y, +z or -z (default +z).
                        Image axis 0 runs along the first remaining world axis in
                        x, y, z order, axis 1 along the second; never mirrored.
  --camera P:F:U:KIND   any view: position P, focal point F and view-up U as
                        x,y,z triples, and KIND parallel=SCALE (half the image
                        height in world units) or angle=DEGREES (perspective,
                        vertical view angle), optionally followed by :near=D
                        (perspective: depth where integration starts; default
                        0.001 times the camera distance)
  --sad MM, --sid MM, --detector WxH, --pitch MM, --gantry DEG, --isocenter X,Y,Z
                        a cone-beam radiograph as radiographers give it (any one of
                        these selects it): source-to-axis distance (default 1000),
                        source-to-image distance (1500), detector pixels (512x512)
                        and pitch (0.8), gantry angle (0: source on +x, the
                        patient's left, turning about z towards +y, so 90
                        puts it posterior: plastimatch's angle a is -a
                        here), isocentre (default: the volume's centre).
                        Image columns run along +y at angle 0, rows along +z,
                        as in plastimatch drr; replaces --view, --camera,
                        --size and --pixel-spacing
  --coordinates C       lps (default) or ras (any case): the points of --camera
                        and --isocenter are in RAS (x to the patient's right, y
                        anterior) and are taken to LPS by negating x and y;
                        --view and --gantry name patient directions either way
  --beer-lambert        output the intensity I0 exp(-line integral) (with --tf mu)
  --i0 I                unattenuated intensity I0 (default 1)
  --photons N           quantum noise: N photons reach an unattenuated pixel,
                        counts are Poisson (implies --beer-lambert; default off)
  --noise-seed N        seed of the noise (default 0)
  --negative-log        output -ln(I / I0), the radiologist's display (bone bright)
  --size WxH            image size in pixels (default: 512 along the longer side)
  --pixel-spacing S     pixel size in world units on the detector plane
  --output FILE         .vti (float64 LineIntegral with geometry), .png or .pfm
                        (default: mcxray.png)
  --window LO:HI        PNG grey window in image units (default 0:maximum)
  --bits 8|16           PNG bit depth (default 8)
  --tolerance T         reference method: relative RMS tolerance (default 1e-3)
  --stored-points       store the point cloud (as an interactive view would),
                        then project it, and time the two stages apart; by
                        default samples are projected as they are generated
  --quiet               print nothing but errors
  --help                this text
)";

const long long DefaultSamples = (1LL << vtkMCXTypes::DefaultSampleExponent) - 1;

double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// An absurd but valid sample count is announced with its cost before the
// work: more than about a minute at the projection rate of a 2-core machine
// (about 100 M samples/s per 2 threads, Performance in the README; the
// footprint deposit costs about 4 times as much per sample).
void WarnOfLongRuns(const Settings& settings)
{
  if (settings.Quiet || settings.Method == "reference" || settings.Method == "every-voxel" ||
    settings.TargetError > 0 || settings.QuantizationLevels > 0)
  {
    return;
  }
  const int threads =
    settings.Threads > 0 ? settings.Threads : vtkSMPTools::GetEstimatedNumberOfThreads();
  const double rate = 5.0e7 * std::max(1, threads) / (settings.Deposit == "footprint" ? 4.0 : 1.0);
  const double seconds = static_cast<double>(settings.Samples) / rate;
  if (seconds > 60.0)
  {
    std::ostringstream line;
    line << "mcxray: warning: " << settings.Samples << " samples take about "
         << std::setprecision(3) << (seconds > 7200 ? seconds / 3600 : seconds / 60)
         << (seconds > 7200 ? " hours" : " minutes") << " on " << threads
         << " threads; Ctrl-C stops the run and writes nothing";
    std::cerr << line.str() << std::endl;
  }
}

// What one option allows depends on another: checked once all are read.
void CheckCombinations(const Settings& settings)
{
  if (settings.Method == "view-ordered")
  {
    Fail("view-ordered sorts every voxel for one view to speed up many TF edits: it is a method "
         "of mcxray view; one render would pay the sort (use hybrid or every-voxel)");
  }
  if (!IsCloudMethod(settings.Method) && settings.Method != "reference")
  {
    Fail("unknown --method '" + settings.Method +
      "' (expected hybrid, mc, qmc, every-voxel or reference)");
  }
  CheckKernel(settings.Kernel);
  CheckDeposit(settings.Deposit);
  if (settings.Method == "every-voxel" &&
    (settings.TargetError > 0 || settings.QuantizationLevels > 0 || settings.SamplesGiven))
  {
    Fail("every-voxel takes each voxel of non-zero weight once: leave out --samples, "
         "--target-error and --quantization-levels");
  }
  if ((settings.TargetError > 0 || settings.QuantizationLevels > 0) &&
    (settings.StoredPoints || settings.Method == "reference"))
  {
    Fail("--target-error and --quantization-levels apply to off-line Monte Carlo rendering only");
  }
  if (settings.QuantizationLevels > 65536)
  {
    Fail("--quantization-levels is limited to 65536");
  }
  if (settings.StoredPoints && settings.Method == "reference")
  {
    Fail("--stored-points applies to the Monte Carlo methods, not to reference");
  }
  if (settings.StoredPoints &&
    settings.Samples > (1LL << vtkMCXTypes::MaximumPointCloudExponent) - 1)
  {
    Fail("--stored-points holds at most 2^30 - 1 points; use fewer --samples or the default "
         "off-line projection");
  }
  if (!IsSupportedOutput(settings.Output))
  {
    Fail("unknown output format of '" + settings.Output + "' (expected .vti, .png or .pfm)");
  }
  if (settings.Radiograph.Geometry &&
    (!settings.Camera.empty() || settings.ViewGiven || settings.SizeGiven ||
      settings.PixelSpacing > 0))
  {
    Fail(
      "the radiograph geometry (--sad, --sid, --detector, --pitch, --gantry, --isocenter) replaces "
      "--view, --camera, --size and --pixel-spacing");
  }
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

void Log(const Settings& settings, const std::string& line)
{
  if (!settings.Quiet)
  {
    std::cout << line << std::endl;
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
  {
  }

  int Run(vtkImageData* volume)
  {
    if (this->Options.Radiograph.Geometry)
    {
      this->View.Camera =
        this->Options.Radiograph.MakeCamera(volume, this->Options.Size, this->Options.PixelSpacing);
    }
    this->BuildIndex(volume);
    std::string error;
    vtkSmartPointer<vtkPiecewiseFunction> tf =
      MakeTransferFunction(this->Options.TF, this->DataRange(), error);
    if (!tf)
    {
      Fail(error);
    }
    vtkImageData* projected = this->Project(tf);
    if (!IsFirstProcess())
    {
      return 0; // the image is the first process's: it logs, applies the physics and writes
    }
    this->Write(this->ApplyRadiograph(projected));
    return 0;
  }

private:
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

  vtkImageData* Project(vtkPiecewiseFunction* tf)
  {
    this->Projector = this->MakeProjector();
    vtkMCXProjectorBase* projector = this->Projector;
    projector->SetInputConnection(this->Index->GetOutputPort());
    if (this->Options.StoredPoints)
    {
      projector->SetInputConnection(this->SampleStoredPoints(tf));
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
    this->Progress.Begin(this->Options.Method == "reference" ? "reference" : "projection");
    const auto start = std::chrono::steady_clock::now();
    projector->Update();
    this->Progress.End();
    bool noisy = false; // an every-voxel image with random parts (the projector's warning)
    for (const std::string& warning : this->Capture.Warnings())
    {
      noisy = noisy || warning.find("not without noise") != std::string::npos;
      if (IsFirstProcess())
      {
        std::cerr << "mcxray: warning: " << warning << std::endl;
      }
    }
    this->Capture.FailOnAnyError();
    const double seconds = Seconds(start);
    vtkImageData* image = projector->GetOutput();
    if (IsFirstProcess())
    {
      WarnWhenTheViewMissesTheVolume(image);
      this->LogProjection(image, seconds, noisy);
    }
    return image;
  }

  // An empty image of a volume that holds something: most often a point
  // given in the wrong world (RAS for LPS), said before the image is written.
  static void WarnWhenTheViewMissesTheVolume(vtkImageData* image)
  {
    vtkDataArray* values = image->GetPointData()->GetScalars();
    vtkDataArray* integral = image->GetFieldData()->GetArray(vtkMCXTypes::IntegralName());
    if (values && integral && integral->GetTuple1(0) > 0 && values->GetRange()[1] == 0)
    {
      std::cerr << "mcxray: warning: the image holds none of the volume: the view misses it "
                   "(check --camera, --isocenter and --coordinates)"
                << std::endl;
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
      line << (this->Options.StoredPoints ? "projection:  "
                                          : "sampling + projection (off-line, fused): ")
           << seconds << " s (" << static_cast<long long>(samples);
      if (this->Options.Method == "every-voxel")
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
  vtkImageData* ApplyRadiograph(vtkImageData* image)
  {
    const RadiographSettings& physics = this->Options.Radiograph;
    this->Radiograph = vtkSmartPointer<vtkMCXRadiograph>::New();
    physics.Configure(this->Radiograph.GetPointer());
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

  void Write(vtkImageData* image) const
  {
    const auto start = std::chrono::steady_clock::now();
    std::string error;
    if (!WriteImage(image, this->Options.Output, this->Options.Window, error))
    {
      Fail(error);
    }
    this->Log("output:      " + this->Options.Output + "  written " +
      std::to_string(Seconds(start)) + " s");
  }

  Settings Options; // a copy: the radiograph geometry sets the size and spacing
  ErrorCapture& Capture;
  ViewChoice View;
  ProgressBar Progress;
  double Range[2] = { 0, 0 };
  vtkNew<vtkMCXDensityIndex> Index;
  vtkSmartPointer<vtkMCXPointSampler> Sampler;
  vtkSmartPointer<vtkMCXProjectorBase> Projector;
  vtkSmartPointer<vtkMCXRadiograph> Radiograph;
};
}

void PrintRenderUsage()
{
  std::printf(Usage, TransferFunctionPresetHelp());
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
  CheckOutputDirectory(settings.Output);
  CheckOutputIsNotInput(
    settings.Output, settings.Input.empty() ? BundledVolumePath() : settings.Input, "--output");
  CheckTransferFunction(settings.TF);
  const ViewChoice view = ChooseView(settings);
  WarnOfLongRuns(settings);
  vtkSmartPointer<vtkImageData> volume = ReadInput(settings);
  RenderPipeline pipeline(settings, capture, view);
  return pipeline.Run(volume);
}

} // namespace mcxapp
