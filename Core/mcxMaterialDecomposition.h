// Materials from CT numbers: a density curve and, per material, its mass
// fraction as a function of HU (piecewise linear, constant beyond the ends),
// the fractions summing to 1 at every HU. Material m's transfer function is
// density(HU) x fraction_m(HU) in g/cm^3.
#ifndef mcxMaterialDecomposition_h
#define mcxMaterialDecomposition_h

#include <string>
#include <vector>

namespace mcx
{

/// A piecewise linear function of HU through (HU[i], Value[i]), HU increasing,
/// constant beyond its first and last points.
struct HUCurve
{
  std::vector<double> HU;
  std::vector<double> Value;
  double At(double hu) const;
};

struct MaterialCurve
{
  std::string Name; // as xraylib names it (mcxMaterialAttenuation.h)
  HUCurve Fraction; // mass fraction in [0, 1]
};

struct MaterialSet
{
  HUCurve Density; // g/cm^3
  std::vector<MaterialCurve> Materials;

  std::size_t Size() const { return this->Materials.size(); }
  std::vector<std::string> Names() const;
  /// Each material's fraction at `hu`, as multiples of 2^-32 that sum to
  /// exactly 1 (the last material present takes what the others leave; one
  /// absent gets exactly 0), so that channel sums in fixed point add up to
  /// the total's exactly.
  void FixedFractionsAt(double hu, double* fractions) const;
};

/// The default decomposition (see the .cxx for its anchors and sources):
/// air, adipose tissue, soft tissue and cortical bone, mixed linearly between
/// the HU of neighbouring ones; optionally titanium from `titaniumHU` up
/// (0: none) and iodinated soft tissue from `iodineHU` up (0: none).
MaterialSet DefaultMaterials(double iodineHU = 0.0, double titaniumHU = 0.0);

/// "default", "default,iodine=<HU>,titanium=<HU>" or a materials file (format
/// in Documentation/polychromatic.md): lines "density HU g/cm3 HU g/cm3 ..."
/// and "material <xraylib name> | HU fraction HU fraction ...", '#' comments.
/// Throws std::invalid_argument with a one-line message.
MaterialSet MaterialsFromText(const std::string& text);
MaterialSet ReadMaterialsFile(const std::string& path);

/// Throws std::invalid_argument unless the set is usable: names xraylib knows,
/// HU increasing, densities >= 0, fractions in [0, 1] summing to 1 (within
/// 1e-6) at every anchor of every curve.
void CheckMaterialSet(const MaterialSet& set, const std::string& where);

} // namespace mcx

#endif
