#include "vtkMCXRadiograph.h"

#include "mcxRadiographEffects.h"
#include "vtkMCXProjectorBase.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"

vtkStandardNewMacro(vtkMCXRadiograph);

namespace
{
mcx::RadiographEffects EffectsOf(bool beerLambert, double incident, double photons, vtkTypeInt64 seed, bool negativeLog)
{
  mcx::RadiographEffects effects;
  effects.BeerLambert = beerLambert;
  effects.IncidentIntensity = incident;
  effects.PhotonsPerPixel = photons;
  effects.Seed = static_cast<std::uint64_t>(seed);
  effects.NegativeLog = negativeLog;
  return effects;
}
}

bool vtkMCXRadiograph::HasEffects() const
{
  return EffectsOf(this->BeerLambert, this->IncidentIntensity, this->PhotonsPerPixel, this->Seed, this->NegativeLog)
    .Any();
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
  vtkDataArray* lineIntegral = input->GetPointData()->GetArray(vtkMCXProjectorBase::LineIntegralName());
  if (!lineIntegral || lineIntegral->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("The input has no one-component LineIntegral array (make it with vtkMCXProjector).");
    output->Initialize();
    return 0;
  }
  // Any effect implies Beer-Lambert: noise and the log act on intensities.
  const mcx::RadiographEffects effects =
    EffectsOf(true, this->IncidentIntensity, this->PhotonsPerPixel, this->Seed, this->NegativeLog);
  const std::uint64_t seedKey = mcx::SeedKey(effects.Seed);

  vtkNew<vtkDoubleArray> values;
  values->SetName(this->NegativeLog ? "Attenuation" : "Intensity");
  const vtkIdType pixels = lineIntegral->GetNumberOfTuples();
  values->SetNumberOfValues(pixels);
  double* out = values->GetPointer(0);
  vtkSMPTools::For(0, pixels, 4096, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType p = begin; p < end; ++p)
    {
      out[p] = effects.Apply(lineIntegral->GetComponent(p, 0), static_cast<std::uint64_t>(p), seedKey);
    }
  });
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
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "NegativeLog: " << this->NegativeLog << "\n";
}
