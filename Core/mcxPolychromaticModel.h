// The per-pixel physics of a polychromatic radiograph: from each material's
// line integral L_m (g/cm^2) to the detected signal relative to the open
// beam, T = sum_E w(E) exp(-sum_m (mu/rho)_m(E) L_m) with w = S D / sum S D,
// S the spectrum's photons and D the detector's response. Its -ln T is the
// effective line integral that mcxRadiographEffects.h turns into intensity,
// noise and the negative log, as for a monochromatic image.
#ifndef mcxPolychromaticModel_h
#define mcxPolychromaticModel_h

#include "mcxTubeSpectrum.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace mcx
{

/// Energy integrating (signal E x absorbed fraction) or photon counting
/// (absorbed fraction); the absorbed fraction of a screen of ScreenMaterial
/// ScreenThickness mm thick is 1 - exp(-mu rho t), of no screen 1 (ideal).
struct Detector
{
  bool PhotonCounting = false;
  std::string ScreenMaterial;   // empty: ideal absorber
  double ScreenThickness = 0.0; // mm
  double ScreenDensity = 0.0;   // g/cm^3; 0: xraylib's, else required for a formula
  /// The response D(E) at each of the spectrum's energies.
  std::vector<double> Response(const Spectrum& spectrum) const;
};

/// "integrating" (default), "counting", optionally followed by
/// ",<material>:<mm>[:<g/cm3>]", e.g. "integrating,CsI:0.6:4.51",
/// "counting,Gd2O2S:0.2:7.3". Throws std::invalid_argument with one line.
Detector ParseDetector(const std::string& text);

class PolychromaticModel
{
public:
  PolychromaticModel() = default;
  /// Throws std::invalid_argument for an empty spectrum or unknown material.
  PolychromaticModel(
    const Spectrum& spectrum, const Detector& detector, const std::vector<std::string>& materials);

  std::size_t Bins() const { return this->Weights.size(); }
  std::size_t Materials() const { return this->MaterialCount; }
  /// The spectrum's photons x response, normalised to sum 1.
  const std::vector<double>& EnergyWeights() const { return this->Weights; }
  /// (mu/rho) of material m at bin e in cm^2/g.
  double MassAttenuation(std::size_t m, std::size_t e) const
  {
    return this->Attenuation[m * this->Bins() + e];
  }

  /// T for the line integrals areaDensity[m] (g/cm^2), in (0, 1].
  double Transmission(const double* areaDensity) const
  {
    const std::size_t bins = this->Bins();
    double sum = 0.0;
    for (std::size_t e = 0; e < bins; ++e)
    {
      double exponent = 0.0;
      for (std::size_t m = 0; m < this->MaterialCount; ++m)
      {
        exponent += this->Attenuation[m * bins + e] * std::max(areaDensity[m], 0.0);
      }
      sum += this->Weights[e] * std::exp(-exponent);
    }
    return sum;
  }

  /// -ln T: the line integral a monochromatic radiograph would need for the
  /// same signal (infinite where T underflows to 0).
  double EffectiveLineIntegral(const double* areaDensity) const
  {
    const double t = this->Transmission(areaDensity);
    return t > 0.0 ? -std::log(t) : HUGE_VAL;
  }

  /// out[p] = EffectiveLineIntegral of pixel p for p < pixels, where the
  /// line integral of material m at pixel p is channels[m][p] x scale
  /// (scale turns the channels' units into g/cm^2), in parallel.
  template <typename Executor, typename Channel, typename Out>
  void EffectiveImage(const Executor& executor, std::int64_t pixels, const Channel* const* channels,
    double scale, Out* out) const
  {
    executor.For(0, pixels, 1024,
      [&](std::int64_t begin, std::int64_t end)
      {
        std::vector<double> l(this->MaterialCount);
        for (std::int64_t p = begin; p < end; ++p)
        {
          for (std::size_t m = 0; m < this->MaterialCount; ++m)
          {
            l[m] = static_cast<double>(channels[m][p]) * scale;
          }
          out[p] = static_cast<Out>(this->EffectiveLineIntegral(l.data()));
        }
      });
  }

private:
  std::vector<double> Weights;
  std::vector<double> Attenuation; // [m * Bins + e]
  std::size_t MaterialCount = 0;
};

} // namespace mcx

#endif
