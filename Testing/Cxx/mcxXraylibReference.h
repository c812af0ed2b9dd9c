// Reference values straight from xraylib for the polychromatic tests. A NIST
// compound's coefficient is summed here from its elements (CS_Total_CP does
// the same, but in xraylib 4.0 leaks on every NIST name, which the sanitized
// test run would report); an element or formula goes to CS_Total_CP.
#ifndef mcxXraylibReference_h
#define mcxXraylibReference_h

#include <xraylib.h>

namespace mcxtest
{

inline double XrlTotal(const char* material, double energy)
{
  if (compoundDataNIST* nist = GetCompoundDataNISTByName(material, nullptr))
  {
    double sum = 0.0;
    for (int i = 0; i < nist->nElements; ++i)
    {
      sum += nist->massFractions[i] * CS_Total(nist->Elements[i], energy, nullptr);
    }
    FreeCompoundDataNIST(nist);
    return sum;
  }
  return CS_Total_CP(material, energy, nullptr);
}

inline double NistDensity(const char* material)
{
  compoundDataNIST* nist = GetCompoundDataNISTByName(material, nullptr);
  if (!nist)
  {
    return 0.0;
  }
  const double density = nist->density;
  FreeCompoundDataNIST(nist);
  return density;
}

} // namespace mcxtest

#endif
