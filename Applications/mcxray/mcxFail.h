// The one way a command ends with an error: a single line on stderr and
// exit status 2, so that scripts and tests can rely on both.
#ifndef mcxFail_h
#define mcxFail_h

#include <string>

namespace mcxapp
{

/// Prints "mcxray: error: message" and exits with status 2 (or, with a
/// handler set, calls it; a handler must not return).
[[noreturn]] void Fail(const std::string& message);

/// What Fail does instead of exiting: the fuzz targets throw, so that one
/// process can try many inputs. Null (the default) restores the exit.
using FailHandler = void (*)(const std::string& message);
void SetFailHandler(FailHandler handler);

/// Exits without the line (the processes of an MPI run other than the first:
/// they fail alike, so one says it).
void SilenceFailures(bool silent);

} // namespace mcxapp

#endif
