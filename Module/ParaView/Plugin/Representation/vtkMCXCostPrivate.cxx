#include "vtkMCXCostPrivate.h"

#include "vtkMCXMemoryCheck.h"

#include "vtkNew.h"
#include "vtkSMDoubleRangeDomain.h"
#include "vtkSMDoubleVectorProperty.h"
#include "vtkSMIntRangeDomain.h"
#include "vtkSMIntVectorProperty.h"
#include "vtkSMPropertyIterator.h"
#include "vtkSMProxy.h"

#include <algorithm>

#include <cmath>
#include <cstdio>

namespace
{
std::string Bytes(double bytes)
{
  char text[32];
  if (bytes >= std::ldexp(1.0, 30))
  {
    std::snprintf(text, sizeof(text), "%.1f GiB", bytes / std::ldexp(1.0, 30));
  }
  else
  {
    std::snprintf(text, sizeof(text), "%.0f MiB", bytes / std::ldexp(1.0, 20));
  }
  return text;
}

std::string Seconds(double seconds)
{
  char text[32];
  if (seconds >= 120.0)
  {
    std::snprintf(text, sizeof(text), "%.0f min", seconds / 60.0);
  }
  else
  {
    std::snprintf(text, sizeof(text), "%.0f s", seconds);
  }
  return text;
}
}

namespace mcx
{

std::string StoredCloudCost(int exponent)
{
  const double points = std::ldexp(1.0, exponent) - 1.0;
  const double bytes = 12.0 * points; // float triples
  const double budget = MemoryBudget();
  const double seconds = points / StoredPointsPerSecond;
  if (bytes <= 0.25 * budget && seconds <= LongRequestSeconds)
  {
    return std::string();
  }
  char share[64] = "";
  if (budget < std::ldexp(1.0, 61))
  {
    std::snprintf(share, sizeof(share), " (%.0f %% of the %s of memory)", 100.0 * bytes / budget,
      Bytes(budget).c_str());
  }
  char text[256];
  std::snprintf(text, sizeof(text), "%.0f points, a %s cloud%s and about %s for a full image",
    points, Bytes(bytes).c_str(), share, Seconds(seconds).c_str());
  return text;
}

std::string ProjectionCost(double samples)
{
  const double seconds = samples / ProjectedSamplesPerSecond;
  if (seconds <= LongRequestSeconds)
  {
    return std::string();
  }
  char text[128];
  std::snprintf(text, sizeof(text), "%.0f samples, about %s", samples, Seconds(seconds).c_str());
  return text;
}

namespace
{
// Clamps the elements of `property` (int or double) to `domain`'s entries
// (one per element, or the first for all).
template <typename Property, typename Domain>
bool ClampElements(Property* property, Domain* domain)
{
  if (!property || !domain || property->GetInformationOnly())
  {
    return false;
  }
  bool changed = false;
  for (unsigned int i = 0; i < property->GetNumberOfElements(); ++i)
  {
    const unsigned int entry = domain->GetNumberOfEntries() > i ? i : 0;
    auto value = property->GetElement(i);
    int exists = 0;
    const auto low = domain->GetMinimum(entry, exists);
    if (exists && value < low)
    {
      value = low;
    }
    const auto high = domain->GetMaximum(entry, exists);
    if (exists && value > high)
    {
      value = high;
    }
    if (value != property->GetElement(i))
    {
      property->SetElement(i, value);
      changed = true;
    }
  }
  return changed;
}
}

bool ClampToRangeDomains(vtkSMProxy* proxy, const std::string& prefix)
{
  bool changed = false;
  vtkNew<vtkSMPropertyIterator> properties;
  properties->SetProxy(proxy);
  for (properties->Begin(); !properties->IsAtEnd(); properties->Next())
  {
    vtkSMProperty* property = properties->GetProperty();
    if (std::string(properties->GetKey()).compare(0, prefix.size(), prefix) != 0)
    {
      continue;
    }
    changed |= ClampElements(
      vtkSMIntVectorProperty::SafeDownCast(property), property->FindDomain<vtkSMIntRangeDomain>());
    changed |= ClampElements(vtkSMDoubleVectorProperty::SafeDownCast(property),
      property->FindDomain<vtkSMDoubleRangeDomain>());
  }
  return changed;
}

} // namespace mcx
