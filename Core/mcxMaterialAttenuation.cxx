#include "mcxMaterialAttenuation.h"

#include <xraylib.h>

#include <memory>
#include <stdexcept>

namespace mcx
{
namespace
{

// xraylib reports through an error object; the message becomes the one line a
// user sees.
struct ErrorSlot
{
  xrl_error* Error = nullptr;
  ~ErrorSlot() { xrl_clear_error(&this->Error); }
  void ThrowIfSet(const std::string& what) const
  {
    if (this->Error)
    {
      throw std::invalid_argument(what + ": " + this->Error->message);
    }
  }
};

int ElementNumber(const std::string& material)
{
  xrl_error* error = nullptr;
  const int z = SymbolToAtomicNumber(material.c_str(), &error);
  xrl_clear_error(&error);
  return z;
}

}

void CheckMaterialName(const std::string& material)
{
  // Any energy in xraylib's range answers whether the name is known.
  (void)MassAttenuation(material, 50.0);
}

double MassAttenuation(const std::string& material, double energyKeV)
{
  ErrorSlot slot;
  const double value = CS_Total_CP(material.c_str(), energyKeV, &slot.Error);
  slot.ThrowIfSet("material '" + material + "' at " + std::to_string(energyKeV) + " keV");
  return value;
}

double MassEnergyAbsorption(const std::string& material, double energyKeV)
{
  ErrorSlot slot;
  const double value = CS_Energy_CP(material.c_str(), energyKeV, &slot.Error);
  slot.ThrowIfSet("material '" + material + "' at " + std::to_string(energyKeV) + " keV");
  return value;
}

double MaterialDensity(const std::string& material, double fallback)
{
  {
    xrl_error* error = nullptr;
    compoundDataNIST* nist = GetCompoundDataNISTByName(material.c_str(), &error);
    xrl_clear_error(&error);
    if (nist)
    {
      const double density = nist->density;
      FreeCompoundDataNIST(nist);
      return density;
    }
  }
  if (const int z = ElementNumber(material); z > 0)
  {
    ErrorSlot slot;
    const double density = ElementDensity(z, &slot.Error);
    slot.ThrowIfSet("density of '" + material + "'");
    return density;
  }
  CheckMaterialName(material);
  if (!(fallback > 0.0))
  {
    throw std::invalid_argument("material '" + material +
      "' is a formula, not a NIST compound or an element: give its density in g/cm^3");
  }
  return fallback;
}

} // namespace mcx
