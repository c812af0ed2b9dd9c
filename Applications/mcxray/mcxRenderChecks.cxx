#include "mcxRenderChecks.h"

#include "mcxBundledVolume.h"
#include "mcxFail.h"
#include "mcxImageOutput.h"
#include "mcxPoseOutput.h"
#include "mcxPreflight.h"
#include "mcxSamplingMethod.h"
#include "mcxSettings.h"

#include "vtkMCXTypes.h"
#include "vtkSMPTools.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace mcxapp
{

namespace
{
// The most samples a render takes: 2^40 - 1 (the long-run warning's
// estimate: about 3 hours of point deposits on 2 cores), 4 million a pixel
// of a 512^2 image, far beyond any useful precision.
const long long MaximumSamples = (1LL << 40) - 1;
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
  // Options that would change nothing are refused, not dropped in silence.
  if ((settings.TargetError > 0 || settings.QuantizationLevels > 0) && settings.SamplesGiven)
  {
    Fail("--target-error and --quantization-levels choose the sample count: leave out --samples");
  }
  if (settings.Method == "reference" && (settings.SamplesGiven || settings.DepositGiven))
  {
    Fail("reference integrates exactly, without samples: leave out --samples and --deposit");
  }
  if (settings.ToleranceGiven && settings.Method != "reference")
  {
    Fail("--tolerance is the reference method's: it goes with --method reference");
  }
  if (settings.Radiograph.IncidentIntensityGiven && !settings.Radiograph.BeerLambert &&
    !(settings.Radiograph.Photons > 0) && settings.Spectrum.empty())
  {
    Fail("--i0 is the radiograph's unattenuated intensity: it goes with --beer-lambert, --photons "
         "or --spectrum");
  }
  if (settings.Samples > MaximumSamples)
  {
    Fail("--samples is at most 2^40 - 1 (1099511627775: about 3 hours of point deposits on 2 "
         "cores, 12 of footprints)");
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
    Fail("unknown output format of '" + settings.Output + "' (expected .vti, .mha, .png or .pfm)");
  }
  settings.Radiograph.CheckCombinations();
  if (settings.Radiograph.Geometry &&
    (!settings.Camera.empty() || settings.ViewGiven || settings.SizeGiven ||
      settings.PixelSpacing > 0))
  {
    Fail("the radiograph geometry (--sad, --sid, --detector, --pitch, --gantry, --isocenter, "
         "--projection-matrix, --intrinsics, ...) replaces --view, --camera, --size and "
         "--pixel-spacing");
  }
}

// Every file the run will write (a sweep's numbered files, its geometry),
// checked before any work: nothing the run reads is overwritten, and a
// name that cannot be written fails now, not after the render.
void CheckOutputs(const Settings& settings)
{
  std::vector<std::pair<std::string, std::string>> outputs; // file, option
  const int poses = settings.Radiograph.PoseCount();
  if (poses > 1 && !WritesStack(settings.Output))
  {
    for (int k = 0; k < poses; ++k)
    {
      outputs.emplace_back(NumberedOutput(settings.Output, k), "--output");
    }
  }
  else
  {
    outputs.emplace_back(settings.Output, "--output");
  }
  if (!settings.OutputGeometry.empty())
  {
    for (const auto& output : outputs)
    {
      if (vtksys::SystemTools::CollapseFullPath(output.first) ==
        vtksys::SystemTools::CollapseFullPath(settings.OutputGeometry))
      {
        Fail("--output-geometry names an image the run writes ('" + output.first + "')");
      }
    }
    outputs.emplace_back(settings.OutputGeometry, "--output-geometry");
  }
  const std::string input = settings.Input.empty() ? BundledVolumePath() : settings.Input;
  for (const auto& output : outputs)
  {
    CheckOutputDirectory(output.first);
    const std::string nameProblem = OutputNameProblem(output.first, output.second);
    if (!nameProblem.empty())
    {
      Fail(nameProblem);
    }
    CheckOutputIsNotInput(output.first, input, output.second);
  }
}

} // namespace mcxapp
