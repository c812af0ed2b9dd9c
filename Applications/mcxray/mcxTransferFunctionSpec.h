// Transfer functions from the command line: "value:weight,value:weight,..."
// in data units, or a named CT preset.
#ifndef mcxTransferFunctionSpec_h
#define mcxTransferFunctionSpec_h

#include "vtkSmartPointer.h"

#include <string>

class vtkPiecewiseFunction;

namespace mcxapp
{

/// Names of the presets, for --help.
const char* TransferFunctionPresetHelp();

/// Builds the TF for spec. dataRange is the volume's value range (used by the
/// "raw" preset). Outside its points the function holds its end values.
/// Returns null and sets error on a malformed spec.
vtkSmartPointer<vtkPiecewiseFunction> MakeTransferFunction(
  const std::string& spec, const double dataRange[2], std::string& error);

/// Whether spec is the attenuation preset, "mu" or "mu=MU_WATER".
bool IsAttenuationSpec(const std::string& spec);

/// The value that counts as air in a volume of values dataRange: -1000 for
/// CT in HU (a lowest value at or below -500 HU), else the lowest value.
double AirValueOf(const double dataRange[2]);

/// "" for values that reach air (AirValueOf), else "the values LOW .. HIGH
/// hold no air (none at or below -500)": what a warning says before what is
/// done about it (CT cropped inside the body, or not in HU at all).
std::string NoAirNote(const double dataRange[2]);

/// The attenuation of a radiograph of the tissue `weight` selects: mu =
/// water (1 + HU / 1000) per world unit (0 at and below air), HU = value -
/// airValue - 1000 (airValue -1000 for CT in HU), times the weight clamped to
/// [0, 1] (a null weight selects all tissue). Exact at the weight's points
/// and the data range's ends, between them within 0.1 % of its largest value.
vtkSmartPointer<vtkPiecewiseFunction> MakeWeightedAttenuation(
  vtkPiecewiseFunction* weight, double water, double airValue, const double dataRange[2]);

} // namespace mcxapp

#endif
