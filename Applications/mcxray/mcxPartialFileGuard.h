// Nothing half-written: while a file is being written under a temporary
// name, every catchable signal that would end the process (SIGINT, SIGTERM,
// SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF, SIGXCPU)
// removes it before the process ends, and a file-size limit (SIGXFSZ) or a
// closed pipe (SIGPIPE) makes the write fail instead of killing the process,
// so the failed write is reported and its file removed.
#ifndef mcxPartialFileGuard_h
#define mcxPartialFileGuard_h

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

} // namespace mcxapp

#endif
