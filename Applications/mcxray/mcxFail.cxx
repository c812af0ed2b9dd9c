#include "mcxFail.h"

#include <cstdlib>
#include <iostream>

namespace mcxapp
{

namespace
{
FailHandler Handler = nullptr;
bool Silent = false;

// One line whatever a message quotes (a file name, an option's value):
// control characters are written as \xNN.
std::string OneLine(const std::string& message)
{
  std::string line;
  for (const char c : message)
  {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f)
    {
      const char* digits = "0123456789abcdef";
      line += "\\x";
      line += digits[byte >> 4];
      line += digits[byte & 15];
    }
    else
    {
      line += c;
    }
  }
  return line;
}
}

void SetFailHandler(FailHandler handler)
{
  Handler = handler;
}

void SilenceFailures(bool silent)
{
  Silent = silent;
}

void Fail(const std::string& message)
{
  const std::string line = OneLine(message);
  if (Handler)
  {
    Handler(line);
  }
  if (!Silent)
  {
    std::cerr << "mcxray: error: " << line << std::endl;
  }
  std::exit(2);
}

} // namespace mcxapp
