#include "mcxViewCommand.h"

#include "mcxBundledVolume.h"
#include "mcxContainedReader.h"
#include "mcxErrorCapture.h"
#include "mcxFail.h"
#include "mcxHalton.h"
#include "mcxImageOutput.h"
#include "mcxMaterialDecomposition.h"
#include "mcxOptionTable.h"
#include "mcxPolychromaticModel.h"
#include "mcxPolychromaticStage.h"
#include "mcxPreflight.h"
#include "mcxProgressBar.h"
#include "mcxSamplingMethod.h"
#include "mcxSettings.h"
#include "mcxTubeSpectrum.h"
#include "mcxXRayViewer.h"
#include "vtkMCXMemoryCheck.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"
#include "vtksys/SystemTools.hxx"

#include <cstdio>
#include <iostream>
#include <string>

namespace mcxapp
{

namespace
{
const char* const Usage = R"(usage: mcxray view [INPUT] [options]

Opens an interactive X-ray view of a volume: drag to rotate, right-drag or
wheel to zoom, middle-drag to pan. While the view is still the image refines
up to all points; the overlay shows the sample count, the time per frame and
the image's estimated relative error.

INPUT   a volume, as for mcxray render (default: the bundled CT head).

options:
  --tf SPEC          initial transfer function (as for mcxray render; default
                     raw); mu or mu=MU_WATER: the attenuation of all tissue
  --samples N        points in the cloud, rounded up to 2^m - 1 (default 4194303)
  --method M         hybrid (default), mc, qmc, every-voxel (each voxel of
                     non-zero weight once, weighted: no sampling noise; replaces
                     --samples, and + and - do nothing) or view-ordered (hybrid
                     in the pixel order of the view: several times less noise
                     where voxels are much smaller than pixels; a TF edit after
                     a camera move first sorts every voxel for the new view,
                     unless --reorder-angle keeps the order)
  --reorder-angle A  view-ordered: a TF edit after the camera turned about the
                     volume by at most A degrees (0 to 180, default 30) from
                     the view last sorted for keeps that order and projects
                     only the new view's control image (an eighth of the time
                     on 400 M voxels, more error at the same samples); a pan,
                     a zoom or a resize sorts again, as does any move with 0
  --kernel K         tent (default) or box
  --deposit D        footprint (default) or point (see mcxray render --help)
  --seed N           seed of the pseudo-random parts (default 0)
  --threads N        worker threads, at most the cores TBB may use (default: all)
  --memory-limit S   memory budget (e.g. 8G; default: the machine's memory)
  --series N         the N-th series of a DICOM folder that holds several
  --read-timeout S   stop a reader that takes longer than S seconds (default 300)
  --size WxH         window size (default 768x768)
  --sad, --sid, --detector, --pitch, --gantry, --isocenter, --coordinates
                     a cone-beam radiograph view as for mcxray render (the
                     detector's pixels become the window)
  --beer-lambert, --i0 I, --photons N, --noise-seed N, --negative-log
                     radiograph physics as for mcxray render; the TF then
                     selects tissue of mu, as with key b
  --spectrum S       a polychromatic radiograph of CT in HU, as for mcxray
                     render (70kVp,2.5mmAl or a spectrum file): the volume is
                     sampled under the materials' density, each material
                     accumulated from the same points, and the view shows the
                     effective line integral -ln T (key b: the intensity
                     I0 T; the radiograph physics above apply to -ln T); no TF
                     and no TF controls
  --materials M, --detector-material M:MM[:G/CM3], --photon-counting
                     with --spectrum, as for mcxray render
  --screenshot FILE  no window: render off screen until all points count,
                     save the window as FILE (.png) and exit
  --help             this text

controls: sliders for the TF window (centre and width, in data units; while
  one is dragged each frame draws a first image under the window of before,
  and the release refines it and sets the window again);
  keys 1 raw (in a radiograph: all tissue), 2 bone, 3 soft-tissue presets;
  + / - double or halve the points; i inverts the display; b switches the
  radiograph on and off: the Beer-Lambert intensity I0 exp(-line integral of
  mu x TF), mu = 0.02 (1 + HU/1000) per mm (0 at air; --tf mu=MU sets the
  water value), the TF clipped to 0..1 selecting the tissue (a volume not in
  HU takes its lowest value for air, with a warning); p switches parallel /
  perspective; r resets the camera; q quits. The overlay and the sliders
  invert with the film: light on dark air, dark on light air.
)";

const long long DefaultSamples = (1LL << vtkMCXTypes::DefaultSampleExponent) - 1;

// What one option allows depends on another: checked once all are read.
void CheckCombinations(const Settings& settings)
{
  settings.Radiograph.CheckCombinations();
  if (!IsCloudMethod(settings.Method))
  {
    Fail("unknown --method '" + settings.Method +
      "' for view (expected hybrid, mc, qmc, every-voxel or view-ordered)");
  }
  if (settings.Method == "every-voxel" && settings.SamplesGiven)
  {
    Fail("every-voxel takes each voxel of non-zero weight once: leave out --samples");
  }
  if (settings.ReorderAngle >= 0 && settings.Method != "view-ordered")
  {
    Fail("--reorder-angle keeps the order of --method view-ordered: leave it out for " +
      settings.Method);
  }
  CheckKernel(settings.Kernel);
  CheckDeposit(settings.Deposit);
  if (settings.Samples > (1LL << vtkMCXTypes::MaximumPointCloudExponent) - 1)
  {
    Fail("the viewer holds at most 2^30 - 1 points");
  }
  const RadiographSettings& radiograph = settings.Radiograph;
  if (radiograph.Geometry && settings.SizeGiven)
  {
    Fail("the radiograph geometry's --detector sets the window size; leave out --size");
  }
  if (radiograph.Geometry &&
    (radiograph.Detector[0] < 16 || radiograph.Detector[1] < 16 || radiograph.Detector[0] > 8192 ||
      radiograph.Detector[1] > 8192))
  {
    Fail("the viewer's --detector must lie between 16x16 and 8192x8192 pixels");
  }
}

// --spectrum and its options: the render command's refusals that apply to a
// view (which has no stored cloud, no processes and no target error).
void CheckPolychromatic(const Settings& settings)
{
  if (!PolychromaticAsked(settings))
  {
    return;
  }
  if (settings.Method == "every-voxel")
  {
    Fail("--spectrum weighs each drawn point by its voxel's materials: use --method hybrid, mc, "
         "qmc or view-ordered");
  }
  if (settings.Deposit != "footprint")
  {
    Fail("--spectrum needs the footprint deposit (its points are voxel centres, each with its "
         "voxel's materials)");
  }
  if (settings.TF != "raw")
  {
    Fail("--spectrum samples the materials' density (--materials): leave out --tf");
  }
  try
  {
    (void)mcx::PolychromaticModel(mcx::SpectrumFromText(settings.Spectrum),
      mcx::ParseDetector(PolychromaticDetector(settings)),
      mcx::MaterialsFromText(settings.Materials).Names());
  }
  catch (const std::exception& error)
  {
    Fail(error.what());
  }
}

void CheckScreenshot(const std::string& screenshot)
{
  if (vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(screenshot)) !=
    ".png")
  {
    Fail("--screenshot writes .png, not '" + screenshot + "'");
  }
  CheckOutputDirectory(screenshot);
  const std::string nameProblem = OutputNameProblem(screenshot, "--screenshot");
  if (!nameProblem.empty())
  {
    Fail(nameProblem);
  }
}

// The window is the detector when a radiograph geometry is given.
ViewerOptions MakeViewerOptions(const Settings& settings)
{
  ViewerOptions viewer;
  viewer.TransferFunction = settings.TF;
  viewer.Seed = settings.Seed;
  viewer.ReorderAngle = settings.ReorderAngle;
  viewer.SampleExponent = static_cast<int>(mcx::ExponentForSampleCount(settings.Samples));
  viewer.Strategy = StrategyOf(settings.Method);
  viewer.Kernel = KernelOf(settings.Kernel);
  viewer.Deposit = DepositOf(settings.Deposit);
  viewer.OffScreen = !settings.Screenshot.empty();
  const int* size = settings.Radiograph.Geometry ? settings.Radiograph.Detector
    : settings.SizeGiven                         ? settings.Size
                                                 : nullptr;
  if (size)
  {
    viewer.Size[0] = size[0];
    viewer.Size[1] = size[1];
  }
  return viewer;
}

// The radiograph geometry's camera and the physics, when asked for.
void ConfigureRadiograph(
  XRayViewer& view, vtkImageData* volume, const RadiographSettings& radiograph)
{
  if (radiograph.Geometry)
  {
    int size[2];
    double spacing = 0;
    view.GetRenderer()->GetActiveCamera()->DeepCopy(radiograph.MakeCamera(volume, size, spacing));
  }
  radiograph.Configure(view.GetMapper());
  view.FollowRadiographPhysics();
}

// The index is built before the first frame, with a progress bar.
void BuildIndex(XRayViewer& view, const ErrorCapture& capture, ProgressBar& progress)
{
  progress.Watch(view.GetIndex());
  progress.Begin("index");
  view.GetMapper()->UpdateDensityIndex();
  progress.End();
  capture.FailOnWatchedError();
}

// Off screen: refine until every point counts, save the window with the
// X-ray alone (no overlay text, no sliders).
void SaveScreenshot(XRayViewer& view, const ErrorCapture& capture, const std::string& screenshot)
{
  const int renders = view.RefineUntilComplete();
  capture.FailOnWatchedError();
  view.ShowControls(false);
  view.GetRenderWindow()->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(view.GetRenderWindow());
  grab->ReadFrontBufferOff();
  grab->Update();
  std::string error;
  if (!WriteScreenshot(grab->GetOutput(), screenshot, error))
  {
    Fail(error);
  }
  const std::string overlay = view.OverlayText(false);
  std::cout << "view:        " << renders << " renders, " << overlay.substr(0, overlay.find('\n'))
            << "\nscreenshot:  " << screenshot << std::endl;
}
}

int RunView(int argc, char* argv[])
{
  Settings settings;
  settings.Samples = DefaultSamples;
  if (!ParseArguments(argc, argv, Command::View, settings))
  {
    std::printf("%s", Usage);
    return 0;
  }
  CheckCombinations(settings);
  CheckPolychromatic(settings);
  if (!settings.Screenshot.empty())
  {
    CheckScreenshot(settings.Screenshot);
  }
  CheckTransferFunction(settings.TF);
  if (settings.Threads > 0)
  {
    vtkSMPTools::Initialize(settings.Threads);
  }
  if (!vtksys::SystemTools::GetEnv("DISPLAY"))
  {
    // VTK's off-screen windows here are X windows too (no EGL, no OSMesa).
    Fail("no display (DISPLAY is not set): run under an X server, e.g. xvfb-run, also for "
         "--screenshot");
  }
  const std::string input = settings.Input.empty() ? BundledVolumePath() : settings.Input;
  if (!settings.Screenshot.empty())
  {
    CheckOutputIsNotInput(settings.Screenshot, input, "--screenshot");
  }
  ErrorCapture capture; // outlives the view, whose pipeline reports to it
  std::string error;
  mcx::SetMemoryBudget(settings.MemoryLimit);
  vtkSmartPointer<vtkImageData> volume =
    mcxio::ReadVolumeContained(input, ReadOptionsOf(settings), ReadLimitsOf(settings), error);
  if (!volume)
  {
    Fail(error);
  }
  XRayViewer view(volume, MakeViewerOptions(settings));
  if (!view.Error().empty())
  {
    Fail(view.Error());
  }
  ConfigureRadiograph(view, volume, settings.Radiograph);
  if (!settings.Spectrum.empty())
  {
    view.SetPolychromatic(settings.Spectrum, settings.Materials, PolychromaticDetector(settings));
  }
  capture.Watch(view.GetIndex());
  capture.Watch(view.GetSampler());
  ProgressBar progress; // lives while the view runs: its index reports to it
  BuildIndex(view, capture, progress);
  if (settings.Screenshot.empty())
  {
    view.Start();
    return 0;
  }
  SaveScreenshot(view, capture, settings.Screenshot);
  return 0;
}

} // namespace mcxapp
