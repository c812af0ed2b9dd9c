#include "vtkMCXAttenuationModePrivate.h"

#include "mcxTransferFunctionSpec.h" // mcxray's mu(HU) x weight
#include "vtkMCXTypes.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkPiecewiseFunction.h"

#include <algorithm>
#include <sstream>

namespace mcx
{

bool IndexDensityRange(vtkImageData* index, double range[2])
{
  vtkDataArray* levels =
    index ? index->GetFieldData()->GetArray(vtkMCXTypes::LevelValuesName()) : nullptr;
  if (!levels || levels->GetNumberOfTuples() < 1)
  {
    return false;
  }
  range[0] = levels->GetTuple1(0);
  range[1] = levels->GetTuple1(levels->GetNumberOfTuples() - 1);
  return true;
}

vtkSmartPointer<vtkPiecewiseFunction> WeightedAttenuation(
  vtkPiecewiseFunction* weight, double water, const double range[2])
{
  const double air = range[0] <= -500.0 ? -1000.0 : range[0];
  const double dataRange[2] = { range[0], std::max(range[1], range[0] + 1.0) };
  return mcxapp::MakeWeightedAttenuation(weight, water, air, dataRange);
}

double LargestValue(vtkPiecewiseFunction* tf)
{
  double largest = 0.0;
  for (int i = 0; tf && i < tf->GetSize(); ++i)
  {
    double node[4];
    tf->GetNodeValue(i, node);
    largest = std::max(largest, node[1]);
  }
  return largest;
}

std::string NotAttenuationWarning(double largest)
{
  std::ostringstream text;
  text << "Monte Carlo X-Ray: Beer-Lambert needs a TF in attenuation per mm (water 0.02), not a "
          "0-1 weight (this one reaches "
       << largest
       << ": line integrals of about 100, a black image); set X-Ray Attenuation to 'HU to mu' "
          "to keep the TF a 0-1 weight on mu(HU).";
  return text.str();
}

} // namespace mcx
