// What IO's forked children share (mcxContainedReader's read, mcxDicomFiles'
// parse): a signal's name for the one line that says how a child ended, and
// SIGCHLD at its default while a child runs. POSIX only; private to IO.
#ifndef mcxChildProcess_h
#define mcxChildProcess_h

#include <csignal>
#include <cstring>
#include <string>

namespace mcxio
{

/// "SIGSEGV" for SIGSEGV; "signal N" for a signal without a name here.
inline std::string SignalName(int signal)
{
  switch (signal)
  {
    case SIGSEGV:
      return "SIGSEGV";
    case SIGBUS:
      return "SIGBUS";
    case SIGFPE:
      return "SIGFPE";
    case SIGABRT:
      return "SIGABRT";
    case SIGILL:
      return "SIGILL";
    case SIGKILL:
      return "SIGKILL";
    default:
      return "signal " + std::to_string(signal);
  }
}

/// SIGCHLD at its default for its lifetime, then as it was: a child's
/// status is needed, and a launcher that ignores SIGCHLD would make the
/// system reap it unseen.
class DefaultChildSignal
{
public:
  DefaultChildSignal()
  {
    struct sigaction standard;
    std::memset(&standard, 0, sizeof(standard));
    standard.sa_handler = SIG_DFL;
    sigemptyset(&standard.sa_mask);
    ::sigaction(SIGCHLD, &standard, &this->Previous);
  }
  ~DefaultChildSignal() { ::sigaction(SIGCHLD, &this->Previous, nullptr); }
  DefaultChildSignal(const DefaultChildSignal&) = delete;
  DefaultChildSignal& operator=(const DefaultChildSignal&) = delete;

private:
  struct sigaction Previous;
};

} // namespace mcxio

#endif
