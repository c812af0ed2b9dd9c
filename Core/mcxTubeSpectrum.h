// X-ray tube spectra: a tungsten anode's photons per energy bin from a
// semi-empirical model (see TungstenSpectrum), filtration, and users' spectra.
#ifndef mcxTubeSpectrum_h
#define mcxTubeSpectrum_h

#include <string>
#include <vector>

namespace mcx
{

/// Photons per energy bin (relative: only ratios matter) at bin centres in keV.
struct Spectrum
{
  std::vector<double> Energies; // keV, increasing
  std::vector<double> Photons;  // photons in each bin, >= 0

  double TotalPhotons() const;
  double MeanEnergy() const; // keV, photon-weighted
  std::size_t Size() const { return this->Energies.size(); }
};

/// A filter in the beam: an xraylib material (element, NIST compound or
/// formula) of a thickness in mm, at its xraylib density unless Density > 0.
struct BeamFilter
{
  std::string Material = "Al";
  double Thickness = 0.0; // mm
  double Density = 0.0;   // g/cm^3; 0: xraylib's
};

struct TubeSettings
{
  double Kilovolts = 70.0;  // tube voltage, 40-150 kVp
  double AnodeAngle = 12.0; // degrees between anode face and central ray
  double BinWidth = 1.0;    // keV, 0.1-5
  /// Mean depth in the anode, g/cm^2, at which a 100 kVp tube makes its
  /// bremsstrahlung (it scales as kVp^2): 1 um of tungsten, a model parameter
  /// (see the .cxx); the straight path to the CSDA range would be 0.023.
  double MeanProductionDepth = 1e-4 * 19.3;
  std::vector<BeamFilter> Filters; // inherent and added filtration
};

/// The tube's limits, one spelling for parsers and messages.
constexpr double MinimumKilovolts = 40.0;
constexpr double MaximumKilovolts = 150.0;

/// Photons per bin on the central ray of a tungsten anode (see the .cxx for
/// the model and its sources), after the settings' filters.
Spectrum TungstenSpectrum(const TubeSettings& settings);

/// Multiplies each bin by the filter's transmission exp(-mu/rho rho t).
void FilterSpectrum(Spectrum& spectrum, const BeamFilter& filter);

/// "70kVp,2.5mmAl,0.1mmCu[,12deg][,0.5keV]": the tube voltage, filters as
/// thickness, "mm" and an element or formula, and optionally the anode angle
/// and the bin width. Throws std::invalid_argument with a one-line message.
TubeSettings ParseTubeSettings(const std::string& text);

/// A user's spectrum: lines "energy_keV photons" (spaces or a comma between,
/// '#' starts a comment), energies increasing in (1, 1000) keV, photons >= 0
/// and not all zero. Throws std::invalid_argument naming the line.
Spectrum ReadSpectrumFile(const std::string& path);

/// ParseTubeSettings's spectrum when `text` starts with a number followed by
/// "kVp", else the file `text`.
Spectrum SpectrumFromText(const std::string& text);

} // namespace mcx

#endif
