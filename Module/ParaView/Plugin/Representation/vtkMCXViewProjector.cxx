#include "vtkMCXViewProjector.h"

#include "vtkMCXCostPrivate.h"

#include "vtkImageData.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"

#include <cmath>
#include <string>

vtkStandardNewMacro(vtkMCXViewProjector);

int vtkMCXViewProjector::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // An index input projects 2^m - 1 samples, unless every voxel once or a
  // target chooses the count (from a pilot run, up to the maximum).
  if (vtkImageData::GetData(inputVector[0], 0) && this->GetStrategy() != vtkMCXTypes::EVERY_VOXEL)
  {
    const bool targeted =
      this->GetTargetRelativeError() > 0.0 || this->GetTargetQuantizationLevels() > 0;
    const int exponent = targeted ? this->GetMaximumSampleExponent() : this->GetSampleExponent();
    const std::string cost = mcx::ProjectionCost(std::ldexp(1.0, exponent) - 1.0);
    if (!cost.empty())
    {
      vtkWarningMacro("X-Ray Projector: " << cost << (targeted ? " at most" : "")
                                          << " before the image is shown.");
    }
  }
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

void vtkMCXViewProjector::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
