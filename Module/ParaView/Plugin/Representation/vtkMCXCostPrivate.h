// What a request of the plugin's properties will cost, said before the work
// starts: a ParaView user who types a large sample exponent learns the size
// and the time in one warning line instead of a GUI that freezes silently.
// The rates are this project's measurements on its 2-core test machine
// (Documentation/paraview.md): a machine with more cores is faster. And the
// panel's fields clamped to what the classes accept.
#ifndef vtkMCXCostPrivate_h
#define vtkMCXCostPrivate_h

#include <string>

class vtkSMProxy;

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

/// Clamps every int and double vector property of the proxy whose name starts
/// with `prefix` and that has a range domain to that range, the ranges being
/// the classes' (not pushed: the
/// proxies call it after pushing, so that the class has clamped and warned,
/// and the panel then shows what the class uses). True when one changed.
bool ClampToRangeDomains(vtkSMProxy* proxy, const std::string& prefix);

} // namespace mcx

#endif
