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
  std::uint64_t NoiseSeed = 0;
  bool NegativeLog = false;

  /// What a radiograph's properties ask for: any effect implies Beer-Lambert,
  /// because noise and the log act on intensities.
  static RadiographEffects FromProperties(bool beerLambert, double incidentIntensity,
    double photonsPerPixel, std::uint64_t noiseSeed, bool negativeLog)
  {
    RadiographEffects effects;
    effects.BeerLambert = beerLambert || photonsPerPixel > 0 || negativeLog;
    effects.IncidentIntensity = incidentIntensity;
    effects.PhotonsPerPixel = photonsPerPixel;
    effects.NoiseSeed = noiseSeed;
    effects.NegativeLog = negativeLog;
    return effects;
  }

  bool Any() const { return this->BeerLambert || this->PhotonsPerPixel > 0 || this->NegativeLog; }

  bool operator==(const RadiographEffects& other) const
  {
    return this->BeerLambert == other.BeerLambert &&
      this->IncidentIntensity == other.IncidentIntensity &&
      this->PhotonsPerPixel == other.PhotonsPerPixel && this->NoiseSeed == other.NoiseSeed &&
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

  /// values[p] = Apply(lineIntegralOf(p), p) for every pixel p < pixels, in
  /// parallel on `executor` (values may be where lineIntegralOf reads).
  template <typename Executor, typename LineIntegralOf, typename Value>
  void ApplyToImage(const Executor& executor, std::int64_t pixels,
    const LineIntegralOf& lineIntegralOf, Value* values) const
  {
    const std::uint64_t seedKey = SeedKey(this->NoiseSeed);
    executor.For(0, pixels, 4096,
      [&](std::int64_t begin, std::int64_t end)
      {
        for (std::int64_t p = begin; p < end; ++p)
        {
          values[p] = static_cast<Value>(
            this->Apply(lineIntegralOf(p), static_cast<std::uint64_t>(p), seedKey));
        }
      });
  }
};

} // namespace mcx

#endif
