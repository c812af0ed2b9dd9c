// A material's coefficients are xraylib's per-element cross-sections combined
// by mass fraction, the mixture rule of xraylib's CS_Total_CP and
// CS_Energy_CP. Those two are not called: in xraylib 4.0 (Debian 12) they
// try the formula parser first, and its failure path (every NIST name)
// leaks memory on each call. So NIST names are looked up in xraylib's NIST
// table, and the parser only sees text that is a formula of known element
// symbols, which it parses without leaking; each composition is kept.
#include "mcxMaterialAttenuation.h"

#include <xraylib.h>

#include <cctype>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace mcx
{
namespace
{

struct Composition
{
  std::vector<int> Elements;
  std::vector<double> MassFractions;
  double Density = 0.0; // g/cm^3: the NIST compound's or the single element's; 0 for a formula
};

// The element symbols xraylib knows.
const std::set<std::string>& ElementSymbols()
{
  static const std::set<std::string> symbols = []
  {
    std::set<std::string> known;
    for (int z = 1; z <= 107; ++z)
    {
      xrl_error* error = nullptr;
      char* symbol = AtomicNumberToSymbol(z, &error);
      xrl_clear_error(&error);
      if (symbol)
      {
        known.insert(symbol);
        xrlFree(symbol);
      }
    }
    return known;
  }();
  return symbols;
}

// Text made of element symbols, counts and brackets only, every symbol known
// ("CsI", "Gd2O2S", "Ca5(PO4)3OH"): what the parser takes without failing.
bool LooksLikeFormula(const std::string& text)
{
  if (text.empty())
  {
    return false;
  }
  int depth = 0;
  for (std::size_t i = 0; i < text.size();)
  {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (std::isupper(c))
    {
      std::size_t end = i + 1;
      while (end < text.size() && std::islower(static_cast<unsigned char>(text[end])))
      {
        ++end;
      }
      if (!ElementSymbols().count(text.substr(i, end - i)))
      {
        return false;
      }
      i = end;
    }
    else if (std::isdigit(c) ||
      (c == '.' && i > 0 && std::isdigit(static_cast<unsigned char>(text[i - 1]))))
    {
      ++i;
    }
    else if (c == '(' || c == ')')
    {
      depth += c == '(' ? 1 : -1;
      if (depth < 0 || (c == ')' && text[i - 1] == '('))
      {
        return false;
      }
      ++i;
    }
    else
    {
      return false;
    }
  }
  return depth == 0 && (std::isupper(static_cast<unsigned char>(text[0])) || text[0] == '(');
}

Composition Lookup(const std::string& material)
{
  Composition composition;
  xrl_error* error = nullptr;
  if (compoundDataNIST* nist = GetCompoundDataNISTByName(material.c_str(), &error))
  {
    composition.Elements.assign(nist->Elements, nist->Elements + nist->nElements);
    composition.MassFractions.assign(nist->massFractions, nist->massFractions + nist->nElements);
    composition.Density = nist->density;
    FreeCompoundDataNIST(nist);
    return composition;
  }
  xrl_clear_error(&error);
  compoundData* parsed =
    LooksLikeFormula(material) ? CompoundParser(material.c_str(), &error) : nullptr;
  xrl_clear_error(&error);
  if (!parsed)
  {
    throw std::invalid_argument("material '" + material +
      "' is neither an xraylib NIST compound name nor a chemical formula of known elements");
  }
  composition.Elements.assign(parsed->Elements, parsed->Elements + parsed->nElements);
  composition.MassFractions.assign(
    parsed->massFractions, parsed->massFractions + parsed->nElements);
  FreeCompoundData(parsed);
  if (composition.Elements.size() == 1)
  {
    composition.Density = ElementDensity(composition.Elements[0], &error);
    xrl_clear_error(&error);
  }
  return composition;
}

// Each name's composition, looked up once (from any thread).
const Composition& CompositionOf(const std::string& material)
{
  static std::mutex mutex;
  static std::map<std::string, Composition> known;
  std::lock_guard<std::mutex> lock(mutex);
  const auto found = known.find(material);
  if (found != known.end())
  {
    return found->second;
  }
  return known.emplace(material, Lookup(material)).first->second;
}

double MassWeighted(
  const std::string& material, double energyKeV, double (*perElement)(int, double, xrl_error**))
{
  const Composition& composition = CompositionOf(material);
  double sum = 0.0;
  for (std::size_t i = 0; i < composition.Elements.size(); ++i)
  {
    xrl_error* error = nullptr;
    const double value = perElement(composition.Elements[i], energyKeV, &error);
    if (error)
    {
      const std::string message = error->message;
      xrl_clear_error(&error);
      throw std::invalid_argument(
        "material '" + material + "' at " + std::to_string(energyKeV) + " keV: " + message);
    }
    sum += composition.MassFractions[i] * value;
  }
  return sum;
}
}

void CheckMaterialName(const std::string& material)
{
  (void)CompositionOf(material);
}

double MassAttenuation(const std::string& material, double energyKeV)
{
  return MassWeighted(material, energyKeV, CS_Total);
}

double MassEnergyAbsorption(const std::string& material, double energyKeV)
{
  return MassWeighted(material, energyKeV, CS_Energy);
}

double MaterialDensity(const std::string& material, double fallback)
{
  const Composition& composition = CompositionOf(material);
  if (composition.Density > 0.0)
  {
    return composition.Density;
  }
  if (!(fallback > 0.0))
  {
    throw std::invalid_argument("material '" + material +
      "' is a formula, not a NIST compound or an element: give its density in g/cm^3");
  }
  return fallback;
}

} // namespace mcx
