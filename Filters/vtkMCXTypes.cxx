#include "vtkMCXTypes.h"

#include "mcxFootprint.h"
#include "mcxSampleGenerator.h"

#include "vtkObjectFactory.h"

#include <cstring>

vtkStandardNewMacro(vtkMCXTypes);

// The public constants are the core's, seen from VTK.
static_assert(vtkMCXTypes::HYBRID == static_cast<int>(mcx::Strategy::Hybrid) &&
    vtkMCXTypes::MONTE_CARLO == static_cast<int>(mcx::Strategy::MonteCarlo) &&
    vtkMCXTypes::QUASI_MONTE_CARLO == static_cast<int>(mcx::Strategy::QuasiMonteCarlo),
  "strategy values differ from mcx::Strategy");
static_assert(vtkMCXTypes::TENT == static_cast<int>(mcx::Kernel::Tent) &&
    vtkMCXTypes::BOX == static_cast<int>(mcx::Kernel::Box),
  "kernel values differ from mcx::Kernel");
static_assert(vtkMCXTypes::POINT == static_cast<int>(mcx::Deposit::Point) &&
    vtkMCXTypes::FOOTPRINT == static_cast<int>(mcx::Deposit::Footprint),
  "deposit values differ from mcx::Deposit");
static_assert(vtkMCXTypes::LargestSampleExponent == static_cast<int>(mcx::MaximumSampleExponent),
  "the largest sample exponent differs from the core's");

namespace
{
// Command names in the order of the enumerations' values.
const char* const StrategyNames[] = { "hybrid", "mc", "qmc", "every-voxel", "view-ordered" };
const char* const KernelNames[] = { "tent", "box" };
const char* const DepositNames[] = { "point", "footprint" };

template <std::size_t N>
const char* NameOf(const char* const (&names)[N], int value)
{
  return value >= 0 && static_cast<std::size_t>(value) < N ? names[value] : nullptr;
}

template <std::size_t N>
int ValueOf(const char* const (&names)[N], const char* name)
{
  for (std::size_t i = 0; name && i < N; ++i)
  {
    if (std::strcmp(names[i], name) == 0)
    {
      return static_cast<int>(i);
    }
  }
  return -1;
}
}

const char* vtkMCXTypes::StrategyCommandName(int strategy)
{
  return NameOf(StrategyNames, strategy);
}

const char* vtkMCXTypes::KernelCommandName(int kernel)
{
  return NameOf(KernelNames, kernel);
}

const char* vtkMCXTypes::DepositCommandName(int deposit)
{
  return NameOf(DepositNames, deposit);
}

int vtkMCXTypes::StrategyFromName(const char* name)
{
  return ValueOf(StrategyNames, name);
}

int vtkMCXTypes::KernelFromName(const char* name)
{
  return ValueOf(KernelNames, name);
}

int vtkMCXTypes::DepositFromName(const char* name)
{
  return ValueOf(DepositNames, name);
}

void vtkMCXTypes::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DefaultSampleExponent: " << DefaultSampleExponent << "\n";
  os << indent << "MaximumPointCloudExponent: " << MaximumPointCloudExponent << "\n";
  os << indent << "LargestSampleExponent: " << LargestSampleExponent << "\n";
  os << indent << "PilotSampleExponent: " << PilotSampleExponent << "\n";
}
