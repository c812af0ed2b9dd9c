// The default decomposition follows the scheme of Schneider, Bortfeld and
// Schlegel, "Correlation between CT numbers and tissue parameters needed for
// Monte Carlo simulations of clinical dose distributions", Phys. Med. Biol. 45
// (2000) 459: CT numbers between two reference tissues are mixtures of them by
// mass, linear in HU. The reference tissues are xraylib's NIST compounds, at
// the densities of xraylib's table, placed at the HU this model assumes a
// scanner gives them: air -1000, adipose tissue -100, soft tissue 40,
// cortical bone 1400 (our choice, not checked against the paper's tables).
// Above 1400 HU the density keeps the soft-tissue-to-bone slope up to 3071 HU
// (the 12-bit scale's top).
#include "mcxMaterialDecomposition.h"

#include "mcxMaterialAttenuation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mcx
{

double HUCurve::At(double hu) const
{
  if (this->HU.empty())
  {
    return 0.0;
  }
  if (!(hu > this->HU.front())) // NaN too
  {
    return this->Value.front();
  }
  if (hu >= this->HU.back())
  {
    return this->Value.back();
  }
  const auto upper = std::upper_bound(this->HU.begin(), this->HU.end(), hu);
  const std::size_t i = static_cast<std::size_t>(upper - this->HU.begin());
  const double t = (hu - this->HU[i - 1]) / (this->HU[i] - this->HU[i - 1]);
  return this->Value[i - 1] + t * (this->Value[i] - this->Value[i - 1]);
}

std::vector<std::string> MaterialSet::Names() const
{
  std::vector<std::string> names;
  for (const MaterialCurve& m : this->Materials)
  {
    names.push_back(m.Name);
  }
  return names;
}

void MaterialSet::FixedFractionsAt(double hu, double* fractions) const
{
  constexpr double scale = 4294967296.0; // 2^32
  // The rest goes to the last material present at this HU, so that one
  // absent gets exactly 0 (a split deposit then leaves its channel alone).
  std::size_t last = this->Size() - 1;
  while (last > 0 && !(this->Materials[last].Fraction.At(hu) > 0.0))
  {
    --last;
  }
  std::uint64_t used = 0;
  for (std::size_t m = 0; m < this->Size(); ++m)
  {
    if (m == last)
    {
      continue;
    }
    const double f = std::min(std::max(this->Materials[m].Fraction.At(hu), 0.0), 1.0);
    std::uint64_t q = static_cast<std::uint64_t>(std::floor(f * scale));
    q = std::min(q, (std::uint64_t(1) << 32) - used);
    used += q;
    fractions[m] = static_cast<double>(q) / scale;
  }
  fractions[last] = static_cast<double>((std::uint64_t(1) << 32) - used) / scale;
}

MaterialSet DefaultMaterials(double iodineHU, double titaniumHU)
{
  const std::vector<std::string> names = { materials::Air, materials::Adipose,
    materials::SoftTissue, materials::CorticalBone };
  const std::vector<double> hu = { -1000.0, -100.0, 40.0, 1400.0 };
  constexpr double top = 3071.0;
  if (iodineHU > 0.0 && !(iodineHU >= hu[2] && iodineHU < 900.0))
  {
    throw std::invalid_argument("--materials: iodine's threshold must be 40-900 HU");
  }
  if (titaniumHU > 0.0 && !(titaniumHU > hu[3] && titaniumHU <= top))
  {
    throw std::invalid_argument("--materials: titanium's threshold must be 1400-3071 HU");
  }
  HUCurve base{ hu, {} };
  for (const std::string& name : names)
  {
    base.Value.push_back(MaterialDensity(name));
  }
  const double slope = (base.Value[3] - base.Value[2]) / (hu[3] - hu[2]);
  base.HU.push_back(top);
  base.Value.push_back(base.Value[3] + slope * (top - hu[3]));
  // Iodine: soft tissue carrying iodine from iodineHU on, 1 mg/ml more per
  // 25 HU (an assumption of this model, of the order contrast CT shows) at 1000 HU, the
  // mass fraction linear in HU from 0 at the threshold, fading out towards
  // the bone's HU; its mass comes out of the soft tissue's.
  const double iodineEnd = 1000.0;
  const HUCurve iodine{ { iodineHU, iodineEnd, hu[3] },
    { 0.0, (iodineEnd - iodineHU) / 25.0 * 1e-3 / base.At(iodineEnd), 0.0 } };
  // Titanium: an implant saturates the scale; all titanium 100 HU above the
  // threshold, at titanium's density.
  const double titaniumFull = titaniumHU + 100.0;
  const double titaniumDensity = titaniumHU > 0.0 ? MaterialDensity("Ti") : 0.0;
  std::vector<double> anchors = base.HU;
  if (iodineHU > 0.0)
  {
    anchors.insert(anchors.end(), iodine.HU.begin(), iodine.HU.end());
  }
  if (titaniumHU > 0.0)
  {
    anchors.push_back(titaniumHU);
    anchors.push_back(titaniumFull);
  }
  std::sort(anchors.begin(), anchors.end());
  anchors.erase(std::unique(anchors.begin(), anchors.end()), anchors.end());
  MaterialSet set;
  std::vector<std::string> all = names;
  if (iodineHU > 0.0)
  {
    all.push_back("I");
  }
  if (titaniumHU > 0.0)
  {
    all.push_back("Ti");
  }
  for (const std::string& name : all)
  {
    set.Materials.push_back({ name, HUCurve{ anchors, {} } });
  }
  set.Density.HU = anchors;
  for (double a : anchors)
  {
    // Tissues: each 1 at its HU, mixed linearly with its neighbours.
    std::vector<double> f(all.size(), 0.0);
    for (std::size_t m = 0; m < names.size(); ++m)
    {
      HUCurve tent{ hu, std::vector<double>(hu.size(), 0.0) };
      tent.Value[m] = 1.0;
      f[m] = tent.At(a);
    }
    double density = base.At(a);
    if (iodineHU > 0.0)
    {
      f[names.size()] = iodine.At(a);
      f[2] -= f[names.size()];
    }
    if (titaniumHU > 0.0 && a > titaniumHU)
    {
      const double t = std::min((a - titaniumHU) / (titaniumFull - titaniumHU), 1.0);
      for (double& value : f)
      {
        value *= 1.0 - t;
      }
      f.back() = t;
      density = (1.0 - t) * base.At(titaniumHU) + t * titaniumDensity;
    }
    set.Density.Value.push_back(density);
    for (std::size_t m = 0; m < all.size(); ++m)
    {
      set.Materials[m].Fraction.Value.push_back(f[m]);
    }
  }
  CheckMaterialSet(set, "the default materials");
  return set;
}

void CheckMaterialSet(const MaterialSet& set, const std::string& where)
{
  const auto increasing = [&](const HUCurve& curve, const std::string& what)
  {
    if (curve.HU.empty() || curve.HU.size() != curve.Value.size())
    {
      throw std::invalid_argument(where + ": " + what + " needs HU and value pairs");
    }
    for (std::size_t i = 0; i < curve.HU.size(); ++i)
    {
      if (!std::isfinite(curve.HU[i]) || !std::isfinite(curve.Value[i]) ||
        (i > 0 && !(curve.HU[i] > curve.HU[i - 1])))
      {
        throw std::invalid_argument(where + ": " + what + "'s HU must be finite and increase");
      }
    }
  };
  increasing(set.Density, "density");
  for (double d : set.Density.Value)
  {
    if (!(d >= 0.0))
    {
      throw std::invalid_argument(where + ": densities must be >= 0 g/cm^3");
    }
  }
  if (set.Materials.empty())
  {
    throw std::invalid_argument(where + ": no material");
  }
  std::vector<double> anchors;
  for (const MaterialCurve& m : set.Materials)
  {
    CheckMaterialName(m.Name);
    increasing(m.Fraction, "material '" + m.Name + "'");
    for (double f : m.Fraction.Value)
    {
      if (!(f >= 0.0 && f <= 1.0))
      {
        throw std::invalid_argument(
          where + ": material '" + m.Name + "' has a fraction outside [0, 1]");
      }
    }
    anchors.insert(anchors.end(), m.Fraction.HU.begin(), m.Fraction.HU.end());
  }
  for (double hu : anchors)
  {
    double sum = 0.0;
    for (const MaterialCurve& m : set.Materials)
    {
      sum += m.Fraction.At(hu);
    }
    if (std::abs(sum - 1.0) > 1e-6)
    {
      std::ostringstream message;
      message << where << ": the fractions sum to " << sum << " at " << hu << " HU, not 1";
      throw std::invalid_argument(message.str());
    }
  }
}

MaterialSet ReadMaterialsFile(const std::string& path)
{
  std::ifstream file(path);
  if (!file)
  {
    throw std::invalid_argument("materials file '" + path + "' cannot be read");
  }
  MaterialSet set;
  std::string line;
  int number = 0;
  bool density = false;
  while (std::getline(file, line))
  {
    ++number;
    line = line.substr(0, line.find('#'));
    const std::string where = "materials file '" + path + "' line " + std::to_string(number);
    std::istringstream fields(line);
    std::string keyword;
    if (!(fields >> keyword))
    {
      continue;
    }
    HUCurve curve;
    std::string name;
    if (keyword == "material")
    {
      std::string rest;
      std::getline(fields, rest);
      const std::size_t bar = rest.find('|');
      if (bar == std::string::npos)
      {
        throw std::invalid_argument(where + ": expected 'material <name> | HU fraction ...'");
      }
      name = rest.substr(0, bar);
      name.erase(0, name.find_first_not_of(" \t"));
      name.erase(name.find_last_not_of(" \t\r") + 1);
      fields.clear();
      fields.str(rest.substr(bar + 1));
    }
    else if (keyword != "density")
    {
      throw std::invalid_argument(
        where + ": '" + keyword + "' is neither 'density' nor 'material'");
    }
    double hu = 0.0, value = 0.0;
    while (fields >> hu)
    {
      if (!(fields >> value))
      {
        throw std::invalid_argument(where + ": HU without a value");
      }
      curve.HU.push_back(hu);
      curve.Value.push_back(value);
    }
    if (!fields.eof())
    {
      throw std::invalid_argument(where + ": expected numbers in HU and value pairs");
    }
    if (keyword == "density")
    {
      if (density)
      {
        throw std::invalid_argument(where + ": a second density line");
      }
      density = true;
      set.Density = curve;
    }
    else
    {
      set.Materials.push_back({ name, curve });
    }
  }
  if (!density)
  {
    throw std::invalid_argument("materials file '" + path + "' has no density line");
  }
  CheckMaterialSet(set, "materials file '" + path + "'");
  return set;
}

MaterialSet MaterialsFromText(const std::string& text)
{
  if (text.rfind("default", 0) != 0)
  {
    return ReadMaterialsFile(text);
  }
  double iodine = 0.0, titanium = 0.0;
  std::stringstream items(text.substr(7));
  std::string item;
  while (std::getline(items, item, ','))
  {
    if (item.empty())
    {
      continue;
    }
    const std::size_t equals = item.find('=');
    const std::string key = item.substr(0, equals);
    double value = 0.0;
    std::size_t used = 0;
    try
    {
      value = std::stod(item.substr(equals + 1), &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (equals == std::string::npos || used != item.size() - equals - 1 ||
      !(value > 0.0 && value < 1e5) || (key != "iodine" && key != "titanium"))
    {
      throw std::invalid_argument(
        "--materials: '" + item + "' is not iodine=<HU> or titanium=<HU> (a threshold above 0 HU)");
    }
    (key == "iodine" ? iodine : titanium) = value;
  }
  return DefaultMaterials(iodine, titanium);
}

} // namespace mcx
