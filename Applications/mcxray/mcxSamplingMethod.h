// The names of --method, --kernel and --deposit, and the sampler's constants for them.
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

/// vtkMCXPointSampler's strategy for a sampling method.
int StrategyOf(const std::string& method);

/// Fails unless kernel is tent or box.
void CheckKernel(const std::string& kernel);

/// Fails unless deposit is footprint or point.
void CheckDeposit(const std::string& deposit);

/// vtkMCXPointSampler's deposit for footprint or point.
int DepositOf(const std::string& deposit);

/// vtkMCXPointSampler's kernel for tent or box.
int KernelOf(const std::string& kernel);

} // namespace mcxapp

#endif
