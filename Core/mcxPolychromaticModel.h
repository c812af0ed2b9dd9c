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
#include <cstring>
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
  /// The pixels whose error EffectiveImage propagates: every 16th, enough for
  /// an image's estimate, at a 16th of the cost of all (it doubled the time).
  static constexpr std::int64_t ErrorStride = 16;
  std::size_t Materials() const { return this->MaterialCount; }
  /// The spectrum's photons x response, normalised to sum 1.
  const std::vector<double>& EnergyWeights() const { return this->Weights; }
  /// (mu/rho) of material m at bin e in cm^2/g.
  double MassAttenuation(std::size_t m, std::size_t e) const
  {
    return this->Attenuation[m * this->Bins() + e];
  }

  /// Doubles of scratch space Transmission needs.
  std::size_t ScratchSize() const { return 3 * this->Bins(); }

  /// T for the line integrals areaDensity[m] (g/cm^2), in (0, 1]; `scratch`
  /// holds ScratchSize() values.
  double Transmission(const double* areaDensity, double* scratch) const
  {
    const std::size_t bins = this->Bins();
    double* exponent = scratch;
    for (std::size_t e = 0; e < bins; ++e)
    {
      exponent[e] = 0.0;
    }
    // Materials outside, energies inside: loops the compiler vectorises.
    for (std::size_t m = 0; m < this->MaterialCount; ++m)
    {
      // 0 for negative and NaN, at most 1e6 g/cm^2 (a in ExpOfNegative's range).
      const double l = areaDensity[m] > 0.0 ? std::min(areaDensity[m], 1e6) : 0.0;
      const double* mu = this->Attenuation.data() + m * bins;
      for (std::size_t e = 0; e < bins; ++e)
      {
        exponent[e] += mu[e] * l;
      }
    }
    double* value = scratch + bins;
    ExpOfNegative(exponent, value, scratch + 2 * bins, bins);
    double sum = 0.0;
    for (std::size_t e = 0; e < bins; ++e)
    {
      sum += this->Weights[e] * value[e];
    }
    return sum;
  }
  double Transmission(const double* areaDensity) const
  {
    std::vector<double> scratch(this->ScratchSize());
    return this->Transmission(areaDensity, scratch.data());
  }

  /// out[i] = exp(-a[i]) for 0 <= a[i] <= 1e12, to about 2 ulp (0 below
  /// 2^-1022), with `work` of count values. No branch and no floating-point
  /// comparison, so that the compiler vectorises each loop (glibc's exp is a
  /// call per value). Cody and Waite's range reduction -a = n ln 2 + r,
  /// |r| <= ln 2 / 2, exp(r) by its Taylor polynomial of degree 13
  /// (truncation below 1e-17), 2^n from exponent bits.
  static void ExpOfNegative(const double* a, double* out, double* work, std::size_t count)
  {
    // Adding 1.5 x 2^52 rounds to an integer and leaves 2^51 + n in the
    // low bits.
    constexpr double shifter = 6755399441055744.0;
    for (std::size_t i = 0; i < count; ++i)
    {
      const double y = -a[i];
      const double shifted = y * 1.4426950408889634 + shifter; // y / ln 2
      const double n = shifted - shifter;
      const double r = (y - n * 6.93147180369123816490e-01) - n * 1.90821492927058770002e-10;
      double p = 1.0 / 6227020800.0; // 1 / 13!
      p = p * r + 1.0 / 479001600.0;
      p = p * r + 1.0 / 39916800.0;
      p = p * r + 1.0 / 3628800.0;
      p = p * r + 1.0 / 362880.0;
      p = p * r + 1.0 / 40320.0;
      p = p * r + 1.0 / 5040.0;
      p = p * r + 1.0 / 720.0;
      p = p * r + 1.0 / 120.0;
      p = p * r + 1.0 / 24.0;
      p = p * r + 1.0 / 6.0;
      p = p * r + 0.5;
      p = p * r + 1.0;
      p = p * r + 1.0;
      out[i] = p;
      work[i] = shifted;
    }
    std::uint64_t bits[64];
    for (std::size_t begin = 0; begin < count; begin += 64)
    {
      const std::size_t block = std::min<std::size_t>(64, count - begin);
      std::memcpy(bits, work + begin, block * sizeof(double));
      for (std::size_t i = 0; i < block; ++i)
      {
        // t = n + 1023, the biased exponent of 2^n: (t << 52) is 2^n's bits;
        // a negative t (2^n below the normal range) gives 0 through the mask.
        const std::uint64_t t =
          (bits[i] & ((std::uint64_t(1) << 52) - 1)) - (std::uint64_t(1) << 51) + 1023;
        const std::uint64_t negative = 0 - (t >> 63);
        bits[i] = (t << 52) & ~negative;
      }
      std::memcpy(work + begin, bits, block * sizeof(double));
      for (std::size_t i = 0; i < block; ++i)
      {
        out[begin + i] *= work[begin + i];
      }
    }
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
  /// (scale turns the channels' units into g/cm^2), in parallel. With
  /// `channelErrors` (each channel's relative error) and `errors`, errors[p]
  /// for every ErrorStride-th pixel (0 for the others) is the first-order
  /// error of out[p]: sum_m |L_m d(-ln T)/dL_m| x
  /// channelErrors[m], the channels' contributions added (a bound for any
  /// correlation between them: they come from the same samples).
  template <typename Executor>
  void EffectiveImage(const Executor& executor, std::int64_t pixels, const double* const* channels,
    double scale, double* out, const double* channelErrors = nullptr,
    double* errors = nullptr) const
  {
    executor.For(0, pixels, 1024,
      [&](std::int64_t begin, std::int64_t end)
      { this->EffectiveRange(begin, end, channels, scale, out, channelErrors, errors); });
  }

  /// EffectiveImage's pixels [begin, end) (compiled for AVX2 too where the
  /// compiler can: the same operations, so the same bits, twice as wide).
  void EffectiveRange(std::int64_t begin, std::int64_t end, const double* const* channels,
    double scale, double* out, const double* channelErrors, double* errors) const;

  /// sum_m |L_m d(-ln T)/dL_m| relativeErrors[m], with d(-ln T)/dL_m =
  /// sum_E w(E) (mu/rho)_m(E) exp(-a(E)) / T from the exponentials that
  /// Transmission left in scratch (its second Bins() values).
  double PropagatedError(
    const double* areaDensity, const double* scratch, double t, const double* relativeErrors) const
  {
    if (!(t > 0.0))
    {
      return 0.0;
    }
    const std::size_t bins = this->Bins();
    const double* value = scratch + bins;
    double error = 0.0;
    for (std::size_t m = 0; m < this->MaterialCount; ++m)
    {
      const double l = areaDensity[m] > 0.0 ? std::min(areaDensity[m], 1e6) : 0.0;
      const double* mu = this->Attenuation.data() + m * bins;
      double slope = 0.0;
      for (std::size_t e = 0; e < bins; ++e)
      {
        slope += this->Weights[e] * mu[e] * value[e];
      }
      error += l * slope / t * relativeErrors[m];
    }
    return error;
  }

private:
  std::vector<double> Weights;
  std::vector<double> Attenuation; // [m * Bins + e]
  std::size_t MaterialCount = 0;
};

} // namespace mcx

#endif
