// The names of --method, --kernel and --deposit, and their vtkMCXTypes constants
// (the names are vtkMCXTypes's: StrategyFromName and the like).
#ifndef mcxSamplingMethod_h
#define mcxSamplingMethod_h

#include <string>

namespace mcxapp
{

/// hybrid, mc or qmc: the methods that sample points (not reference).
bool IsSamplingMethod(const std::string& method);
/// A sampling method, every-voxel or view-ordered: the methods that make a
/// point cloud.
bool IsCloudMethod(const std::string& method);

/// The vtkMCXTypes strategy of a sampling method.
int StrategyOf(const std::string& method);

/// Fails unless kernel is tent or box.
void CheckKernel(const std::string& kernel);

/// Fails unless deposit is footprint or point.
void CheckDeposit(const std::string& deposit);

/// The vtkMCXTypes deposit of footprint or point.
int DepositOf(const std::string& deposit);

/// The vtkMCXTypes kernel of tent or box.
int KernelOf(const std::string& kernel);

} // namespace mcxapp

#endif
