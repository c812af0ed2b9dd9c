// X-Ray Attenuation "HU to mu" of the representation and X-Ray Projector:
// mcxray's own composition of mu(HU) and the TF as a 0-1 weight
// (mcxapp::MakeWeightedAttenuation, `mcxray view`'s key b), with the
// viewer's rule for air, and the one-line warning for radiograph physics of
// a TF that is not an attenuation.
#ifndef vtkMCXAttenuationModePrivate_h
#define vtkMCXAttenuationModePrivate_h

#include "vtkSmartPointer.h" // for the result

#include <string>

class vtkImageData;
class vtkPiecewiseFunction;

namespace mcx
{

/// A TF whose values reach above this (per world unit) is not an attenuation
/// per mm (water 0.02, dense bone about 0.08 at 70 keV).
constexpr double LargestAttenuation = 0.1;

/// The densities of a density index (its LevelValues, lowest and highest);
/// false when it has none.
bool IndexDensityRange(vtkImageData* index, double range[2]);

/// mu(HU) x weight over the densities `range`: HU = value for CT in HU
/// (lowest value -500 or below), else the lowest value is air (-1000 HU), as
/// in `mcxray view`; a null weight selects all tissue.
vtkSmartPointer<vtkPiecewiseFunction> WeightedAttenuation(
  vtkPiecewiseFunction* weight, double water, const double range[2]);

/// The largest value of the TF's points (0 without points).
double LargestValue(vtkPiecewiseFunction* tf);

/// The warning (one line) for Beer-Lambert
/// or noise of a TF up to `largest` that is not an attenuation.
std::string NotAttenuationWarning(double largest);

} // namespace mcx

#endif
