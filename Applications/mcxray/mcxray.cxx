// mcxray: simulated X-ray images of CT and MRI volumes by hybrid Monte Carlo
// volume rendering, from the command line.
#include "mcxHalton.h"
#include "mcxImageOutput.h"
#include "mcxTransferFunctionSpec.h"
#include "mcxVolumeReader.h"
#include "mcxXRayViewer.h"

#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"
#include "vtkMCXRadiograph.h"
#include "vtkMCXRadiographGeometry.h"
#include "vtkMCXReferenceProjector.h"
#include "vtkMCXXRayMapper.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkWindowToImageFilter.h"
#include "vtkSMPTools.h"
#include "vtksys/SystemTools.hxx"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
const char* const Usage = R"(usage: mcxray render [INPUT] [options]
       mcxray view [INPUT] [options]     (interactive; see mcxray view --help)

Renders a simulated X-ray image (a DRR): per pixel, the mean over the pixel's
area of the line integral of g = TF(density), reconstructed with the chosen
kernel, in TF units times world length (mm for medical data).

INPUT   a volume: .vti, .mha/.mhd, .nii/.nii.gz, .nrrd/.nhdr, .vtk, .slc, or a
        DICOM series directory. Default: the bundled CT head (VTK's headsq).

options:
  --tf SPEC             transfer function: value:weight,value:weight,... in data
                        units (held constant beyond its end points), or a preset:
                        %s. Default: raw
  --samples N           number of samples, rounded up to 2^m - 1 (default 16777215)
  --target-error E      choose the sample count for a relative RMS error E (a
                        pilot run of 65535 samples measures the image; up to
                        2^30 - 1 samples); replaces --samples
  --quantization-levels L
                        choose the sample count by the paper's criterion: the
                        mean pixel deviation below one of L grey levels
  --method M            hybrid (default), mc, qmc, or reference (exact, slow)
  --kernel K            tent (trilinear, default) or box (nearest neighbour)
  --seed N              seed of the pseudo-random parts (default 0)
  --threads N           worker threads (default: all cores); results do not depend on it
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
                        and pitch (0.8), gantry angle (0: source on +x, turning
                        about z), isocentre (default: the volume's centre). Image
                        columns run along +y at angle 0, rows along +z, as in
                        plastimatch drr; replaces --view, --camera, --size and
                        --pixel-spacing
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

const char* const ViewUsage = R"(usage: mcxray view [INPUT] [options]

Opens an interactive X-ray view of a volume: drag to rotate, right-drag or
wheel to zoom, middle-drag to pan. While the view is still the image refines
up to all points; the overlay shows the sample count, the time per frame and
the image's estimated relative error.

INPUT   a volume, as for mcxray render (default: the bundled CT head).

options:
  --tf SPEC          initial transfer function (as for mcxray render; default raw)
  --samples N        points in the cloud, rounded up to 2^m - 1 (default 4194303)
  --method M         hybrid (default), mc or qmc
  --kernel K         tent (default) or box
  --seed N           seed of the pseudo-random parts (default 0)
  --threads N        worker threads (default: all cores)
  --size WxH         window size (default 768x768)
  --sad, --sid, --detector, --pitch, --gantry, --isocenter
                     a cone-beam radiograph view as for mcxray render (the
                     detector's pixels become the window)
  --beer-lambert, --i0 I, --photons N, --noise-seed N, --negative-log
                     radiograph physics as for mcxray render (with --tf mu)
  --screenshot FILE  no window: render off screen until all points count,
                     save the window as FILE (.png) and exit
  --help             this text

controls: sliders for the TF window (centre and width, in data units);
  keys 1 raw, 2 bone, 3 soft-tissue presets; + / - double or halve the points;
  i inverts the display; b switches Beer-Lambert intensity on and off;
  p switches parallel / perspective; r resets the camera; q quits.
)";


[[noreturn]] void Fail(const std::string& message)
{
  std::cerr << "mcxray: error: " << message << std::endl;
  std::exit(2);
}

double ParseNumber(const std::string& text, const std::string& option)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value))
  {
    Fail("bad value '" + text + "' for " + option);
  }
  return value;
}

long long ParseInteger(const std::string& text, const std::string& option, long long minimum)
{
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || value < minimum)
  {
    Fail("bad value '" + text + "' for " + option + " (expected an integer >= " + std::to_string(minimum) + ")");
  }
  return value;
}

std::vector<std::string> Split(const std::string& text, char separator)
{
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, separator))
  {
    parts.push_back(part);
  }
  return parts;
}

// "WxH" with each side in [smallest, largest].
void ParseSize(const std::string& text, int smallest, int largest, int size[2])
{
  const std::vector<std::string> parts = Split(text, 'x');
  if (parts.size() != 2)
  {
    Fail("bad --size '" + text + "' (expected WxH, e.g. 512x512)");
  }
  for (int k = 0; k < 2; ++k)
  {
    size[k] = static_cast<int>(ParseInteger(parts[k], "--size", smallest));
    if (size[k] > largest)
    {
      Fail("--size is limited to " + std::to_string(largest) + " pixels per side");
    }
  }
}

void ParseTriple(const std::string& text, double out[3], const std::string& what)
{
  const std::vector<std::string> parts = Split(text, ',');
  if (parts.size() != 3)
  {
    Fail("bad --camera " + what + " '" + text + "' (expected x,y,z)");
  }
  for (int a = 0; a < 3; ++a)
  {
    out[a] = ParseNumber(parts[a], "--camera " + what);
  }
}

// The sampler's constants for --method (hybrid, mc, qmc) and --kernel.
int StrategyOf(const std::string& method)
{
  return method == "mc" ? vtkMCXPointSampler::MONTE_CARLO
    : method == "qmc"   ? vtkMCXPointSampler::QUASI_MONTE_CARLO
                        : vtkMCXPointSampler::HYBRID;
}

int KernelOf(const std::string& kernel)
{
  return kernel == "box" ? vtkMCXPointSampler::BOX : vtkMCXPointSampler::TENT;
}

void CheckKernel(const std::string& kernel)
{
  if (kernel != "tent" && kernel != "box")
  {
    Fail("unknown --kernel '" + kernel + "' (expected tent or box)");
  }
}

// The radiograph geometry and physics options, shared by render and view;
// each is off unless asked for.
struct RadiographOptions
{
  bool Geometry = false; // any of --sad, --sid, --detector, --pitch, --gantry, --isocenter
  double SourceToAxis = 1000.0;
  double SourceToImage = 1500.0;
  int Detector[2] = { 512, 512 };
  double Pitch = 0.8;
  double Gantry = 0.0;
  bool HasIsocenter = false;
  double Isocenter[3] = { 0, 0, 0 };
  bool BeerLambert = false;
  double IncidentIntensity = 1.0;
  double Photons = 0.0;
  long long NoiseSeed = 0;
  bool NegativeLog = false;

  bool ParseFlag(const std::string& arg)
  {
    if (arg == "--beer-lambert" || arg == "--negative-log")
    {
      (arg == "--beer-lambert" ? this->BeerLambert : this->NegativeLog) = true;
      return true;
    }
    return false;
  }

  bool ParseOption(const std::string& arg, const std::string& value)
  {
    if (arg == "--sad" || arg == "--sid" || arg == "--pitch")
    {
      const double distance = ParseNumber(value, arg);
      if (!(distance > 0))
      {
        Fail(arg + " must be positive");
      }
      (arg == "--sad" ? this->SourceToAxis : arg == "--sid" ? this->SourceToImage : this->Pitch) = distance;
      this->Geometry = true;
    }
    else if (arg == "--detector")
    {
      ParseSize(value, 1, 65536, this->Detector);
      this->Geometry = true;
    }
    else if (arg == "--gantry")
    {
      this->Gantry = ParseNumber(value, arg);
      this->Geometry = true;
    }
    else if (arg == "--isocenter")
    {
      ParseTriple(value, this->Isocenter, "isocenter");
      this->HasIsocenter = true;
      this->Geometry = true;
    }
    else if (arg == "--i0")
    {
      this->IncidentIntensity = ParseNumber(value, arg);
      if (!(this->IncidentIntensity > 0))
      {
        Fail("--i0 must be positive");
      }
    }
    else if (arg == "--photons")
    {
      this->Photons = ParseNumber(value, arg);
      if (!(this->Photons > 0) || this->Photons > 1e15)
      {
        Fail("--photons must lie in (0, 1e15]");
      }
    }
    else if (arg == "--noise-seed")
    {
      this->NoiseSeed = ParseInteger(value, arg, 0);
    }
    else
    {
      return false;
    }
    return true;
  }

  /// The camera of the radiograph geometry (isocentre: the volume's centre
  /// unless given); sets the image size and the pixel spacing to the detector's.
  vtkSmartPointer<vtkCamera> MakeCamera(vtkImageData* volume, int size[2], double& spacing) const
  {
    vtkNew<vtkMCXRadiographGeometry> radiograph;
    radiograph->SetSourceToAxisDistance(this->SourceToAxis);
    radiograph->SetSourceToImageDistance(this->SourceToImage);
    radiograph->SetDetectorPixels(this->Detector[0], this->Detector[1]);
    radiograph->SetPixelPitch(this->Pitch);
    radiograph->SetGantryAngle(this->Gantry);
    double bounds[6];
    volume->GetBounds(bounds);
    const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2 };
    radiograph->SetIsocenter(this->HasIsocenter ? this->Isocenter : centre);
    auto camera = vtkSmartPointer<vtkCamera>::New();
    if (!radiograph->ConfigureCamera(camera)) // the geometry's error says why
    {
      Fail("bad radiograph geometry");
    }
    size[0] = this->Detector[0];
    size[1] = this->Detector[1];
    spacing = radiograph->GetPixelSpacingAtIsocenter();
    return camera;
  }
};

struct Options
{
  std::string Input;
  std::string TF = "raw";
  long long Samples = 16777215;
  std::string Method = "hybrid";
  std::string Kernel = "tent";
  unsigned long long Seed = 0;
  int Threads = 0;
  std::string View = "+z";
  std::string Camera;
  int Size[2] = { 0, 0 };
  double PixelSpacing = 0.0;
  std::string Output = "mcxray.png";
  mcxapp::PngWindow Window;
  double Tolerance = 1e-3;
  bool Quiet = false;
  bool StoredPoints = false;
  double TargetError = 0.0;
  int QuantizationLevels = 0;
  bool ViewGiven = false;
  RadiographOptions Physics;
};


Options Parse(int argc, char* argv[])
{
  Options options;
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)
  {
    std::printf(Usage, mcxapp::TransferFunctionPresetHelp());
    std::exit(argc < 2 ? 2 : 0);
  }
  if (std::strcmp(argv[1], "render") != 0)
  {
    Fail(std::string("unknown command '") + argv[1] + "' (expected render or view; try: mcxray render --help)");
  }
  for (int i = 2; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h")
    {
      std::printf(Usage, mcxapp::TransferFunctionPresetHelp());
      std::exit(0);
    }
    if (arg == "--quiet")
    {
      options.Quiet = true;
      continue;
    }
    if (arg == "--stored-points")
    {
      options.StoredPoints = true;
      continue;
    }
    if (options.Physics.ParseFlag(arg))
    {
      continue;
    }
    if (arg.rfind("--", 0) != 0)
    {
      if (!options.Input.empty())
      {
        Fail("more than one input: '" + options.Input + "' and '" + arg + "'");
      }
      options.Input = arg;
      continue;
    }
    if (i + 1 >= argc)
    {
      Fail("option " + arg + " needs a value");
    }
    const std::string value = argv[++i];
    if (arg == "--tf")
      options.TF = value;
    else if (arg == "--samples")
      options.Samples = ParseInteger(value, arg, 1);
    else if (arg == "--target-error")
    {
      options.TargetError = ParseNumber(value, arg);
      if (!(options.TargetError > 0 && options.TargetError < 1))
      {
        Fail("--target-error must lie in (0, 1)");
      }
    }
    else if (arg == "--quantization-levels")
      options.QuantizationLevels = static_cast<int>(ParseInteger(value, arg, 2));
    else if (arg == "--method")
      options.Method = value;
    else if (arg == "--kernel")
      options.Kernel = value;
    else if (arg == "--seed")
      options.Seed = static_cast<unsigned long long>(ParseInteger(value, arg, 0));
    else if (arg == "--threads")
      options.Threads = static_cast<int>(ParseInteger(value, arg, 1));
    else if (arg == "--view")
    {
      options.View = value;
      options.ViewGiven = true;
    }
    else if (options.Physics.ParseOption(arg, value))
    {
    }
    else if (arg == "--camera")
      options.Camera = value;
    else if (arg == "--size")
      ParseSize(value, 1, 65536, options.Size);
    else if (arg == "--pixel-spacing")
    {
      options.PixelSpacing = ParseNumber(value, arg);
      if (!(options.PixelSpacing > 0))
      {
        Fail("--pixel-spacing must be positive");
      }
    }
    else if (arg == "--output")
      options.Output = value;
    else if (arg == "--window")
    {
      const std::vector<std::string> parts = Split(value, ':');
      if (parts.size() != 2)
      {
        Fail("bad --window '" + value + "' (expected LO:HI)");
      }
      options.Window.Automatic = false;
      options.Window.Low = ParseNumber(parts[0], arg);
      options.Window.High = ParseNumber(parts[1], arg);
      if (!(options.Window.High > options.Window.Low))
      {
        Fail("--window needs LO < HI");
      }
    }
    else if (arg == "--bits")
    {
      options.Window.Bits = static_cast<int>(ParseInteger(value, arg, 8));
      if (options.Window.Bits != 8 && options.Window.Bits != 16)
      {
        Fail("--bits must be 8 or 16");
      }
    }
    else if (arg == "--tolerance")
    {
      options.Tolerance = ParseNumber(value, arg);
      if (!(options.Tolerance > 0 && options.Tolerance < 1))
      {
        Fail("--tolerance must lie in (0, 1)");
      }
    }
    else
    {
      Fail("unknown option " + arg + " (try: mcxray render --help)");
    }
  }
  if (options.Method != "hybrid" && options.Method != "mc" && options.Method != "qmc" && options.Method != "reference")
  {
    Fail("unknown --method '" + options.Method + "' (expected hybrid, mc, qmc or reference)");
  }
  CheckKernel(options.Kernel);
  if ((options.TargetError > 0 || options.QuantizationLevels > 0) &&
    (options.StoredPoints || options.Method == "reference"))
  {
    Fail("--target-error and --quantization-levels apply to off-line Monte Carlo rendering only");
  }
  if (options.QuantizationLevels > 65536)
  {
    Fail("--quantization-levels is limited to 65536");
  }
  if (options.StoredPoints && options.Method == "reference")
  {
    Fail("--stored-points applies to the Monte Carlo methods, not to reference");
  }
  if (options.StoredPoints && options.Samples > (1LL << vtkMCXPointSampler::MaximumPointCloudExponent) - 1)
  {
    Fail("--stored-points holds at most 2^30 - 1 points; use fewer --samples or the default off-line projection");
  }
  if (!mcxapp::IsSupportedOutput(options.Output))
  {
    Fail("unknown output format of '" + options.Output + "' (expected .vti, .png or .pfm)");
  }
  if (options.Physics.Geometry &&
    (!options.Camera.empty() || options.ViewGiven || options.Size[0] > 0 || options.PixelSpacing > 0))
  {
    Fail("the radiograph geometry (--sad, --sid, --detector, --pitch, --gantry, --isocenter) replaces "
         "--view, --camera, --size and --pixel-spacing");
  }
  return options;
}

// Camera from "P:F:U:parallel=S" or "P:F:U:angle=A[:near=D]".
vtkSmartPointer<vtkCamera> ParseCamera(const std::string& text)
{
  const std::vector<std::string> parts = Split(text, ':');
  if (parts.size() != 4 && parts.size() != 5)
  {
    Fail("bad --camera '" + text + "' (expected P:F:U:parallel=S or P:F:U:angle=A[:near=D])");
  }
  double position[3], focal[3], up[3];
  ParseTriple(parts[0], position, "position");
  ParseTriple(parts[1], focal, "focal point");
  ParseTriple(parts[2], up, "view-up");
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetPosition(position);
  camera->SetFocalPoint(focal);
  camera->SetViewUp(up);
  const double distance = std::sqrt(vtkMath::Distance2BetweenPoints(position, focal));
  if (!(distance > 0))
  {
    Fail("--camera position and focal point coincide");
  }
  const std::string& kind = parts[3];
  if (kind.rfind("parallel=", 0) == 0)
  {
    const double scale = ParseNumber(kind.substr(9), "--camera parallel");
    if (!(scale > 0))
    {
      Fail("--camera parallel scale must be positive");
    }
    camera->ParallelProjectionOn();
    camera->SetParallelScale(scale);
    if (parts.size() == 5)
    {
      Fail("--camera near= applies to perspective views only");
    }
  }
  else if (kind.rfind("angle=", 0) == 0)
  {
    const double angle = ParseNumber(kind.substr(6), "--camera angle");
    if (!(angle > 0 && angle < 180))
    {
      Fail("--camera angle must lie in (0, 180) degrees");
    }
    camera->ParallelProjectionOff();
    camera->SetViewAngle(angle);
    double nearDistance = 1e-3 * distance;
    if (parts.size() == 5)
    {
      if (parts[4].rfind("near=", 0) != 0)
      {
        Fail("bad --camera '" + parts[4] + "' (expected near=D)");
      }
      nearDistance = ParseNumber(parts[4].substr(5), "--camera near");
      if (!(nearDistance > 0))
      {
        Fail("--camera near must be positive");
      }
    }
    camera->SetClippingRange(nearDistance, std::max(nearDistance * 2, 1e6 * distance));
  }
  else
  {
    Fail("bad --camera kind '" + kind + "' (expected parallel=S or angle=A)");
  }
  return camera;
}

// Progress bar on stderr, only on a terminal and only once a stage runs long.
struct ProgressBar
{
  bool Enabled = false;
  const char* Stage = "";
  std::chrono::steady_clock::time_point Start;
  bool Shown = false;
  vtkNew<vtkCallbackCommand> Command;

  ProgressBar()
  {
    this->Enabled = isatty(STDERR_FILENO) != 0;
    this->Command->SetClientData(this);
    this->Command->SetCallback([](vtkObject*, unsigned long, void* self, void* data) {
      static_cast<ProgressBar*>(self)->Update(*static_cast<double*>(data));
    });
  }

  void Begin(const char* stage)
  {
    this->Stage = stage;
    this->Start = std::chrono::steady_clock::now();
    this->Shown = false;
  }

  void Update(double fraction)
  {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
    if (!this->Enabled || elapsed < 0.5)
    {
      return;
    }
    const int width = 40;
    const int filled = static_cast<int>(fraction * width);
    std::fprintf(stderr, "\r%-12s [%s%s] %3d%%", this->Stage, std::string(filled, '#').c_str(),
      std::string(width - filled, ' ').c_str(), static_cast<int>(fraction * 100));
    std::fflush(stderr);
    this->Shown = true;
  }

  void End()
  {
    if (this->Shown)
    {
      std::fprintf(stderr, "\r%s\r", std::string(70, ' ').c_str());
      std::fflush(stderr);
    }
  }
};

// Turns VTK error and warning events of an algorithm into one-line messages.
struct MessageCapture
{
  std::string Error;
  std::vector<std::string> Warnings;
  vtkNew<vtkCallbackCommand> ErrorCommand;
  vtkNew<vtkCallbackCommand> WarningCommand;

  static std::string Clean(const char* text)
  {
    std::string message = text ? text : "";
    const std::size_t colon = message.find("): ");
    if (colon != std::string::npos)
    {
      message = message.substr(colon + 3);
    }
    while (!message.empty() && (message.back() == '\n' || message.back() == '\r'))
    {
      message.pop_back();
    }
    return message.substr(0, message.find('\n'));
  }

  void Watch(vtkAlgorithm* algorithm)
  {
    this->ErrorCommand->SetClientData(this);
    this->ErrorCommand->SetCallback([](vtkObject*, unsigned long, void* self, void* text) {
      auto* capture = static_cast<MessageCapture*>(self);
      if (capture->Error.empty())
      {
        capture->Error = Clean(static_cast<const char*>(text));
      }
    });
    this->WarningCommand->SetClientData(this);
    this->WarningCommand->SetCallback([](vtkObject*, unsigned long, void* self, void* text) {
      static_cast<MessageCapture*>(self)->Warnings.push_back(Clean(static_cast<const char*>(text)));
    });
    algorithm->AddObserver(vtkCommand::ErrorEvent, this->ErrorCommand);
    algorithm->AddObserver(vtkCommand::WarningEvent, this->WarningCommand);
  }
};

// VTK messages that reach no observer (an executive's "returned failure",
// say) are kept here rather than printed, so that errors stay one line.
class QuietOutputWindow : public vtkOutputWindow
{
public:
  static QuietOutputWindow* New();
  vtkTypeMacro(QuietOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override
  {
    if (this->First.empty() && text)
    {
      this->First = text;
    }
  }
  std::string First;
};
vtkStandardNewMacro(QuietOutputWindow);

double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}
}

int RunView(int argc, char* argv[])
{
  std::string input, screenshot;
  mcxapp::ViewerOptions viewer;
  long long samples = (1LL << 22) - 1;
  std::string method = "hybrid", kernel = "tent";
  int threads = 0;
  RadiographOptions physics;
  bool sizeGiven = false;
  for (int i = 2; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h")
    {
      std::printf("%s", ViewUsage);
      return 0;
    }
    if (physics.ParseFlag(arg))
    {
      continue;
    }
    if (arg.rfind("--", 0) != 0)
    {
      if (!input.empty())
      {
        Fail("more than one input: '" + input + "' and '" + arg + "'");
      }
      input = arg;
      continue;
    }
    if (i + 1 >= argc)
    {
      Fail("option " + arg + " needs a value");
    }
    const std::string value = argv[++i];
    if (arg == "--tf")
      viewer.TransferFunction = value;
    else if (arg == "--samples")
      samples = ParseInteger(value, arg, 1);
    else if (arg == "--method")
      method = value;
    else if (arg == "--kernel")
      kernel = value;
    else if (arg == "--seed")
      viewer.Seed = static_cast<unsigned long long>(ParseInteger(value, arg, 0));
    else if (arg == "--threads")
      threads = static_cast<int>(ParseInteger(value, arg, 1));
    else if (arg == "--size")
    {
      ParseSize(value, 16, 8192, viewer.Size);
      sizeGiven = true;
    }
    else if (physics.ParseOption(arg, value))
    {
    }
    else if (arg == "--screenshot")
      screenshot = value;
    else
      Fail("unknown option " + arg + " (try: mcxray view --help)");
  }
  if (method != "hybrid" && method != "mc" && method != "qmc")
  {
    Fail("unknown --method '" + method + "' for view (expected hybrid, mc or qmc)");
  }
  CheckKernel(kernel);
  if (samples > (1LL << vtkMCXPointSampler::MaximumPointCloudExponent) - 1)
  {
    Fail("the viewer holds at most 2^30 - 1 points");
  }
  viewer.SampleExponent = static_cast<int>(mcx::ExponentForSampleCount(samples));
  viewer.Strategy = StrategyOf(method);
  viewer.Kernel = KernelOf(kernel);
  viewer.OffScreen = !screenshot.empty();
  if (physics.Geometry && sizeGiven)
  {
    Fail("the radiograph geometry's --detector sets the window size; leave out --size");
  }
  if (physics.Geometry && (physics.Detector[0] < 16 || physics.Detector[1] < 16 ||
                            physics.Detector[0] > 8192 || physics.Detector[1] > 8192))
  {
    Fail("the viewer's --detector must lie between 16x16 and 8192x8192 pixels");
  }
  if (!screenshot.empty())
  {
    const std::string directory =
      vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::CollapseFullPath(screenshot));
    if (vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(screenshot)) != ".png")
    {
      Fail("--screenshot writes .png, not '" + screenshot + "'");
    }
    if (!vtksys::SystemTools::FileIsDirectory(directory) || access(directory.c_str(), W_OK) != 0)
    {
      Fail("cannot write '" + screenshot + "': directory '" + directory + "' is missing or not writable");
    }
  }
  {
    const double probeRange[2] = { 0.0, 1.0 };
    std::string tfError;
    if (!mcxapp::MakeTransferFunction(viewer.TransferFunction, probeRange, tfError))
    {
      Fail(tfError);
    }
  }
  if (threads > 0)
  {
    vtkSMPTools::Initialize(threads);
  }
  if (screenshot.empty() && !vtksys::SystemTools::GetEnv("DISPLAY"))
  {
    Fail("no display (DISPLAY is not set): use --screenshot FILE, or run under xvfb-run");
  }
  vtkNew<QuietOutputWindow> quiet;
  vtkOutputWindow::SetInstance(quiet);
  std::string error;
  const std::string path = input.empty() ? mcxapp::BundledVolumePath() : input;
  vtkSmartPointer<vtkImageData> volume = mcxapp::ReadVolume(path, error);
  if (!volume)
  {
    Fail(error);
  }
  if (physics.Geometry)
  {
    viewer.Size[0] = physics.Detector[0];
    viewer.Size[1] = physics.Detector[1];
  }
  mcxapp::XRayViewer view(volume, viewer);
  if (!view.Error().empty())
  {
    Fail(view.Error());
  }
  if (physics.Geometry)
  {
    int size[2];
    double spacing = 0;
    view.GetRenderer()->GetActiveCamera()->DeepCopy(physics.MakeCamera(volume, size, spacing));
  }
  vtkMCXXRayMapper* mapper = view.GetMapper();
  mapper->SetBeerLambert(physics.BeerLambert);
  mapper->SetIncidentIntensity(physics.IncidentIntensity);
  mapper->SetPhotonsPerPixel(physics.Photons);
  mapper->SetNoiseSeed(physics.NoiseSeed);
  mapper->SetNegativeLog(physics.NegativeLog);
  MessageCapture messages;
  messages.Watch(view.GetIndex());
  messages.Watch(view.GetSampler());
  ProgressBar progress;
  view.GetIndex()->AddObserver(vtkCommand::ProgressEvent, progress.Command);
  progress.Begin("index");
  view.GetIndex()->Update();
  progress.End();
  if (!messages.Error.empty())
  {
    Fail(messages.Error);
  }
  if (screenshot.empty())
  {
    view.Start();
    return 0;
  }
  const int renders = view.RefineUntilComplete();
  if (!messages.Error.empty())
  {
    Fail(messages.Error);
  }
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(view.GetRenderWindow());
  grab->ReadFrontBufferOff();
  grab->Update();
  if (!mcxapp::WriteScreenshot(grab->GetOutput(), screenshot, error))
  {
    Fail(error);
  }
  std::cout << "view:        " << renders << " renders, " << view.OverlayText(false).substr(0, view.OverlayText(false).find('\n'))
            << "\nscreenshot:  " << screenshot << std::endl;
  return 0;
}

int main(int argc, char* argv[])
{
  if (argc >= 2 && std::strcmp(argv[1], "view") == 0)
  {
    return RunView(argc, argv);
  }
  Options options = Parse(argc, argv);
  vtkNew<QuietOutputWindow> quiet;
  vtkOutputWindow::SetInstance(quiet);
  if (options.Threads > 0)
  {
    vtkSMPTools::Initialize(options.Threads);
  }
  const std::string outputDirectory = vtksys::SystemTools::GetFilenamePath(
    vtksys::SystemTools::CollapseFullPath(options.Output));
  if (!vtksys::SystemTools::FileIsDirectory(outputDirectory) || access(outputDirectory.c_str(), W_OK) != 0)
  {
    Fail("cannot write '" + options.Output + "': directory '" + outputDirectory + "' is missing or not writable");
  }
  // Everything that can be checked without the data is checked before any work.
  {
    const double probeRange[2] = { 0.0, 1.0 };
    std::string tfError;
    if (!mcxapp::MakeTransferFunction(options.TF, probeRange, tfError))
    {
      Fail(tfError);
    }
  }
  vtkSmartPointer<vtkCamera> camera = options.Camera.empty() ? nullptr : ParseCamera(options.Camera);
  double detectorU[3] = { 0, 0, 0 }, detectorV[3] = { 0, 0, 0 };
  if (!camera)
  {
    static const std::map<std::string, int> axes = { { "+x", 0 }, { "-x", 0 }, { "x", 0 }, { "+y", 1 },
      { "-y", 1 }, { "y", 1 }, { "+z", 2 }, { "-z", 2 }, { "z", 2 } };
    const auto axis = axes.find(options.View);
    if (axis == axes.end())
    {
      Fail("unknown --view '" + options.View + "' (expected +x, -x, +y, -y, +z or -z)");
    }
    // Image axes: the two remaining world axes in x, y, z order (never mirrored).
    detectorU[axis->second == 0 ? 1 : 0] = 1;
    detectorV[axis->second == 2 ? 1 : 2] = 1;
  }
  const std::string input = options.Input.empty() ? mcxapp::BundledVolumePath() : options.Input;
  auto log = [&](const std::string& line) {
    if (!options.Quiet)
    {
      std::cout << line << std::endl;
    }
  };

  auto start = std::chrono::steady_clock::now();
  std::string error;
  vtkSmartPointer<vtkImageData> volume = mcxapp::ReadVolume(input, error);
  if (!volume)
  {
    Fail(error);
  }
  int dims[3];
  volume->GetDimensions(dims);
  {
    std::ostringstream line;
    line << "input:       " << input << " (" << dims[0] << "x" << dims[1] << "x" << dims[2] << ", "
         << volume->GetPointData()->GetScalars()->GetDataTypeAsString() << ")  read " << Seconds(start) << " s";
    log(line.str());
  }

  if (options.Physics.Geometry)
  {
    camera = options.Physics.MakeCamera(volume, options.Size, options.PixelSpacing);
  }

  MessageCapture messages;
  ProgressBar progress;
  // An error from a watched algorithm, or else from VTK itself, ends the run.
  auto failOnError = [&]() {
    if (!messages.Error.empty() || !quiet->First.empty())
    {
      Fail(messages.Error.empty() ? MessageCapture::Clean(quiet->First.c_str()) : messages.Error);
    }
  };

  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  messages.Watch(index);
  index->AddObserver(vtkCommand::ProgressEvent, progress.Command);
  progress.Begin("index");
  start = std::chrono::steady_clock::now();
  index->Update();
  progress.End();
  failOnError();
  const double indexSeconds = Seconds(start);
  vtkImageData* indexed = index->GetOutput();
  vtkDataArray* levels = indexed->GetFieldData()->GetArray(vtkMCXDensityIndex::LevelValuesName());
  double dataRange[2] = { 0, 0 };
  if (levels->GetNumberOfTuples() > 0)
  {
    dataRange[0] = levels->GetTuple1(0);
    dataRange[1] = levels->GetTuple1(levels->GetNumberOfTuples() - 1);
  }
  {
    std::ostringstream line;
    line << "index:       " << indexSeconds << " s (" << levels->GetNumberOfTuples() << " density levels, "
         << static_cast<double>(dims[0]) * dims[1] * dims[2] / indexSeconds / 1e6 << " M voxels/s)";
    log(line.str());
  }

  vtkSmartPointer<vtkPiecewiseFunction> tf = mcxapp::MakeTransferFunction(options.TF, dataRange, error);
  if (!tf)
  {
    Fail(error);
  }

  const int strategy = StrategyOf(options.Method);
  const int kernel = KernelOf(options.Kernel);
  vtkSmartPointer<vtkMCXProjectorBase> projector;
  if (options.Method == "reference")
  {
    auto reference = vtkSmartPointer<vtkMCXReferenceProjector>::New();
    reference->SetRelativeTolerance(options.Tolerance);
    projector = reference;
  }
  else
  {
    auto monteCarlo = vtkSmartPointer<vtkMCXProjector>::New();
    monteCarlo->SetNumberOfSamples(options.Samples);
    monteCarlo->SetStrategy(strategy);
    monteCarlo->SetSeed(options.Seed);
    monteCarlo->SetTargetRelativeError(options.TargetError);
    monteCarlo->SetTargetQuantizationLevels(options.QuantizationLevels);
    projector = monteCarlo;
  }
  projector->SetInputConnection(index->GetOutputPort());
  if (options.StoredPoints)
  {
    vtkNew<vtkMCXPointSampler> sampler;
    sampler->SetInputConnection(index->GetOutputPort());
    sampler->SetTransferFunction(tf);
    sampler->SetNumberOfSamples(options.Samples);
    sampler->SetStrategy(strategy);
    sampler->SetKernel(kernel);
    sampler->SetSeed(options.Seed);
    messages.Watch(sampler);
    sampler->AddObserver(vtkCommand::ProgressEvent, progress.Command);
    progress.Begin("sampling");
    start = std::chrono::steady_clock::now();
    sampler->Update();
    progress.End();
    failOnError();
    const double samplingSeconds = Seconds(start);
    std::ostringstream line;
    line << "sampling:    " << samplingSeconds << " s (" << sampler->GetOutput()->GetNumberOfPoints()
         << " stored points, " << sampler->GetOutput()->GetNumberOfPoints() / samplingSeconds / 1e6
         << " M points/s)";
    log(line.str());
    projector->SetInputConnection(sampler->GetOutputPort());
  }
  projector->SetTransferFunction(tf);
  projector->SetKernel(kernel);
  projector->SetImageSize(options.Size[0], options.Size[1]);
  projector->SetPixelSpacing(options.PixelSpacing);
  projector->SetCamera(camera);
  projector->SetDetectorAxisU(detectorU);
  projector->SetDetectorAxisV(detectorV);
  messages.Watch(projector);
  projector->AddObserver(vtkCommand::ProgressEvent, progress.Command);
  progress.Begin(options.Method == "reference" ? "reference" : "projection");
  start = std::chrono::steady_clock::now();
  projector->Update();
  progress.End();
  for (const std::string& warning : messages.Warnings)
  {
    std::cerr << "mcxray: warning: " << warning << std::endl;
  }
  failOnError();
  const double projectSeconds = Seconds(start);
  vtkImageData* image = projector->GetOutput();
  {
    std::ostringstream line;
    int size[3];
    image->GetDimensions(size);
    if (options.Method == "reference")
    {
      line << "reference:   " << projectSeconds << " s (exact line integrals, "
           << image->GetFieldData()->GetArray("RaysPerPixelAxis")->GetTuple1(0) << "^2 rays per pixel, estimated relative error "
           << image->GetFieldData()->GetArray("EstimatedRelativeError")->GetTuple1(0) << ")";
    }
    else
    {
      const double samples = image->GetFieldData()->GetArray("SampleCount")->GetTuple1(0);
      line << (options.StoredPoints ? "projection:  " : "sampling + projection (off-line, fused): ")
           << projectSeconds << " s (" << static_cast<long long>(samples) << " samples, "
           << samples / projectSeconds / 1e6 << " M samples/s, estimated relative RMS error "
           << image->GetFieldData()->GetArray("EstimatedRelativeError")->GetTuple1(0) << ")";
    }
    log(line.str());
    std::ostringstream geometry;
    geometry << "image:       " << size[0] << "x" << size[1] << " pixels of " << image->GetSpacing()[0] << " x "
             << image->GetSpacing()[1] << ", LineIntegral range " << image->GetPointData()->GetScalars()->GetRange()[0]
             << " .. " << image->GetPointData()->GetScalars()->GetRange()[1] << " (TF units x length)";
    log(geometry.str());
  }

  // Physics after accumulation, only what was asked for.
  vtkNew<vtkMCXRadiograph> physics;
  physics->SetBeerLambert(options.Physics.BeerLambert);
  physics->SetIncidentIntensity(options.Physics.IncidentIntensity);
  physics->SetPhotonsPerPixel(options.Physics.Photons);
  physics->SetNoiseSeed(options.Physics.NoiseSeed);
  physics->SetNegativeLog(options.Physics.NegativeLog);
  if (physics->HasEffects())
  {
    physics->SetInputData(image);
    start = std::chrono::steady_clock::now();
    physics->Update();
    image = physics->GetOutput();
    std::ostringstream line;
    line << "radiograph:  " << Seconds(start) << " s (" << (options.Physics.NegativeLog ? "-ln(I/I0)" : "I = I0 exp(-line integral)")
         << (options.Physics.Photons > 0 ? ", Poisson noise of " + std::to_string(options.Physics.Photons) + " photons per pixel" : "")
         << "), range " << image->GetPointData()->GetScalars()->GetRange()[0] << " .. "
         << image->GetPointData()->GetScalars()->GetRange()[1];
    log(line.str());
  }

  start = std::chrono::steady_clock::now();
  if (!mcxapp::WriteImage(image, options.Output, options.Window, error))
  {
    Fail(error);
  }
  log("output:      " + options.Output + "  written " + std::to_string(Seconds(start)) + " s");
  return 0;
}
