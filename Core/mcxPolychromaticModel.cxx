#include "mcxPolychromaticModel.h"

#include "mcxMaterialAttenuation.h"

#include <sstream>
#include <stdexcept>

// AVX2 where the CPU has it, the baseline elsewhere, chosen when the program
// loads (GCC's function multi-versioning). No FMA: both versions do the same
// operations in the same order, so they give the same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define MCX_ALSO_AVX2 __attribute__((target_clones("avx2", "default")))
#else
#define MCX_ALSO_AVX2
#endif

namespace mcx
{

MCX_ALSO_AVX2 void PolychromaticModel::EffectiveRange(std::int64_t begin, std::int64_t end,
  const double* const* channels, double scale, double* out, const double* channelErrors,
  double* errors) const
{
  std::vector<double> l(this->MaterialCount), scratch(this->ScratchSize());
  for (std::int64_t p = begin; p < end; ++p)
  {
    for (std::size_t m = 0; m < this->MaterialCount; ++m)
    {
      l[m] = channels[m][p] * scale;
    }
    const double t = this->Transmission(l.data(), scratch.data());
    out[p] = t > 0.0 ? -std::log(t) : HUGE_VAL;
    if (errors)
    {
      errors[p] = p % ErrorStride == 0
        ? this->PropagatedError(l.data(), scratch.data(), t, channelErrors)
        : 0.0;
    }
  }
}

std::vector<double> Detector::Response(const Spectrum& spectrum) const
{
  std::vector<double> response(spectrum.Size(), 1.0);
  double density = 0.0;
  if (!this->ScreenMaterial.empty())
  {
    density = MaterialDensity(this->ScreenMaterial, this->ScreenDensity);
    if (this->ScreenDensity > 0.0)
    {
      density = this->ScreenDensity;
    }
  }
  for (std::size_t i = 0; i < spectrum.Size(); ++i)
  {
    const double energy = spectrum.Energies[i];
    double absorbed = 1.0;
    if (!this->ScreenMaterial.empty())
    {
      absorbed = 1.0 -
        std::exp(
          -MassAttenuation(this->ScreenMaterial, energy) * density * this->ScreenThickness * 0.1);
    }
    response[i] = absorbed * (this->PhotonCounting ? 1.0 : energy);
  }
  return response;
}

Detector ParseDetector(const std::string& text)
{
  Detector detector;
  const std::size_t comma = text.find(',');
  const std::string kind = text.substr(0, comma);
  if (kind == "counting")
  {
    detector.PhotonCounting = true;
  }
  else if (kind != "integrating")
  {
    throw std::invalid_argument(
      "--detector: '" + kind + "' is neither 'integrating' nor 'counting'");
  }
  if (comma == std::string::npos)
  {
    return detector;
  }
  std::stringstream parts(text.substr(comma + 1));
  std::string material, thickness, density;
  std::getline(parts, material, ':');
  std::getline(parts, thickness, ':');
  std::getline(parts, density, ':');
  const auto number = [&](const std::string& field, const char* what)
  {
    std::size_t used = 0;
    double value = 0.0;
    try
    {
      value = std::stod(field, &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (used != field.size() || !(value > 0.0 && value <= 100.0))
    {
      throw std::invalid_argument("--detector: the screen's " + std::string(what) + " '" + field +
        "' is not a number in (0, 100]");
    }
    return value;
  };
  if (material.empty() || thickness.empty())
  {
    throw std::invalid_argument(
      "--detector: a screen is <material>:<mm>[:<g/cm3>], e.g. CsI:0.6:4.51");
  }
  CheckMaterialName(material);
  detector.ScreenMaterial = material;
  detector.ScreenThickness = number(thickness, "thickness in mm");
  if (!density.empty())
  {
    detector.ScreenDensity = number(density, "density in g/cm^3");
  }
  (void)MaterialDensity(material, detector.ScreenDensity); // a formula needs its density
  return detector;
}

PolychromaticModel::PolychromaticModel(
  const Spectrum& spectrum, const Detector& detector, const std::vector<std::string>& materials)
{
  if (spectrum.Size() == 0 || !(spectrum.TotalPhotons() > 0.0))
  {
    throw std::invalid_argument("the spectrum has no photons");
  }
  const std::vector<double> response = detector.Response(spectrum);
  double sum = 0.0;
  for (std::size_t e = 0; e < spectrum.Size(); ++e)
  {
    this->Weights.push_back(spectrum.Photons[e] * response[e]);
    sum += this->Weights.back();
  }
  if (!(sum > 0.0))
  {
    throw std::invalid_argument("the detector absorbs none of the spectrum");
  }
  for (double& w : this->Weights)
  {
    w /= sum;
  }
  this->MaterialCount = materials.size();
  for (const std::string& material : materials)
  {
    for (double energy : spectrum.Energies)
    {
      this->Attenuation.push_back(mcx::MassAttenuation(material, energy));
    }
  }
}

} // namespace mcx
