#include "mcxFail.h"

#include "mcxPrintableText.h"

#include <cstdlib>
#include <iostream>

namespace mcxapp
{

namespace
{
FailHandler Handler = nullptr;
bool Silent = false;
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
  // One line whatever a message quotes (a file name, a header's bytes, an
  // option's value): controls and what is no UTF-8 as \xNN.
  const std::string line = mcx::PrintableText(message);
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
