#include "mcxPolychromaticStage.h"

#include "mcxFail.h"
#include "mcxHalfValueLayer.h"
#include "mcxMaterialDecomposition.h"
#include "mcxPolychromaticModel.h"
#include "mcxProcesses.h"
#include "mcxSamplingMethod.h"
#include "mcxSettings.h"
#include "mcxTubeSpectrum.h"

#include "vtkAlgorithmOutput.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMCXMaterialWeights.h"
#include "vtkMCXPolychromaticRadiograph.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"

#include <chrono>
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

PolychromaticStage::PolychromaticStage(const Settings& settings)
{
  const bool asked = !settings.Spectrum.empty() || settings.MaterialsGiven ||
    !settings.DetectorMaterial.empty() || settings.PhotonCounting;
  if (!asked)
  {
    return;
  }
  if (settings.Spectrum.empty())
  {
    Fail("--materials, --detector-material and --photon-counting need --spectrum");
  }
  if (!IsCloudMethod(settings.Method) || settings.Method == "every-voxel")
  {
    Fail("--spectrum projects one drawn cloud once per material: use --method hybrid, mc or qmc");
  }
  if (settings.Deposit != "footprint")
  {
    Fail("--spectrum needs the footprint deposit (its points are voxel centres, each with its "
         "voxel's materials)");
  }
  if (NumberOfProcesses() > 1)
  {
    Fail("--spectrum renders on one process (not under mpirun)");
  }
  if (settings.TF != "raw")
  {
    Fail("--spectrum samples the materials' density (--materials): leave out --tf");
  }
  if (settings.Radiograph.BeerLambert)
  {
    Fail("--spectrum makes a radiograph already: leave out --beer-lambert");
  }
  if (settings.TargetError > 0 || settings.QuantizationLevels > 0)
  {
    Fail("--spectrum projects a stored cloud of --samples points per material: leave out "
         "--target-error and --quantization-levels");
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
  for (int m = 0; m < this->Count; ++m)
  {
    this->Names.emplace_back(this->Weights->GetMaterialName(m));
  }
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

vtkAlgorithmOutput* PolychromaticStage::Connect(vtkAlgorithmOutput* cloud, vtkImageData* volume)
{
  this->Weights->SetInputConnection(0, cloud);
  this->Weights->SetInputData(1, volume);
  return this->Weights->GetOutputPort();
}

void PolychromaticStage::SetChannel(int m)
{
  this->Weights->SetChannel(m);
}

void PolychromaticStage::Keep(vtkImageData* projected)
{
  auto copy = vtkSmartPointer<vtkImageData>::New();
  copy->DeepCopy(projected);
  this->Kept.push_back(copy);
}

vtkImageData* PolychromaticStage::Radiograph(const Settings& settings, int k, std::string& line)
{
  const RadiographSettings& physics = settings.Radiograph;
  vtkMCXPolychromaticRadiograph* filter = this->Filter;
  filter->RemoveAllInputConnections(0);
  for (vtkImageData* channel : this->Kept)
  {
    filter->AddInputData(channel);
  }
  filter->SetIncidentIntensity(physics.IncidentIntensity);
  filter->SetPhotonsPerPixel(physics.Photons);
  filter->SetNoiseSeed(physics.NoiseSeed + k);
  filter->SetNegativeLog(physics.NegativeLog);
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  this->Kept.clear();
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
  if (vtkDataArray* estimate = result->GetFieldData()->GetArray("EstimatedRelativeError"))
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
