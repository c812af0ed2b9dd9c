#include "mcxSamplingMethod.h"

#include "mcxFail.h"

#include "vtkMCXPointSampler.h"

namespace mcxapp
{

bool IsSamplingMethod(const std::string& method)
{
  return method == "hybrid" || method == "mc" || method == "qmc";
}

bool IsCloudMethod(const std::string& method)
{
  return IsSamplingMethod(method) || method == "every-voxel" || method == "view-ordered";
}

int StrategyOf(const std::string& method)
{
  return method == "mc"       ? vtkMCXPointSampler::MONTE_CARLO
    : method == "qmc"         ? vtkMCXPointSampler::QUASI_MONTE_CARLO
    : method == "every-voxel"  ? vtkMCXPointSampler::EVERY_VOXEL
    : method == "view-ordered" ? vtkMCXPointSampler::VIEW_ORDERED
                               : vtkMCXPointSampler::HYBRID;
}

void CheckKernel(const std::string& kernel)
{
  if (kernel != "tent" && kernel != "box")
  {
    Fail("unknown --kernel '" + kernel + "' (expected tent or box)");
  }
}

void CheckDeposit(const std::string& deposit)
{
  if (deposit != "footprint" && deposit != "point")
  {
    Fail("unknown --deposit '" + deposit + "' (expected footprint or point)");
  }
}

int DepositOf(const std::string& deposit)
{
  return deposit == "point" ? vtkMCXPointSampler::POINT : vtkMCXPointSampler::FOOTPRINT;
}

int KernelOf(const std::string& kernel)
{
  return kernel == "box" ? vtkMCXPointSampler::BOX : vtkMCXPointSampler::TENT;
}

} // namespace mcxapp
