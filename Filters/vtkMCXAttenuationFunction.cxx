#include "vtkMCXAttenuationFunction.h"

#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkMCXAttenuationFunction);

void vtkMCXAttenuationFunction::SetHounsfieldRange(double lowest, double highest)
{
  if (!(highest > lowest) || !std::isfinite(lowest) || !std::isfinite(highest))
  {
    vtkErrorMacro(
      "HounsfieldRange needs finite lowest < highest, not " << lowest << ", " << highest << ".");
    return;
  }
  if (lowest != this->HounsfieldRange[0] || highest != this->HounsfieldRange[1])
  {
    this->HounsfieldRange[0] = lowest;
    this->HounsfieldRange[1] = highest;
    this->Modified();
  }
}

void vtkMCXAttenuationFunction::FillTransferFunction(vtkPiecewiseFunction* tf)
{
  if (!tf)
  {
    vtkErrorMacro("FillTransferFunction needs a vtkPiecewiseFunction, not null.");
    return;
  }
  // Piecewise linear and exact: 0 up to air, then the straight line of mu.
  const double lowest = this->HounsfieldRange[0];
  const double highest = this->HounsfieldRange[1];
  auto mu = [this](double hu)
  { return std::max(0.0, this->WaterAttenuation * (1.0 + hu / 1000.0)); };
  tf->RemoveAllPoints();
  tf->ClampingOn();
  tf->AddPoint(lowest, mu(lowest));
  if (lowest < -1000.0 && highest > -1000.0)
  {
    tf->AddPoint(-1000.0, 0.0);
  }
  tf->AddPoint(highest, mu(highest));
}

void vtkMCXAttenuationFunction::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "WaterAttenuation: " << this->WaterAttenuation << "\n";
  os << indent << "HounsfieldRange: " << this->HounsfieldRange[0] << " " << this->HounsfieldRange[1]
     << "\n";
}
