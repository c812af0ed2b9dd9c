// Nothing half-written: while a file is being written under a temporary
// name, every catchable signal that would end the process (SIGINT, SIGTERM,
// SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF, SIGXCPU)
// removes it before the process ends, and a file-size limit (SIGXFSZ) or a
// closed pipe (SIGPIPE) makes the write fail instead of killing the process,
// so the failed write is reported and its file removed.
#ifndef mcxPartialFileGuard_h
#define mcxPartialFileGuard_h

#include <cstddef>
#include <string>

namespace mcxapp
{

/// Installs the signal handlers (once per process): an interrupted run
/// prints one line, "mcxray: error: interrupted by SIGINT", removes the
/// file being written, if any (and says so), and ends as the signal would
/// have ended it; the CPU time limit (SIGXCPU) ends it with exit status 2
/// ("the CPU time limit was reached").
void InstallInterruptHandlers();

/// Registers path as the file being written for the guard's lifetime.
class PartialFileGuard
{
public:
  explicit PartialFileGuard(const std::string& path);
  ~PartialFileGuard();
  PartialFileGuard(const PartialFileGuard&) = delete;
  PartialFileGuard& operator=(const PartialFileGuard&) = delete;
};

/// From now on in this process, up to `most` files written all or nothing
/// (mcxImageOutput) stay under their temporary names until
/// CommitHeldOutputs: a run of many outputs (poses, their geometry file)
/// writes all of them or none. A signal, or an exit before the commit (a
/// failed run), removes them.
void HoldOutputs(std::size_t most);

/// Renames the held temporaries to their paths, in the order written; false
/// (error set, the rest removed) if one cannot be.
bool CommitHeldOutputs(std::string& error);

/// Whether HoldOutputs is in force; then HoldOutput takes a written
/// temporary to be renamed to path at the commit (false, taking nothing,
/// past the `most` reserved).
bool OutputsHeld();
bool HoldOutput(const std::string& temporary, const std::string& path);

} // namespace mcxapp

#endif
