#include "mcxOptionTable.h"

#include "mcxFail.h"
#include "mcxOptionValues.h"
#include "mcxSettings.h"

#include "vtkMCXPatientSpace.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace mcxapp
{

namespace
{
struct Argument
{
  const std::string& Name;
  const std::string& Value; // empty for a flag
};

enum Accepted
{
  Render = static_cast<int>(Command::Render),
  View = static_cast<int>(Command::View),
  Both = Render | View
};

struct Option
{
  const char* Name;
  int Commands; // Accepted bits
  bool TakesValue;
  void (*Apply)(Settings& settings, const Argument& argument);
};

// More threads than any machine has cores is a typing error (TBB would try
// to start them all).
const long long MaximumThreads = 4096;

// TBB starts no more workers than the cores it may use (it ignores a larger
// request with a two-line warning of its own): more threads are refused.
int ThreadsOf(const Argument& argument)
{
  const int threads =
    static_cast<int>(ParseInteger(argument.Value, argument.Name, 1, MaximumThreads));
  const char* backend = vtkSMPTools::GetBackend();
  if (!backend || std::string(backend) != "TBB")
  {
    return threads;
  }
  // Before any Initialize: TBB's default, the cores this process may use.
  const int cores = vtkSMPTools::GetEstimatedNumberOfThreads();
  if (threads > cores)
  {
    Fail(argument.Name + " " + std::to_string(threads) + " is more than the " +
      std::to_string(cores) + " cores TBB can use here (at most " + std::to_string(cores) + ")");
  }
  return threads;
}

// A distance of the radiograph geometry: giving one selects the geometry.
void SetGeometryDistance(Settings& settings, double& distance, const Argument& argument)
{
  distance = ParsePositive(argument.Value, argument.Name);
  settings.Radiograph.Geometry = true;
}

void SetSize(Settings& settings, const Argument& argument, int smallest, int largest)
{
  ParseSize(argument.Value, argument.Name, smallest, largest, settings.Size);
  settings.SizeGiven = true;
}

// The geometry's numbers, plastimatch's way ("x y z") or ours ("x,y,z").
void SetNumbers(Settings& settings, const Argument& argument, std::size_t count, double* out)
{
  const std::vector<double> numbers = ParseNumberList(argument.Value, count, argument.Name);
  std::copy(numbers.begin(), numbers.end(), out);
  settings.Radiograph.Geometry = true;
}

// Columns and rows: 512x512 (ours), "512 512" or 512,512 (plastimatch's -r).
void SetDetectorPixels(Settings& settings, const Argument& argument)
{
  std::string value = argument.Value;
  const std::size_t first = value.find_first_not_of(" \t");
  const std::size_t last = value.find_last_not_of(" \t");
  value = first == std::string::npos ? std::string() : value.substr(first, last - first + 1);
  std::string size;
  for (char c : value)
  {
    const bool separator = c == ' ' || c == '\t' || c == ',';
    if (!separator)
    {
      size += c;
    }
    else if (!size.empty() && size.back() != 'x')
    {
      size += 'x';
    }
  }
  ParseSize(size, argument.Name, 1, 65536, settings.Radiograph.Detector);
  settings.Radiograph.Geometry = true;
}

void SetDetectorSize(Settings& settings, const Argument& argument)
{
  SetNumbers(settings, argument, 2, settings.Radiograph.DetectorSize);
  for (double side : settings.Radiograph.DetectorSize)
  {
    if (!(side > 0) || !std::isfinite(side))
    {
      Fail(argument.Name + " must be two positive sizes in mm, not '" + argument.Value + "'");
    }
  }
  settings.Radiograph.DetectorSizeGiven = true;
}

// An angle in degrees: finite and within a million degrees (beyond, its
// sine and cosine are rounding noise, and an angle past 1e308 once
// overflowed into the view-up check's error).
double ParseAngle(const std::string& text, const std::string& option)
{
  const double degrees = ParseNumber(text, option);
  if (!(std::fabs(degrees) <= 1e6))
  {
    Fail("bad value '" + text + "' for " + option + " (expected degrees from -1e6 to 1e6)");
  }
  return degrees;
}

// DEG, or START:STOP:COUNT: COUNT angles from START, STOP excluded (a full
// turn 0:360:N repeats no angle), as plastimatch's -a COUNT -N STEP.
void SetGantry(Settings& settings, const Argument& argument)
{
  settings.Radiograph.Geometry = true;
  settings.Radiograph.GantryGiven = true;
  const std::vector<std::string> parts = Split(argument.Value, ':');
  if (parts.size() == 1)
  {
    settings.Radiograph.Gantry = ParseAngle(argument.Value, argument.Name);
    return;
  }
  if (parts.size() != 3)
  {
    Fail("bad " + argument.Name + " '" + argument.Value + "' (expected DEG or START:STOP:COUNT)");
  }
  const double start = ParseAngle(parts[0], argument.Name);
  const double stop = ParseAngle(parts[1], argument.Name);
  const long long count = ParseInteger(parts[2], argument.Name, 1, 100000);
  settings.Radiograph.GantryList.clear();
  for (long long k = 0; k < count; ++k)
  {
    settings.Radiograph.GantryList.push_back(start + (stop - start) * k / count);
  }
}

void SetAngleCount(Settings& settings, const Argument& argument)
{
  settings.Radiograph.AngleCount =
    static_cast<int>(ParseInteger(argument.Value, argument.Name, 1, 100000));
  settings.Radiograph.Geometry = true;
}

void SetAngleStep(Settings& settings, const Argument& argument)
{
  settings.Radiograph.AngleStep = ParseAngle(argument.Value, argument.Name);
  settings.Radiograph.Geometry = true;
}

void SetNormal(Settings& settings, const Argument& argument)
{
  SetNumbers(settings, argument, 3, settings.Radiograph.Normal);
  settings.Radiograph.HasNormal = true;
}

void SetImageCenter(Settings& settings, const Argument& argument)
{
  SetNumbers(settings, argument, 2, settings.Radiograph.ImageCenter);
  settings.Radiograph.HasImageCenter = true;
}

void SetIsocenter(Settings& settings, const Argument& argument)
{
  SetNumbers(settings, argument, 3, settings.Radiograph.Isocenter);
  settings.Radiograph.HasIsocenter = true;
}

// Values are checked as they are read; what depends on other options is
// checked by the command once all are read.
const Option Options[] = {
  { "--quiet", Render, false, [](Settings& s, const Argument&) { s.Quiet = true; } },
  { "--stored-points", Render, false, [](Settings& s, const Argument&) { s.StoredPoints = true; } },
  { "--beer-lambert", Both, false,
    [](Settings& s, const Argument&) { s.Radiograph.BeerLambert = true; } },
  { "--negative-log", Both, false,
    [](Settings& s, const Argument&) { s.Radiograph.NegativeLog = true; } },
  { "--tf", Both, true, [](Settings& s, const Argument& a) { s.TF = a.Value; } },
  { "--spectrum", Both, true, [](Settings& s, const Argument& a) { s.Spectrum = a.Value; } },
  { "--materials", Both, true,
    [](Settings& s, const Argument& a)
    {
      s.Materials = a.Value;
      s.MaterialsGiven = true;
    } },
  { "--detector-material", Both, true,
    [](Settings& s, const Argument& a) { s.DetectorMaterial = a.Value; } },
  { "--photon-counting", Both, false,
    [](Settings& s, const Argument&) { s.PhotonCounting = true; } },
  { "--samples", Both, true,
    [](Settings& s, const Argument& a)
    {
      s.Samples = ParseInteger(a.Value, a.Name, 1);
      s.SamplesGiven = true;
    } },
  { "--target-error", Render, true,
    [](Settings& s, const Argument& a)
    { s.TargetError = ParseOpenUnitFraction(a.Value, a.Name); } },
  { "--quantization-levels", Render, true,
    [](Settings& s, const Argument& a)
    { s.QuantizationLevels = static_cast<int>(ParseInteger(a.Value, a.Name, 2, INT_MAX)); } },
  { "--method", Both, true, [](Settings& s, const Argument& a) { s.Method = a.Value; } },
  { "--kernel", Both, true, [](Settings& s, const Argument& a) { s.Kernel = a.Value; } },
  { "--deposit", Both, true,
    [](Settings& s, const Argument& a)
    {
      s.Deposit = a.Value;
      s.DepositGiven = true;
    } },
  { "--seed", Both, true,
    [](Settings& s, const Argument& a)
    { s.Seed = static_cast<unsigned long long>(ParseInteger(a.Value, a.Name, 0)); } },
  { "--reorder-angle", View, true,
    [](Settings& s, const Argument& a)
    {
      s.ReorderAngle = ParseNumber(a.Value, a.Name);
      if (!(s.ReorderAngle >= 0 && s.ReorderAngle <= 180))
      {
        Fail(a.Name + " must be 0 to 180 degrees");
      }
    } },
  { "--threads", Both, true, [](Settings& s, const Argument& a) { s.Threads = ThreadsOf(a); } },
  { "--memory-limit", Both, true,
    [](Settings& s, const Argument& a) { s.MemoryLimit = ParseByteSize(a.Value, a.Name); } },
  { "--series", Both, true,
    [](Settings& s, const Argument& a)
    { s.DicomSeries = static_cast<int>(ParseInteger(a.Value, a.Name, 1, 1000000)); } },
  { "--read-timeout", Both, true,
    [](Settings& s, const Argument& a) { s.ReadTimeout = ParsePositive(a.Value, a.Name); } },
  { "--view", Render, true,
    [](Settings& s, const Argument& a)
    {
      s.View = a.Value;
      s.ViewGiven = true;
    } },
  { "--sad", Both, true,
    [](Settings& s, const Argument& a)
    {
      SetGeometryDistance(s, s.Radiograph.SourceToAxis, a);
      s.Radiograph.SourceToAxisGiven = true;
    } },
  { "--sid", Both, true,
    [](Settings& s, const Argument& a)
    {
      SetGeometryDistance(s, s.Radiograph.SourceToImage, a);
      s.Radiograph.SourceToImageGiven = true;
    } },
  { "--pitch", Both, true,
    [](Settings& s, const Argument& a)
    {
      SetGeometryDistance(s, s.Radiograph.Pitch, a);
      s.Radiograph.PitchGiven = true;
    } },
  { "--detector", Both, true, [](Settings& s, const Argument& a) { SetDetectorPixels(s, a); } },
  { "-r", Both, true, [](Settings& s, const Argument& a) { SetDetectorPixels(s, a); } },
  { "--dim", Both, true, [](Settings& s, const Argument& a) { SetDetectorPixels(s, a); } },
  { "-z", Both, true, [](Settings& s, const Argument& a) { SetDetectorSize(s, a); } },
  { "--detector-size", Both, true, [](Settings& s, const Argument& a) { SetDetectorSize(s, a); } },
  { "--gantry", Both, true, [](Settings& s, const Argument& a) { SetGantry(s, a); } },
  { "-y", Both, true, [](Settings& s, const Argument& a) { SetGantry(s, a); } },
  { "--gantry-angle", Both, true, [](Settings& s, const Argument& a) { SetGantry(s, a); } },
  { "-a", Render, true, [](Settings& s, const Argument& a) { SetAngleCount(s, a); } },
  { "--num-angles", Render, true, [](Settings& s, const Argument& a) { SetAngleCount(s, a); } },
  { "-N", Render, true, [](Settings& s, const Argument& a) { SetAngleStep(s, a); } },
  { "--gantry-angle-spacing", Render, true,
    [](Settings& s, const Argument& a) { SetAngleStep(s, a); } },
  { "-n", Both, true, [](Settings& s, const Argument& a) { SetNormal(s, a); } },
  { "--nrm", Both, true, [](Settings& s, const Argument& a) { SetNormal(s, a); } },
  { "--vup", Both, true,
    [](Settings& s, const Argument& a)
    {
      SetNumbers(s, a, 3, s.Radiograph.Up);
      s.Radiograph.UpGiven = true;
    } },
  { "-c", Render, true, [](Settings& s, const Argument& a) { SetImageCenter(s, a); } },
  { "--image-center", Render, true, [](Settings& s, const Argument& a) { SetImageCenter(s, a); } },
  { "--isocenter", Both, true, [](Settings& s, const Argument& a) { SetIsocenter(s, a); } },
  { "-o", Both, true, [](Settings& s, const Argument& a) { SetIsocenter(s, a); } },
  { "--projection-matrix", Render, true,
    [](Settings& s, const Argument& a)
    {
      SetNumbers(s, a, 12, s.Radiograph.Matrix);
      s.Radiograph.HasMatrix = true;
    } },
  { "--intrinsics", Render, true,
    [](Settings& s, const Argument& a)
    {
      SetNumbers(s, a, 4, s.Radiograph.Intrinsics);
      s.Radiograph.HasIntrinsics = true;
    } },
  { "--extrinsics", Render, true,
    [](Settings& s, const Argument& a)
    {
      SetNumbers(s, a, 12, s.Radiograph.Extrinsics);
      s.Radiograph.HasExtrinsics = true;
    } },
  { "--projection-matrices", Render, true,
    [](Settings& s, const Argument& a)
    {
      s.Radiograph.MatrixFile = a.Value;
      s.Radiograph.Geometry = true;
    } },
  { "--rtk-geometry", Render, true,
    [](Settings& s, const Argument& a)
    {
      s.Radiograph.RTKGeometry = a.Value;
      s.Radiograph.Geometry = true;
    } },
  { "--detector-origin", Render, true,
    [](Settings& s, const Argument& a)
    {
      SetNumbers(s, a, 2, s.Radiograph.DetectorOrigin);
      s.Radiograph.HasDetectorOrigin = true;
    } },
  { "--rtplan", Render, true,
    [](Settings& s, const Argument& a)
    {
      s.Radiograph.RTPlan = a.Value;
      s.Radiograph.Geometry = true;
    } },
  { "--beam", Render, true,
    [](Settings& s, const Argument& a)
    {
      if (a.Value.empty())
      {
        Fail("--beam needs a beam number or name");
      }
      s.Radiograph.Beam = a.Value;
    } },
  { "--output-geometry", Render, true,
    [](Settings& s, const Argument& a) { s.OutputGeometry = a.Value; } },
  { "--i0", Both, true,
    [](Settings& s, const Argument& a)
    {
      s.Radiograph.IncidentIntensity = ParsePositive(a.Value, a.Name);
      s.Radiograph.IncidentIntensityGiven = true;
    } },
  { "--photons", Both, true,
    [](Settings& s, const Argument& a)
    {
      s.Radiograph.Photons = ParseNumber(a.Value, a.Name);
      if (!(s.Radiograph.Photons > 0) || s.Radiograph.Photons > 1e15)
      {
        Fail("--photons must lie in (0, 1e15]");
      }
    } },
  { "--noise-seed", Both, true,
    [](Settings& s, const Argument& a)
    { s.Radiograph.NoiseSeed = ParseInteger(a.Value, a.Name, 0); } },
  { "--camera", Render, true, [](Settings& s, const Argument& a) { s.Camera = a.Value; } },
  { "--coordinates", Both, true,
    [](Settings& s, const Argument& a)
    {
      std::string value = a.Value;
      std::transform(value.begin(), value.end(), value.begin(),
        [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      if (value != "lps" && value != "ras")
      {
        Fail("bad --coordinates '" + a.Value + "' (expected lps or ras)");
      }
      s.RASCoordinates = value == "ras";
    } },
  // An image may be large; a window must fit a screen.
  { "--size", Render, true, [](Settings& s, const Argument& a) { SetSize(s, a, 1, 65536); } },
  { "--size", View, true, [](Settings& s, const Argument& a) { SetSize(s, a, 16, 8192); } },
  { "--pixel-spacing", Render, true,
    [](Settings& s, const Argument& a) { s.PixelSpacing = ParsePositive(a.Value, a.Name); } },
  { "--output", Render, true, [](Settings& s, const Argument& a) { s.Output = a.Value; } },
  { "--window", Render, true,
    [](Settings& s, const Argument& a)
    {
      const std::vector<std::string> parts = Split(a.Value, ':');
      if (parts.size() != 2)
      {
        Fail("bad --window '" + a.Value + "' (expected LO:HI)");
      }
      s.Window.Automatic = false;
      s.Window.Low = ParseNumber(parts[0], a.Name);
      s.Window.High = ParseNumber(parts[1], a.Name);
      if (!(s.Window.High > s.Window.Low))
      {
        Fail("--window needs LO < HI");
      }
    } },
  { "--bits", Render, true,
    [](Settings& s, const Argument& a)
    {
      const long long bits = ParseInteger(a.Value, a.Name, 8);
      if (bits != 8 && bits != 16)
      {
        Fail("--bits must be 8 or 16");
      }
      s.Window.Bits = static_cast<int>(bits);
    } },
  { "--tolerance", Render, true,
    [](Settings& s, const Argument& a)
    {
      s.Tolerance = ParseOpenUnitFraction(a.Value, a.Name);
      s.ToleranceGiven = true;
    } },
  { "--screenshot", View, true, [](Settings& s, const Argument& a) { s.Screenshot = a.Value; } },
};

// The option named name that command accepts; null if none.
const Option* Find(const std::string& name, Command command)
{
  for (const Option& option : Options)
  {
    if (name == option.Name && (option.Commands & static_cast<int>(command)) != 0)
    {
      return &option;
    }
  }
  return nullptr;
}

void SetInput(Settings& settings, const std::string& input)
{
  // An empty argument ("$FILE" unset) is not the absence of one: it would
  // render the bundled CT instead of the volume meant.
  if (input.empty())
  {
    Fail("the input path is empty");
  }
  if (!settings.Input.empty())
  {
    Fail("more than one input: '" + settings.Input + "' and '" + input + "'");
  }
  settings.Input = input;
}
}

const char* CommandName(Command command)
{
  return command == Command::View ? "view" : "render";
}

bool ParseArguments(int argc, char* argv[], Command command, Settings& settings)
{
  std::set<const Option*> given; // an option twice is a typo or a script's slip, not an override
  for (int i = 2; i < argc; ++i)
  {
    const std::string name = argv[i];
    if (name == "--help" || name == "-h")
    {
      return false;
    }
    const Option* option = Find(name, command);
    if (option && !given.insert(option).second)
    {
      Fail("option " + name + " is given twice");
    }
    if (option && !option->TakesValue)
    {
      option->Apply(settings, { name, std::string() });
      continue;
    }
    if (!option && name.rfind("--", 0) != 0)
    {
      SetInput(settings, name);
      continue;
    }
    if (!option)
    {
      Fail("unknown option " + name + " (try: mcxray " + CommandName(command) + " --help)");
    }
    if (i + 1 >= argc)
    {
      Fail("option " + name + " needs a value");
    }
    const std::string value = argv[++i];
    option->Apply(settings, { name, value });
  }
  if (settings.RASCoordinates)
  {
    // Points and directions given in RAS, taken to patient space (LPS)
    // once; the camera when it is parsed (ChooseView). A matrix of RAS
    // points takes LPS points once its first two columns are negated.
    RadiographSettings& r = settings.Radiograph;
    vtkMCXPatientSpace::FlipRightAnterior(r.Isocenter);
    vtkMCXPatientSpace::FlipRightAnterior(r.Normal);
    vtkMCXPatientSpace::FlipRightAnterior(r.Up);
    for (int row = 0; row < 3; ++row)
    {
      for (int column = 0; column < 2; ++column)
      {
        r.Matrix[4 * row + column] = -r.Matrix[4 * row + column];
        r.Extrinsics[3 * row + column] = -r.Extrinsics[3 * row + column];
      }
    }
  }
  return true;
}

} // namespace mcxapp
