// Nothing half-written: while a file is being written under a temporary
// name, SIGINT, SIGTERM and SIGHUP remove it before the process ends, and a
// file-size limit (SIGXFSZ) makes the write fail instead of killing the
// process, so the failed write is reported and its file removed.
#ifndef mcxPartialFileGuard_h
#define mcxPartialFileGuard_h

#include <string>

namespace mcxapp
{

/// Installs the signal handlers (once per process): an interrupted run
/// prints one line, "mcxray: error: interrupted by SIGINT", removes the
/// file being written, if any (and says so), and ends as the signal would
/// have ended it.
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
