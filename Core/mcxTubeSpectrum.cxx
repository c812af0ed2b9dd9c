// The tungsten anode model: Kramers' thin-target cross-section (photons per
// unit photon energy and path proportional to 1 / (E T) for an electron of
// kinetic energy T > E) integrated along the electron's slowing-down by the
// Thomson-Whiddington law (T0^2 - T^2 = C rho x), which without absorption
// gives Kramers' thick-target law N(E) ~ (T0 - E) / E, and with absorption
// weights each depth by the anode's self-absorption exp(-(mu/rho)_W(E) rho x /
// sin(anode angle)): the scheme of Birch and Marshall, Phys. Med. Biol. 24
// (1979) 505. The K lines come from the bremsstrahlung the anode absorbs above
// tungsten's K edge (photoexcitation: (1 - 1/J_K) of it ionises the K shell,
// omega_K of that fluoresces, split by the lines' radiative rates); electron-
// impact ionisation is not modelled, so the lines are weaker than measured.
// Every coefficient, edge, line energy, rate and yield is xraylib's.
#include "mcxTubeSpectrum.h"

#include "mcxMaterialAttenuation.h"

#include <xraylib.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mcx
{
namespace
{

constexpr int Tungsten = 74;
// The Thomson-Whiddington constant C (keV^2 cm^2/g) comes from the settings'
// mean production depth at 100 kVp, 2/3 of T0^2 / C. Electrons diffuse in
// tungsten, so photons are made far shallower than on a straight path to the
// CSDA range (taken as 0.035 g/cm^2 at 100 keV, NIST ESTAR's value as we
// recall it, not checked here; mean depth 0.023), which hardens the spectra
// far too much (Documentation/polychromatic.md shows both); the default, 1 um
// of tungsten, is a model parameter chosen here, not a measurement.
constexpr int DepthSteps = 64;
// xraylib's tables start at 1 keV; no such photon passes a tube's window.
constexpr double LowestEnergy = 1.0;

double Xrl(double (*function)(int, int, xrl_error**), int z, int which)
{
  xrl_error* error = nullptr;
  const double value = function(z, which, &error);
  xrl_clear_error(&error);
  return error ? 0.0 : value;
}

double TungstenAttenuation(double energy)
{
  xrl_error* error = nullptr;
  const double value = CS_Total(Tungsten, energy, &error);
  xrl_clear_error(&error);
  return value;
}

// Integral over T in [from, t0] of exp(-a (t0^2 - T^2)) dT by the midpoint
// rule on DepthSteps steps: smooth where the anode absorbs little (the error
// far below 1e-4 from about 5 keV); near 1 keV, where tungsten's mu/rho is in
// the thousands of cm^2/g, the integrand falls steeply and the error reaches
// the percent level, for photons that any filtration removes.
double DepthIntegral(double a, double from, double t0)
{
  const double step = (t0 - from) / DepthSteps;
  double sum = 0.0;
  for (int i = 0; i < DepthSteps; ++i)
  {
    const double t = from + (i + 0.5) * step;
    sum += std::exp(-a * (t0 * t0 - t * t));
  }
  return sum * step;
}

double Number(const std::string& text, const std::string& what)
{
  std::size_t used = 0;
  double value = 0.0;
  try
  {
    value = std::stod(text, &used);
  }
  catch (const std::exception&)
  {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(value))
  {
    throw std::invalid_argument("--spectrum: '" + text + "' is not a number (" + what + ")");
  }
  return value;
}

bool EndsWith(const std::string& text, const std::string& tail)
{
  return text.size() > tail.size() &&
    text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

}

double Spectrum::TotalPhotons() const
{
  double sum = 0.0;
  for (double n : this->Photons)
  {
    sum += n;
  }
  return sum;
}

double Spectrum::MeanEnergy() const
{
  double sum = 0.0;
  for (std::size_t i = 0; i < this->Size(); ++i)
  {
    sum += this->Photons[i] * this->Energies[i];
  }
  return sum / this->TotalPhotons();
}

Spectrum TungstenSpectrum(const TubeSettings& settings)
{
  const double t0 = settings.Kilovolts;
  if (!(t0 >= MinimumKilovolts && t0 <= MaximumKilovolts))
  {
    std::ostringstream message;
    message << "tube voltage " << t0 << " kVp is outside " << MinimumKilovolts << "-"
            << MaximumKilovolts << " kVp";
    throw std::invalid_argument(message.str());
  }
  if (!(settings.BinWidth >= 0.1 && settings.BinWidth <= 5.0))
  {
    throw std::invalid_argument("energy bin width must be 0.1-5 keV");
  }
  if (!(settings.AnodeAngle >= 5.0 && settings.AnodeAngle <= 45.0))
  {
    throw std::invalid_argument("anode angle must be 5-45 degrees");
  }
  const double sine = std::sin(settings.AnodeAngle * M_PI / 180.0);
  if (!(settings.MeanProductionDepth > 0.0 && settings.MeanProductionDepth < 1.0))
  {
    throw std::invalid_argument("the mean production depth must be in (0, 1) g/cm^2");
  }
  const double c = 1e4 * 2.0 / 3.0 / settings.MeanProductionDepth;
  Spectrum spectrum;
  const int bins = static_cast<int>(std::floor(t0 / settings.BinWidth + 1e-9));
  int firstBin = 0;
  const double edge = Xrl(EdgeEnergy, Tungsten, K_SHELL);
  double absorbedK = 0.0; // photons per sr-equivalent the anode absorbs above its K edge
  for (int b = 0; b < bins; ++b)
  {
    const double energy = (b + 0.5) * settings.BinWidth;
    if (energy < LowestEnergy)
    {
      firstBin = b + 1;
      continue;
    }
    const double a = TungstenAttenuation(energy) / (c * sine);
    // Per steradian, per keV: (2 / (E C)) x integral of the self-absorption.
    const double emitted = 2.0 / (energy * c) * DepthIntegral(a, energy, t0);
    const double generated = 2.0 * (t0 - energy) / (energy * c);
    spectrum.Energies.push_back(energy);
    spectrum.Photons.push_back(emitted * settings.BinWidth);
    if (energy > edge)
    {
      // Half the isotropic emission goes into the anode, the rest leaves
      // attenuated as along the central ray: absorbed = 4 pi (G - N / 2).
      absorbedK += 4.0 * M_PI * (generated - 0.5 * emitted) * settings.BinWidth;
    }
  }
  if (t0 > edge && absorbedK > 0.0)
  {
    const double jump = Xrl(JumpFactor, Tungsten, K_SHELL);
    const double yield = Xrl(FluorYield, Tungsten, K_SHELL);
    const double ionised = absorbedK * (1.0 - 1.0 / jump) * yield / (4.0 * M_PI);
    for (int line : { KL2_LINE, KL3_LINE, KM2_LINE, KM3_LINE, KN2_LINE, KN3_LINE })
    {
      const double energy = Xrl(LineEnergy, Tungsten, line);
      const double rate = Xrl(RadRate, Tungsten, line);
      const int bin = static_cast<int>(energy / settings.BinWidth);
      if (energy <= 0.0 || rate <= 0.0 || bin >= bins || bin < firstBin)
      {
        continue;
      }
      // The lines leave from where the absorbed photons were made: the
      // bremsstrahlung depths above the edge, attenuated at the line's energy.
      const double a = TungstenAttenuation(energy) / (c * sine);
      const double escape = DepthIntegral(a, edge, t0) / (t0 - edge);
      spectrum.Photons[bin - firstBin] += ionised * rate * escape;
    }
  }
  for (const BeamFilter& filter : settings.Filters)
  {
    FilterSpectrum(spectrum, filter);
  }
  return spectrum;
}

void FilterSpectrum(Spectrum& spectrum, const BeamFilter& filter)
{
  if (!(filter.Thickness >= 0.0 && filter.Thickness <= 1000.0))
  {
    throw std::invalid_argument("filter thickness must be 0-1000 mm");
  }
  const double density = filter.Density > 0 ? filter.Density : MaterialDensity(filter.Material);
  for (std::size_t i = 0; i < spectrum.Size(); ++i)
  {
    const double mu = MassAttenuation(filter.Material, spectrum.Energies[i]) * density;
    spectrum.Photons[i] *= std::exp(-mu * filter.Thickness * 0.1);
  }
}

TubeSettings ParseTubeSettings(const std::string& text)
{
  TubeSettings settings;
  bool voltage = false;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ','))
  {
    if (EndsWith(item, "kVp") || EndsWith(item, "kV"))
    {
      settings.Kilovolts = Number(item.substr(0, item.find("kV")), "tube voltage in kVp");
      voltage = true;
    }
    else if (EndsWith(item, "deg"))
    {
      settings.AnodeAngle = Number(item.substr(0, item.size() - 3), "anode angle in degrees");
    }
    else if (EndsWith(item, "keV"))
    {
      settings.BinWidth = Number(item.substr(0, item.size() - 3), "bin width in keV");
    }
    else if (const std::size_t mm = item.find("mm"); mm != std::string::npos && mm > 0)
    {
      BeamFilter filter;
      filter.Thickness = Number(item.substr(0, mm), "filter thickness in mm");
      filter.Material = item.substr(mm + 2);
      if (filter.Material.empty())
      {
        throw std::invalid_argument("--spectrum: filter '" + item + "' names no material");
      }
      CheckMaterialName(filter.Material);
      settings.Filters.push_back(filter);
    }
    else
    {
      throw std::invalid_argument(
        "--spectrum: '" + item + "' is none of <kV>kVp, <mm>mm<material>, <angle>deg, <width>keV");
    }
  }
  if (!voltage)
  {
    throw std::invalid_argument("--spectrum: '" + text + "' gives no tube voltage (e.g. 70kVp)");
  }
  return settings;
}

Spectrum ReadSpectrumFile(const std::string& path)
{
  std::ifstream file(path);
  if (!file)
  {
    throw std::invalid_argument("spectrum file '" + path + "' cannot be read");
  }
  Spectrum spectrum;
  std::string line;
  int number = 0;
  while (std::getline(file, line))
  {
    ++number;
    line = line.substr(0, line.find('#'));
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    double energy = 0.0, photons = 0.0;
    std::string rest;
    if (!(fields >> energy))
    {
      if (line.find_first_not_of(" \t\r") == std::string::npos)
      {
        continue;
      }
      energy = -1.0;
    }
    const std::string where = "spectrum file '" + path + "' line " + std::to_string(number);
    if (!(fields >> photons) || (fields >> rest))
    {
      throw std::invalid_argument(where + ": expected two numbers, energy in keV and photons");
    }
    if (!(energy > 1.0 && energy < 1000.0) ||
      (!spectrum.Energies.empty() && !(energy > spectrum.Energies.back())))
    {
      throw std::invalid_argument(where + ": energies must increase within 1-1000 keV");
    }
    if (!(photons >= 0.0) || !std::isfinite(photons))
    {
      throw std::invalid_argument(where + ": photons must be finite and >= 0");
    }
    spectrum.Energies.push_back(energy);
    spectrum.Photons.push_back(photons);
  }
  if (!(spectrum.TotalPhotons() > 0.0))
  {
    throw std::invalid_argument("spectrum file '" + path + "' has no photons");
  }
  return spectrum;
}

Spectrum SpectrumFromText(const std::string& text)
{
  const std::size_t kv = text.find("kV");
  if (kv != std::string::npos && kv > 0 && text.find(',') != 0 &&
    std::isdigit(static_cast<unsigned char>(text[0])) && text.find('/') == std::string::npos)
  {
    return TungstenSpectrum(ParseTubeSettings(text));
  }
  return ReadSpectrumFile(text);
}

} // namespace mcx
