#include "mcxFail.h"

#include <cstdlib>
#include <iostream>

namespace mcxapp
{

void Fail(const std::string& message)
{
  std::cerr << "mcxray: error: " << message << std::endl;
  std::exit(2);
}

} // namespace mcxapp
