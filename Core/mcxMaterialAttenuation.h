// Materials' interaction coefficients from xraylib, the one source of every
// attenuation value of the polychromatic physics (never hand-copied tables).
#ifndef mcxMaterialAttenuation_h
#define mcxMaterialAttenuation_h

#include <string>

namespace mcx
{

/// A material as xraylib names it: a NIST compound of its table ("Tissue, Soft
/// (ICRP)", "Air, Dry (near sea level)", ...), an element symbol ("Al", "I") or
/// a chemical formula ("CsI", "Gd2O2S"). Throws std::invalid_argument with a
/// one-line message for a name xraylib does not know.
void CheckMaterialName(const std::string& material);

/// Total mass attenuation coefficient (coherent scattering included) in cm^2/g
/// at `energyKeV`: xraylib's CS_Total of each element by mass fraction (what
/// CS_Total_CP computes; see the .cxx for why it is not called).
double MassAttenuation(const std::string& material, double energyKeV);

/// Mass energy-absorption coefficient in cm^2/g: xraylib's CS_Energy of each
/// element by mass fraction (CS_Energy_CP's rule).
double MassEnergyAbsorption(const std::string& material, double energyKeV);

/// Density in g/cm^3: the NIST compound's, else the element's (xraylib's
/// ElementDensity), else `fallback` for a formula (throws if fallback <= 0).
double MaterialDensity(const std::string& material, double fallback = 0.0);

/// The NIST names the polychromatic physics uses by default.
namespace materials
{
constexpr const char* Air = "Air, Dry (near sea level)";
constexpr const char* Adipose = "Adipose Tissue (ICRP)";
constexpr const char* SoftTissue = "Tissue, Soft (ICRP)";
constexpr const char* CorticalBone = "Bone, Cortical (ICRP)";
constexpr const char* Water = "Water, Liquid";
}

} // namespace mcx

#endif
