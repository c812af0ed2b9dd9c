#include "vtkMCXMemoryCheck.h"

#include "mcxByteSize.h"

#include "vtkObject.h"
#include "vtkSMPTools.h"
#include "vtksys/SystemInformation.hxx"

#include <atomic>
#include <cmath>

namespace mcx
{

namespace
{
std::atomic<double> Budget{ 0.0 };

double PhysicalMemory()
{
  vtksys::SystemInformation system;
  return static_cast<double>(system.GetHostMemoryTotal()) * 1024.0; // KiB
}
}

double MemoryBudget()
{
  const double set = Budget.load();
  if (set > 0)
  {
    return set;
  }
  const double physical = PhysicalMemory();
  return physical > 0 ? physical : std::ldexp(1.0, 62); // unknown: in effect none
}

void SetMemoryBudget(double bytes)
{
  Budget.store(bytes > 0 ? bytes : 0.0);
}

std::string MemoryProblem(double bytes, const std::string& what)
{
  const double budget = MemoryBudget();
  if (bytes <= budget)
  {
    return std::string();
  }
  return what + " needs " + DescribeBytes(bytes) + ", more than the memory budget of " +
    DescribeBytes(budget);
}

bool CheckMemory(vtkObject* self, double bytes, const std::string& what)
{
  const std::string problem = MemoryProblem(bytes, what);
  if (problem.empty())
  {
    return true;
  }
  vtkErrorWithObjectMacro(self, << problem << ".");
  return false;
}

double ProjectionBytesPerPixel()
{
  return 32.0 * vtkSMPTools::GetEstimatedNumberOfThreads() + 48.0 + 96.0;
}

} // namespace mcx
