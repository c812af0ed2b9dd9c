#include "mcxHalfValueLayer.h"

#include "mcxMaterialAttenuation.h"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace mcx
{

double AirKerma(const Spectrum& spectrum)
{
  double kerma = 0.0;
  for (std::size_t i = 0; i < spectrum.Size(); ++i)
  {
    kerma += spectrum.Photons[i] * spectrum.Energies[i] *
      MassEnergyAbsorption(materials::Air, spectrum.Energies[i]);
  }
  return kerma;
}

double HalfValueLayer(const Spectrum& spectrum, const std::string& material)
{
  const double density = MaterialDensity(material);
  std::vector<double> kerma(spectrum.Size()), mu(spectrum.Size());
  double open = 0.0;
  for (std::size_t i = 0; i < spectrum.Size(); ++i)
  {
    kerma[i] = spectrum.Photons[i] * spectrum.Energies[i] *
      MassEnergyAbsorption(materials::Air, spectrum.Energies[i]);
    mu[i] = MassAttenuation(material, spectrum.Energies[i]) * density * 0.1; // 1/mm
    open += kerma[i];
  }
  const auto behind = [&](double thickness)
  {
    double sum = 0.0;
    for (std::size_t i = 0; i < spectrum.Size(); ++i)
    {
      sum += kerma[i] * std::exp(-mu[i] * thickness);
    }
    return sum;
  };
  // The kerma falls monotonically with thickness: bisect.
  double low = 0.0, high = 1.0;
  while (behind(high) > 0.5 * open)
  {
    high *= 2.0;
    if (high > 1e4)
    {
      throw std::invalid_argument("the spectrum's half-value layer is over 10 m of " + material);
    }
  }
  while (high - low > 1e-6)
  {
    const double middle = 0.5 * (low + high);
    (behind(middle) > 0.5 * open ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

double FitFiltration(TubeSettings settings, double hvl, const std::string& material)
{
  const auto hvlWith = [&](double thickness)
  {
    settings.Filters.assign(1, BeamFilter{ material, thickness, 0.0 });
    return HalfValueLayer(TungstenSpectrum(settings));
  };
  double low = 0.0, high = 50.0;
  if (hvlWith(low) > hvl || hvlWith(high) < hvl)
  {
    throw std::invalid_argument("no filtration of 0-50 mm " + material + " gives an HVL of " +
      std::to_string(hvl) + " mm Al at " + std::to_string(settings.Kilovolts) + " kVp");
  }
  while (high - low > 1e-5)
  {
    const double middle = 0.5 * (low + high);
    (hvlWith(middle) < hvl ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

} // namespace mcx
