#include "vtkMCXRadiograph.h"

#include "mcxRadiographEffects.h"
#include "vtkMCXProjectorBase.h"
#include "vtkMCXSMPExecutor.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

vtkStandardNewMacro(vtkMCXRadiograph);

vtkMCXRadiograph::vtkMCXRadiograph()
{
  this->SetProgressText("X-Ray Radiograph"); // what progress bars show (ParaView's label)
}

namespace
{
// The properties in the core's terms (the getters are not const in VTK 9.1).
mcx::RadiographEffects EffectsOf(vtkMCXRadiograph* self)
{
  return mcx::RadiographEffects::FromProperties(self->GetBeerLambert(),
    self->GetIncidentIntensity(), self->GetPhotonsPerPixel(),
    static_cast<std::uint64_t>(self->GetNoiseSeed()), self->GetNegativeLog());
}
}

bool vtkMCXRadiograph::HasEffects()
{
  return EffectsOf(this).Any();
}

int vtkMCXRadiograph::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  output->ShallowCopy(input);
  if (!this->HasEffects())
  {
    return 1; // nothing asked for, nothing done
  }
  vtkDataArray* lineIntegral =
    input->GetPointData()->GetArray(vtkMCXTypes::LineIntegralName());
  if (!lineIntegral || lineIntegral->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro(
      "The input has no one-component LineIntegral array (make it with vtkMCXProjector).");
    output->Initialize();
    return 0;
  }
  // Intensities of line integrals that are not an attenuation's are black.
  if ((this->BeerLambert && !this->NegativeLog) || this->PhotonsPerPixel > 0)
  {
    double sum = 0.0;
    vtkIdType positive = 0;
    for (vtkIdType p = 0; p < lineIntegral->GetNumberOfTuples(); ++p)
    {
      const double value = lineIntegral->GetComponent(p, 0);
      sum += value > 0 ? value : 0.0;
      positive += value > 0 ? 1 : 0;
    }
    const double mean = positive > 0 ? sum / positive : 0.0;
    if (mean > NotAttenuationMean && !this->ToldNotAttenuation)
    {
      vtkWarningMacro("Beer-Lambert of line integrals averaging "
        << mean
        << ": not an attenuation's (per mm, a few through a body), so the image is black; "
           "project mu (vtkMCXAttenuationFunction, X-Ray Projector's Attenuation 'HU to mu').");
    }
    this->ToldNotAttenuation = mean > NotAttenuationMean;
  }
  vtkNew<vtkDoubleArray> values;
  values->SetName(this->NegativeLog ? vtkMCXTypes::AttenuationName() : vtkMCXTypes::IntensityName());
  const vtkIdType pixels = lineIntegral->GetNumberOfTuples();
  if (!values->SetNumberOfValues(pixels))
  {
    // Under an address-space limit: an error, never a write through null.
    vtkErrorMacro("Cannot allocate the radiograph of " << pixels << " pixels.");
    output->Initialize();
    return 0;
  }
  EffectsOf(this).ApplyToImage(
    mcx::SMPExecutor(), pixels,
    [&](std::int64_t p) { return lineIntegral->GetComponent(static_cast<vtkIdType>(p), 0); },
    values->GetPointer(0));
  output->GetPointData()->AddArray(values);
  output->GetPointData()->SetActiveScalars(values->GetName());
  return 1;
}

void vtkMCXRadiograph::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BeerLambert: " << this->BeerLambert << "\n";
  os << indent << "IncidentIntensity: " << this->IncidentIntensity << "\n";
  os << indent << "PhotonsPerPixel: " << this->PhotonsPerPixel << "\n";
  os << indent << "NoiseSeed: " << this->NoiseSeed << "\n";
  os << indent << "NegativeLog: " << this->NegativeLog << "\n";
  os << indent << "ToldNotAttenuation: " << this->ToldNotAttenuation << "\n";
}
