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

} // namespace mcxapp

#endif
