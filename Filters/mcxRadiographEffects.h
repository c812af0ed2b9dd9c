// The per-pixel physics of a radiograph, after accumulation: shared by
// vtkMCXRadiograph (off line) and the mapper (on screen).
#ifndef mcxRadiographEffects_h
#define mcxRadiographEffects_h

#include "mcxPoisson.h"
#include "mcxRandom.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace mcx
{

struct RadiographEffects
{
  bool BeerLambert = false;
  double IncidentIntensity = 1.0;
  double PhotonsPerPixel = 0.0; // 0: no noise
  std::uint64_t Seed = 0;
  bool NegativeLog = false;

  bool Any() const { return this->BeerLambert || this->PhotonsPerPixel > 0 || this->NegativeLog; }

  bool operator==(const RadiographEffects& other) const
  {
    return this->BeerLambert == other.BeerLambert && this->IncidentIntensity == other.IncidentIntensity &&
      this->PhotonsPerPixel == other.PhotonsPerPixel && this->Seed == other.Seed &&
      this->NegativeLog == other.NegativeLog;
  }
  bool operator!=(const RadiographEffects& other) const { return !(*this == other); }

  /// The value of pixel `pixel` whose line integral of mu is `lineIntegral`:
  /// I0 exp(-L), its Poisson-noisy version, or -ln(I / I0).
  double Apply(double lineIntegral, std::uint64_t pixel, std::uint64_t seedKey) const
  {
    double transmission = std::exp(-std::max(lineIntegral, 0.0));
    if (this->PhotonsPerPixel > 0)
    {
      CounterRandom random(seedKey, pixel);
      const double counts = PoissonVariate(this->PhotonsPerPixel * transmission, random);
      // No photons at all: half a photon keeps -ln finite.
      transmission = std::max(counts, this->NegativeLog ? 0.5 : 0.0) / this->PhotonsPerPixel;
    }
    if (this->NegativeLog)
    {
      return this->PhotonsPerPixel > 0 ? -std::log(transmission) : std::max(lineIntegral, 0.0);
    }
    return this->IncidentIntensity * transmission;
  }
};

} // namespace mcx

#endif
