#include "mcxPartialFileGuard.h"

#include <algorithm>
#include <csignal>
#include <cstring>

#include <unistd.h>

namespace mcxapp
{

namespace
{
// Only async-signal-safe work in the handler: a fixed buffer and unlink().
char PartialPath[4096];
volatile std::sig_atomic_t HasPartial = 0;
bool TerminalStderr = false; // set before the handlers, read only by them

void Say(const char* text)
{
  ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

extern "C" void OnInterrupt(int signal)
{
  if (HasPartial)
  {
    ::unlink(PartialPath);
  }
  // On a terminal the progress bar's line may be open: start a new one.
  Say(TerminalStderr ? "\nmcxray: error: interrupted by " : "mcxray: error: interrupted by ");
  Say(signal == SIGINT ? "SIGINT" : (signal == SIGTERM ? "SIGTERM" : "SIGHUP"));
  Say(HasPartial ? "; the unfinished output was removed\n" : "\n");
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}
}

void InstallInterruptHandlers()
{
  TerminalStderr = ::isatty(STDERR_FILENO) == 1;
  for (int signal : { SIGINT, SIGTERM, SIGHUP })
  {
    struct sigaction action;
    std::memset(&action, 0, sizeof(action));
    action.sa_handler = &OnInterrupt;
    sigemptyset(&action.sa_mask);
    sigaction(signal, &action, nullptr);
  }
  std::signal(SIGXFSZ, SIG_IGN); // the write fails with EFBIG and is reported
}

PartialFileGuard::PartialFileGuard(const std::string& path)
{
  HasPartial = 0;
  const std::size_t n = std::min(path.size(), sizeof(PartialPath) - 1);
  std::memcpy(PartialPath, path.data(), n);
  PartialPath[n] = '\0';
  HasPartial = path.size() < sizeof(PartialPath) ? 1 : 0;
}

PartialFileGuard::~PartialFileGuard()
{
  HasPartial = 0;
}

} // namespace mcxapp
