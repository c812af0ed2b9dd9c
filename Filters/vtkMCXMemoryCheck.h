// Allocations that scale with user input (an image size, a sample count, a
// volume) are checked against a memory budget before any work starts, so
// that an absurd request fails with an error that names the size instead
// of aborting the process (std::bad_alloc) or swapping the machine to a
// halt. The budget is the machine's physical memory unless set (the command
// line's --memory-limit).
#ifndef vtkMCXMemoryCheck_h
#define vtkMCXMemoryCheck_h

#include "MonteCarloXRayFiltersModule.h" // for the export macro

#include <string>

class vtkObject;

namespace mcx
{

/// The budget in bytes: what SetMemoryBudget set, else the physical memory
/// (2^62 where that is unknown).
MONTECARLOXRAYFILTERS_EXPORT double MemoryBudget();

/// Sets the budget for this process; 0 goes back to the physical memory.
MONTECARLOXRAYFILTERS_EXPORT void SetMemoryBudget(double bytes);

/// "" when bytes fit the budget; else "<what> needs N, more than the memory
/// budget of B" (no full stop).
MONTECARLOXRAYFILTERS_EXPORT std::string MemoryProblem(double bytes, const std::string& what);

/// True when bytes fit the budget; else reports "<what> needs N, more than
/// the memory budget of B" as an error of self and returns false.
MONTECARLOXRAYFILTERS_EXPORT bool CheckMemory(
  vtkObject* self, double bytes, const std::string& what);

/// Bytes per pixel of a projection: the per-thread fixed-point sums (all
/// samples and the first half, 16 bytes each), their collection, the
/// float64 output, and the two buffers that exchange the sums between
/// processes (48 bytes each).
MONTECARLOXRAYFILTERS_EXPORT double ProjectionBytesPerPixel();

} // namespace mcx

#endif
