// Exact Poisson variates from a counter-based stream, so that noisy images
// are the same for any number of threads: inversion by sequential search
// below a mean of 10, Hormann's transformed rejection with squeeze (PTRS,
// "The transformed rejection method for generating Poisson random
// variables", 1993) above it -- the pair NumPy uses.
#ifndef mcxPoisson_h
#define mcxPoisson_h

#include "mcxRandom.h"

#include <cmath>
#include <cstdint>

namespace mcx
{

/// A Poisson(mean) variate drawn from `random`; mean <= 0 or NaN gives 0.
inline double PoissonVariate(double mean, CounterRandom& random)
{
  if (!(mean > 0))
  {
    return 0.0;
  }
  if (mean < 10.0)
  {
    // Inversion: the smallest k whose cumulative probability reaches u.
    const double u = random.NextOpenClosed();
    double p = std::exp(-mean);
    double cumulative = p;
    double k = 0.0;
    while (cumulative < u && k < 1000.0)
    {
      k += 1.0;
      p *= mean / k;
      cumulative += p;
    }
    return k;
  }
  const double root = std::sqrt(mean);
  const double logMean = std::log(mean);
  const double b = 0.931 + 2.53 * root;
  const double a = -0.059 + 0.02483 * b;
  const double inverseAlpha = 1.1239 + 1.1328 / (b - 3.4);
  const double vr = 0.9277 - 3.6224 / (b - 2.0);
  for (;;)
  {
    const double u = random.NextOpenClosed() - 0.5;
    const double v = random.NextOpenClosed();
    const double us = 0.5 - std::fabs(u);
    const double k = std::floor((2.0 * a / us + b) * u + mean + 0.43);
    if (us >= 0.07 && v <= vr)
    {
      return k;
    }
    if (k < 0 || (us < 0.013 && v > us))
    {
      continue;
    }
    if (std::log(v) + std::log(inverseAlpha) - std::log(a / (us * us) + b) <=
      -mean + k * logMean - std::lgamma(k + 1.0))
    {
      return k;
    }
  }
}

} // namespace mcx

#endif
