#include "vtkMCXPolychromaticRadiograph.h"

#include "mcxMaterialDecomposition.h"
#include "mcxPolychromaticModel.h"
#include "mcxRadiographEffects.h"
#include "mcxTubeSpectrum.h"
#include "vtkMCXSMPExecutor.h"
#include "vtkMCXTypes.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include <cmath>
#include <stdexcept>
#include <vector>

vtkStandardNewMacro(vtkMCXPolychromaticRadiograph);

vtkMCXPolychromaticRadiograph::vtkMCXPolychromaticRadiograph()
{
  this->SetSpectrum("70kVp,2.5mmAl");
  this->SetDetector("integrating");
  this->SetMaterials("default");
}

vtkMCXPolychromaticRadiograph::~vtkMCXPolychromaticRadiograph()
{
  this->SetSpectrum(nullptr);
  this->SetDetector(nullptr);
  this->SetMaterials(nullptr);
}

int vtkMCXPolychromaticRadiograph::FillInputPortInformation(int port, vtkInformation* info)
{
  this->Superclass::FillInputPortInformation(port, info);
  info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  return 1;
}

const mcx::PolychromaticModel* vtkMCXPolychromaticRadiograph::Model()
{
  const auto text = [](const char* s) { return std::string(s ? s : ""); };
  const std::string key =
    text(this->Spectrum) + '\n' + text(this->Detector) + '\n' + text(this->Materials);
  if (!this->Cached || key != this->CachedKey)
  {
    this->Cached.reset();
    try
    {
      const mcx::Spectrum spectrum = mcx::SpectrumFromText(text(this->Spectrum));
      const mcx::Detector detector = mcx::ParseDetector(text(this->Detector));
      const mcx::MaterialSet set = mcx::MaterialsFromText(text(this->Materials));
      this->Cached.reset(new mcx::PolychromaticModel(spectrum, detector, set.Names()));
      this->CachedNames = set.Names();
      this->CachedKey = key;
      this->CachedMeanEnergy = spectrum.MeanEnergy();
    }
    catch (const std::exception& error)
    {
      vtkErrorMacro(<< error.what());
      return nullptr;
    }
  }
  return this->Cached.get();
}

double vtkMCXPolychromaticRadiograph::GetMeanEnergy()
{
  return this->Model() ? this->CachedMeanEnergy : 0.0;
}

int vtkMCXPolychromaticRadiograph::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector);
  const mcx::PolychromaticModel* model = this->Model();
  if (!model)
  {
    return 0;
  }
  std::vector<std::vector<double>> values;
  std::vector<double> channelErrors;
  if (!this->ReadChannels(
        inputVector[0], static_cast<int>(model->Materials()), output, values, channelErrors))
  {
    return 0;
  }
  const int channels = static_cast<int>(values.size());
  const vtkIdType pixels = static_cast<vtkIdType>(values[0].size());
  std::vector<const double*> pointers(channels);
  for (int m = 0; m < channels; ++m)
  {
    pointers[m] = values[m].data();
  }
  vtkNew<vtkDoubleArray> effective;
  effective->SetName("EffectiveLineIntegral");
  effective->SetNumberOfValues(pixels);
  // The channels are g/cm^3 x mm: 0.1 of that is g/cm^2.
  std::vector<double> errors(pixels);
  model->EffectiveImage(mcx::SMPExecutor(), pixels, pointers.data(), 0.1, effective->GetPointer(0),
    channelErrors.data(), errors.data());
  // The effective line integral's relative RMS error, as the projector
  // states its own: sqrt(sum of squared errors / sum of squared values),
  // over the pixels whose error was propagated, summed in pixel order (the
  // same for any number of threads).
  double squaredErrors = 0.0, squaredValues = 0.0;
  for (vtkIdType p = 0; p < pixels; p += mcx::PolychromaticModel::ErrorStride)
  {
    const double value = effective->GetValue(p);
    if (std::isfinite(value))
    {
      squaredErrors += errors[p] * errors[p];
      squaredValues += value * value;
    }
  }
  const mcx::RadiographEffects effects =
    mcx::RadiographEffects::FromProperties(true, this->IncidentIntensity, this->PhotonsPerPixel,
      static_cast<std::uint64_t>(this->NoiseSeed), this->NegativeLog);
  vtkNew<vtkDoubleArray> result;
  result->SetName(
    this->NegativeLog ? vtkMCXTypes::AttenuationName() : vtkMCXTypes::IntensityName());
  result->SetNumberOfValues(pixels);
  const double* l = effective->GetPointer(0);
  effects.ApplyToImage(
    mcx::SMPExecutor(), pixels, [&](std::int64_t p) { return l[p]; }, result->GetPointer(0));
  vtkNew<vtkDoubleArray> estimate;
  estimate->SetName(vtkMCXTypes::EstimatedRelativeErrorName());
  estimate->InsertNextValue(squaredValues > 0.0 ? std::sqrt(squaredErrors / squaredValues) : 0.0);
  output->GetFieldData()->RemoveArray(vtkMCXTypes::EstimatedRelativeErrorName());
  output->GetFieldData()->AddArray(estimate);
  output->GetPointData()->AddArray(effective);
  output->GetPointData()->AddArray(this->ChannelArray(values));
  output->GetPointData()->AddArray(result);
  output->GetPointData()->SetActiveScalars(result->GetName());
  return 1;
}

bool vtkMCXPolychromaticRadiograph::ReadChannels(vtkInformationVector* inputs, int materials,
  vtkImageData* output, std::vector<std::vector<double>>& values,
  std::vector<double>& channelErrors)
{
  const int connected = inputs->GetNumberOfInformationObjects();
  vtkImageData* first = vtkImageData::GetData(inputs, 0);
  auto splitOf = [](vtkImageData* image)
  {
    return image ? image->GetPointData()->GetArray(vtkMCXTypes::ChannelLineIntegralName())
                 : nullptr;
  };
  vtkDataArray* split = connected == 1 ? splitOf(first) : nullptr;
  for (int m = 0; m < connected && connected > 1; ++m)
  {
    if (splitOf(vtkImageData::GetData(inputs, m)))
    {
      vtkErrorMacro("Input " << m
                             << " is a projection split into channels: connect it alone, "
                                "not with other images.");
      return false;
    }
  }
  const int channels = split ? split->GetNumberOfComponents() : connected;
  if (channels != materials)
  {
    vtkErrorMacro("" << (split ? "A projection split into " : "") << channels
                     << (split ? " channels" : " channel images") << " for " << materials
                     << " materials: connect one projection split into a channel per material "
                        "(vtkMCXProjector::SetNumberOfChannels), or one image per material, in "
                        "the materials' order.");
    return false;
  }
  values.assign(static_cast<std::size_t>(channels), std::vector<double>());
  channelErrors.assign(static_cast<std::size_t>(channels), 0.0);
  vtkIdType pixels = -1;
  for (int m = 0; m < channels; ++m)
  {
    vtkImageData* image = split ? first : vtkImageData::GetData(inputs, m);
    vtkDataArray* line = split ? split
      : image                  ? image->GetPointData()->GetArray(vtkMCXTypes::LineIntegralName())
                               : nullptr;
    if (!line || (!split && line->GetNumberOfComponents() != 1) ||
      (pixels >= 0 && line->GetNumberOfTuples() != pixels))
    {
      vtkErrorMacro("Channel image " << m
                                     << " has no one-component LineIntegral array of the "
                                        "others' size.");
      return false;
    }
    pixels = line->GetNumberOfTuples();
    vtkDataArray* estimate =
      image->GetFieldData()->GetArray(split ? vtkMCXTypes::ChannelEstimatedRelativeErrorName()
                                            : vtkMCXTypes::EstimatedRelativeErrorName());
    channelErrors[m] = estimate && estimate->GetNumberOfTuples() > (split ? m : 0)
      ? estimate->GetComponent(split ? m : 0, 0)
      : 0.0;
    const int component = split ? m : 0;
    values[m].resize(static_cast<std::size_t>(pixels));
    for (vtkIdType p = 0; p < pixels; ++p)
    {
      values[m][static_cast<std::size_t>(p)] = line->GetComponent(p, component);
    }
  }
  // The geometry and the projector's fields (its matrix, sample count) of
  // the first image: every channel has the same, and a split projection's
  // are those of the one sampling pass.
  output->CopyStructure(first);
  output->GetFieldData()->ShallowCopy(first->GetFieldData());
  output->GetFieldData()->RemoveArray(vtkMCXTypes::ChannelEstimatedRelativeErrorName());
  return true;
}

vtkSmartPointer<vtkDoubleArray> vtkMCXPolychromaticRadiograph::ChannelArray(
  const std::vector<std::vector<double>>& values) const
{
  auto channels = vtkSmartPointer<vtkDoubleArray>::New();
  channels->SetName(vtkMCXTypes::ChannelLineIntegralName());
  channels->SetNumberOfComponents(static_cast<int>(values.size()));
  channels->SetNumberOfTuples(static_cast<vtkIdType>(values[0].size()));
  for (std::size_t m = 0; m < values.size(); ++m)
  {
    if (m < this->CachedNames.size())
    {
      channels->SetComponentName(static_cast<vtkIdType>(m), this->CachedNames[m].c_str());
    }
    for (std::size_t p = 0; p < values[m].size(); ++p)
    {
      channels->SetTypedComponent(static_cast<vtkIdType>(p), static_cast<int>(m), values[m][p]);
    }
  }
  return channels;
}

void vtkMCXPolychromaticRadiograph::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Spectrum: " << (this->Spectrum ? this->Spectrum : "(none)") << "\n";
  os << indent << "Detector: " << (this->Detector ? this->Detector : "(none)") << "\n";
  os << indent << "Materials: " << (this->Materials ? this->Materials : "(none)") << "\n";
  os << indent << "IncidentIntensity: " << this->IncidentIntensity << "\n";
  os << indent << "PhotonsPerPixel: " << this->PhotonsPerPixel << "\n";
  os << indent << "NoiseSeed: " << this->NoiseSeed << "\n";
  os << indent << "NegativeLog: " << this->NegativeLog << "\n";
  os << indent << "Cached: " << (this->Cached ? "a model" : "none") << "\n";
  os << indent << "CachedKey: " << this->CachedKey << "\n";
  os << indent << "CachedMeanEnergy: " << this->CachedMeanEnergy << "\n";
  os << indent << "CachedNames:";
  for (const std::string& name : this->CachedNames)
  {
    os << " '" << name << "'";
  }
  os << "\n";
}
