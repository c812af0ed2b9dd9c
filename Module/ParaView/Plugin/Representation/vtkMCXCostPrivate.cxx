#include "vtkMCXCostPrivate.h"

#include "vtkMCXMemoryCheckPrivate.h"

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

} // namespace mcx
