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
/// per mm of what a CT holds: CT numbers stop at 3071 HU (12 bits), which
/// mu = mu_water (1 + HU / 1000) makes 4.07 mu_water, 0.092 per mm at 50 keV
/// (water 0.0227 per mm, NIST XCOM; the lowest energy X-Ray Water
/// Attenuation lists, and mu only falls with energy above it). A 0-1 weight
/// reaches 1. Metal (steel about 1 per mm at 60 keV) is above it too, but a
/// CT number cannot say so.
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
