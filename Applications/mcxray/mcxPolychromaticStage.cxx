#include "mcxPolychromaticStage.h"

#include "mcxFail.h"
#include "mcxHalfValueLayer.h"
#include "mcxMaterialDecomposition.h"
#include "mcxPolychromaticModel.h"
#include "mcxProcesses.h"
#include "mcxSamplingMethod.h"
#include "mcxSettings.h"
#include "mcxTubeSpectrum.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMCXMaterialWeights.h"
#include "vtkMCXPolychromaticRadiograph.h"
#include "vtkMCXProjector.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mcxapp
{

std::string PolychromaticDetector(const Settings& settings)
{
  std::string detector = settings.PhotonCounting ? "counting" : "integrating";
  if (!settings.DetectorMaterial.empty())
  {
    detector += "," + settings.DetectorMaterial;
  }
  return detector;
}

bool PolychromaticAsked(const Settings& settings)
{
  const bool asked = !settings.Spectrum.empty() || settings.MaterialsGiven ||
    !settings.DetectorMaterial.empty() || settings.PhotonCounting;
  if (asked && settings.Spectrum.empty())
  {
    Fail("--materials, --detector-material and --photon-counting need --spectrum");
  }
  return asked;
}

PolychromaticStage::PolychromaticStage(const Settings& settings)
{
  if (!PolychromaticAsked(settings))
  {
    return;
  }
  if (!IsCloudMethod(settings.Method))
  {
    Fail("--spectrum splits the samples' deposit into the materials' channels: use --method "
         "hybrid, mc, qmc or every-voxel");
  }
  if (settings.StoredPoints)
  {
    Fail("--spectrum splits the deposit of the samples as they are drawn: leave out "
         "--stored-points");
  }
  if (settings.TF != "raw")
  {
    Fail("--spectrum samples the materials' density (--materials): leave out --tf");
  }
  if (settings.Radiograph.BeerLambert)
  {
    Fail("--spectrum makes a radiograph already: leave out --beer-lambert");
  }
  const std::string detector = PolychromaticDetector(settings);
  try
  {
    const mcx::Spectrum spectrum = mcx::SpectrumFromText(settings.Spectrum);
    const mcx::MaterialSet set = mcx::MaterialsFromText(settings.Materials);
    (void)mcx::PolychromaticModel(spectrum, mcx::ParseDetector(detector), set.Names());
    std::ostringstream summary;
    summary << "spectrum:    " << settings.Spectrum << " (mean " << spectrum.MeanEnergy()
            << " keV, first HVL " << mcx::HalfValueLayer(spectrum) << " mm Al), detector "
            << detector << ", materials " << settings.Materials << ":";
    for (const std::string& name : set.Names())
    {
      summary << " '" << name << "'";
    }
    this->Summary = summary.str();
  }
  catch (const std::exception& error)
  {
    Fail(error.what());
  }
  this->Enabled = true;
  this->Weights->SetMaterials(settings.Materials.c_str());
  this->Count = this->Weights->GetNumberOfMaterials();
  this->Weights->FillDensityFunction(this->DensityFunction);
  this->Filter->SetSpectrum(settings.Spectrum.c_str());
  this->Filter->SetMaterials(settings.Materials.c_str());
  this->Filter->SetDetector(detector.c_str());
}

PolychromaticStage::~PolychromaticStage() = default;

vtkPiecewiseFunction* PolychromaticStage::Density() const
{
  return this->DensityFunction;
}

void PolychromaticStage::SplitIntoChannels(vtkMCXProjector* projector)
{
  projector->SetNumberOfChannels(this->Count);
  for (int m = 0; m < this->Count; ++m)
  {
    vtkNew<vtkPiecewiseFunction> fraction;
    this->Weights->FillFractionFunction(m, fraction);
    projector->SetChannelFraction(m, fraction);
  }
}

vtkImageData* PolychromaticStage::Radiograph(
  vtkImageData* channels, const Settings& settings, int k, std::string& line)
{
  const RadiographSettings& physics = settings.Radiograph;
  vtkMCXPolychromaticRadiograph* filter = this->Filter;
  filter->SetInputData(channels);
  filter->SetIncidentIntensity(physics.IncidentIntensity);
  filter->SetPhotonsPerPixel(physics.Photons);
  filter->SetNoiseSeed(physics.NoiseSeed + k);
  filter->SetNegativeLog(physics.NegativeLog);
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  vtkImageData* result = filter->GetOutput();
  vtkDataArray* values = result->GetPointData()->GetScalars();
  if (!values)
  {
    Fail("the polychromatic radiograph failed");
  }
  const double* range = values->GetRange();
  std::ostringstream text;
  text << "radiograph:  "
       << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
       << " s (polychromatic, " << this->Count << " channels; "
       << (physics.NegativeLog ? "-ln(I/I0)" : "I = I0 T")
       << (physics.Photons > 0
              ? ", Poisson noise of " + std::to_string(physics.Photons) + " photons per pixel"
              : "")
       << "), range " << range[0] << " .. " << range[1];
  // Every voxel once has no sampling error to estimate (NaN): nothing said, as for one energy.
  vtkDataArray* estimate = result->GetFieldData()->GetArray("EstimatedRelativeError");
  if (estimate && std::isfinite(estimate->GetComponent(0, 0)))
  {
    text << ", -ln(I/I0) estimated relative RMS error " << estimate->GetComponent(0, 0);
  }
  line = text.str();
  return result;
}

std::string PolychromaticStage::Describe() const
{
  return this->Summary;
}

} // namespace mcxapp
