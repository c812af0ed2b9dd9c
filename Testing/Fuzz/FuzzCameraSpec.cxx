// libFuzzer target: --camera specs on arbitrary text. A spec is refused
// with one line, or gives a camera whose position, focal point and view-up
// are finite and apart.
#include "FuzzFailThrows.h"
#include "mcxCameraSpec.h"

#include "vtkCamera.h"
#include "vtkMath.h"

#include <cmath>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  mcxfuzz::ThrowOnFail();
  const std::string text(reinterpret_cast<const char*>(data), size);
  try
  {
    vtkSmartPointer<vtkCamera> camera = mcxapp::ParseCamera(text);
    const double* p = camera->GetPosition();
    const double* f = camera->GetFocalPoint();
    const double distance = std::sqrt(vtkMath::Distance2BetweenPoints(p, f));
    if (!std::isfinite(distance) || !(distance > 0))
    {
      __builtin_trap();
    }
    double u[3], v[3];
    mcxapp::AxisViewDetector(text.size() > 1 ? text.substr(0, 2) : text, u, v);
  }
  catch (const mcxfuzz::Refusal&)
  {
  }
  return 0;
}
