// A byte count in words for messages: "1.5 GiB", "12 MiB", "300 bytes".
#ifndef mcxByteSize_h
#define mcxByteSize_h

#include <cstdio>
#include <string>

namespace mcx
{

inline std::string DescribeBytes(double bytes)
{
  const char* units[] = { "bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB", "ZiB" };
  int unit = 0;
  while (bytes >= 1024 && unit < 7)
  {
    bytes /= 1024;
    ++unit;
  }
  char text[64];
  std::snprintf(text, sizeof(text), unit == 0 ? "%.0f %s" : "%.3g %s", bytes, units[unit]);
  return text;
}

} // namespace mcx

#endif
