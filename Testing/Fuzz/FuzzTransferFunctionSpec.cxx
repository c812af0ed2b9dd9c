// libFuzzer target: transfer-function specs ("value:weight,...", presets)
// on arbitrary text. A spec either builds a TF whose points are finite and
// ascending, or is refused with a reason.
#include "mcxTransferFunctionSpec.h"

#include "vtkPiecewiseFunction.h"

#include <cmath>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string spec(reinterpret_cast<const char*>(data), size);
  const double range[2] = { -1024.0, 3071.0 };
  std::string error;
  vtkSmartPointer<vtkPiecewiseFunction> tf = mcxapp::MakeTransferFunction(spec, range, error);
  if (!tf)
  {
    if (error.empty())
    {
      __builtin_trap(); // a refusal must say why (Fail makes it one line)
    }
    return 0;
  }
  double previous = -INFINITY;
  for (int n = 0; n < tf->GetSize(); ++n)
  {
    double node[4];
    tf->GetNodeValue(n, node);
    if (!std::isfinite(node[0]) || !std::isfinite(node[1]) || node[0] < previous)
    {
      __builtin_trap();
    }
    previous = node[0];
  }
  return 0;
}
