#include "mcxSamplingMethod.h"

#include "mcxFail.h"

#include "vtkMCXTypes.h"

namespace mcxapp
{

bool IsSamplingMethod(const std::string& method)
{
  const int strategy = vtkMCXTypes::StrategyFromName(method.c_str());
  return strategy == vtkMCXTypes::HYBRID || strategy == vtkMCXTypes::MONTE_CARLO ||
    strategy == vtkMCXTypes::QUASI_MONTE_CARLO;
}

bool IsCloudMethod(const std::string& method)
{
  return vtkMCXTypes::StrategyFromName(method.c_str()) >= 0;
}

int StrategyOf(const std::string& method)
{
  const int strategy = vtkMCXTypes::StrategyFromName(method.c_str());
  return strategy >= 0 ? strategy : vtkMCXTypes::HYBRID;
}

void CheckKernel(const std::string& kernel)
{
  if (vtkMCXTypes::KernelFromName(kernel.c_str()) < 0)
  {
    Fail("unknown --kernel '" + kernel + "' (expected tent or box)");
  }
}

void CheckDeposit(const std::string& deposit)
{
  if (vtkMCXTypes::DepositFromName(deposit.c_str()) < 0)
  {
    Fail("unknown --deposit '" + deposit + "' (expected footprint or point)");
  }
}

int DepositOf(const std::string& deposit)
{
  const int value = vtkMCXTypes::DepositFromName(deposit.c_str());
  return value >= 0 ? value : vtkMCXTypes::FOOTPRINT;
}

int KernelOf(const std::string& kernel)
{
  const int value = vtkMCXTypes::KernelFromName(kernel.c_str());
  return value >= 0 ? value : vtkMCXTypes::TENT;
}

} // namespace mcxapp
