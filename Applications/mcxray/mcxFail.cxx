#include "mcxFail.h"

#include "mcxProcesses.h"

#include <cstdlib>
#include <iostream>

namespace mcxapp
{

namespace
{
FailHandler Handler = nullptr;

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

void Fail(const std::string& message)
{
  const std::string line = OneLine(message);
  if (Handler)
  {
    Handler(line);
  }
  // Under MPI the processes fail alike (errors in the filters are agreed on
  // and name the process they come from), so the first one says it; the
  // launcher ends the others (no MPI_Finalize: it would wait for a process
  // that is still at work).
  if (IsFirstProcess())
  {
    std::cerr << "mcxray: error: " << line << std::endl;
  }
  std::exit(2);
}

} // namespace mcxapp
