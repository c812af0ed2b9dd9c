// The one way a command ends with an error: a single line on stderr and
// exit status 2, so that scripts and tests can rely on both.
#ifndef mcxFail_h
#define mcxFail_h

#include <string>

namespace mcxapp
{

/// Prints "mcxray: error: message" and exits with status 2.
[[noreturn]] void Fail(const std::string& message);

} // namespace mcxapp

#endif
