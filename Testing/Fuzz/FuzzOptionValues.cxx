// libFuzzer target: the option value parsers (numbers, integers with
// bounds, sizes, byte sizes, triples) on arbitrary text. A value is
// refused with one line, or lies within what was asked.
#include "FuzzFailThrows.h"
#include "mcxOptionValues.h"

#include <cmath>
#include <cstdint>
#include <string>

namespace
{
template <typename Parse>
void Try(const Parse& parse)
{
  try
  {
    parse();
  }
  catch (const mcxfuzz::Refusal&)
  {
  }
}
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  mcxfuzz::ThrowOnFail();
  const std::string text(reinterpret_cast<const char*>(data), size);
  Try([&] {
    if (!std::isfinite(mcxapp::ParseNumber(text, "--x")))
      __builtin_trap();
  });
  Try([&] {
    if (!(mcxapp::ParsePositive(text, "--x") > 0))
      __builtin_trap();
  });
  Try([&] {
    const double f = mcxapp::ParseOpenUnitFraction(text, "--x");
    if (!(f > 0 && f < 1))
      __builtin_trap();
  });
  Try([&] {
    const long long n = mcxapp::ParseInteger(text, "--x", 1, 4096);
    if (n < 1 || n > 4096)
      __builtin_trap();
  });
  Try([&] {
    const double bytes = mcxapp::ParseByteSize(text, "--x");
    if (!(bytes > 0) || bytes > std::ldexp(1.0, 60))
      __builtin_trap();
  });
  Try([&] {
    int wh[2] = { 0, 0 };
    mcxapp::ParseSize(text, "--size", 1, 65536, wh);
    if (wh[0] < 1 || wh[1] < 1 || wh[0] > 65536 || wh[1] > 65536)
      __builtin_trap();
  });
  Try([&] {
    double xyz[3];
    mcxapp::ParseTriple(text, xyz, "--camera position");
    if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
      __builtin_trap();
  });
  return 0;
}
