// What a request of the plugin's properties will cost, said before the work
// starts: a ParaView user who types a large sample exponent learns the size
// and the time in one warning line instead of a GUI that freezes silently.
// The rates are this project's measurements on its 2-core test machine
// (Documentation/paraview.md): a machine with more cores is faster.
#ifndef vtkMCXCostPrivate_h
#define vtkMCXCostPrivate_h

#include <string>

namespace mcx
{

/// Points a second the X-ray representation samples and draws (stored cloud).
constexpr double StoredPointsPerSecond = 5.0e6;
/// Samples a second X-Ray Projector projects from an index (never stored).
constexpr double ProjectedSamplesPerSecond = 1.5e7;
/// A request is said when it takes longer than this or a quarter of the memory.
constexpr double LongRequestSeconds = 10.0;

/// "" for a cheap stored cloud of 2^exponent - 1 points; else "N points, a
/// cloud of S (P % of the memory) and about T s for a full image" (no full stop).
std::string StoredCloudCost(int exponent);

/// "" for a quick projection of `samples`; else "N samples, about T s".
std::string ProjectionCost(double samples);

} // namespace mcx

#endif
