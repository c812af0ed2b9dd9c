// Half-value layers as users measure them: the air kerma behind growing
// aluminium, from xraylib's energy-absorption coefficients of air.
#ifndef mcxHalfValueLayer_h
#define mcxHalfValueLayer_h

#include "mcxTubeSpectrum.h"

namespace mcx
{

/// Air kerma (relative) of a spectrum: sum of photons x E x (mu_en/rho)_air(E).
double AirKerma(const Spectrum& spectrum);

/// First half-value layer in mm of `material` (default aluminium): the
/// thickness that halves the air kerma, to 1e-6 mm.
double HalfValueLayer(const Spectrum& spectrum, const std::string& material = "Al");

/// The total filtration in mm of the settings' first filter's material that
/// gives the first HVL `hvl` mm Al at the settings' voltage (the settings'
/// filters are replaced by that one). Throws std::invalid_argument when no
/// thickness in [0, 50] mm reaches it.
double FitFiltration(TubeSettings settings, double hvl, const std::string& material = "Al");

/// IEC 61267:2005's RQR 2-10 radiation qualities: tube voltage and first HVL.
struct RadiationQuality
{
  const char* Name;
  double Kilovolts;
  double HalfValueLayer; // mm Al
};
constexpr RadiationQuality RQRQualities[] = { { "RQR 2", 40, 1.4 }, { "RQR 3", 50, 1.8 },
  { "RQR 4", 60, 2.2 }, { "RQR 5", 70, 2.6 }, { "RQR 6", 80, 3.0 }, { "RQR 7", 90, 3.5 },
  { "RQR 8", 100, 4.0 }, { "RQR 9", 120, 5.0 }, { "RQR 10", 150, 6.6 } };

} // namespace mcx

#endif
