#include "mcxPartialFileGuard.h"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <unistd.h>

namespace mcxapp
{

namespace
{
// Only async-signal-safe work in the handlers: a fixed buffer and unlink().
char PartialPath[4096];
volatile std::sig_atomic_t HasPartial = 0;
bool TerminalStderr = false; // set before the handlers, read only by them

// HoldOutputs' temporaries and their paths. The handlers read them; they
// change only with the terminating signals blocked (SignalsBlocked).
struct HeldOutput
{
  std::string Temporary;
  std::string Path;
};
std::vector<HeldOutput> Held;
bool Holding = false;

void Say(const char* text)
{
  ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

// Every signal that ends the process by default and can be caught, with its
// name (SIGPIPE is ignored instead: a closed pipe is a failed write).
struct Terminating
{
  int Signal;
  const char* Name;
};
const Terminating Signals[] = { { SIGINT, "SIGINT" }, { SIGTERM, "SIGTERM" }, { SIGHUP, "SIGHUP" },
  { SIGQUIT, "SIGQUIT" }, { SIGUSR1, "SIGUSR1" }, { SIGUSR2, "SIGUSR2" }, { SIGALRM, "SIGALRM" },
  { SIGVTALRM, "SIGVTALRM" }, { SIGPROF, "SIGPROF" }, { SIGXCPU, "SIGXCPU" } };

const char* NameOf(int signal)
{
  for (const Terminating& t : Signals)
  {
    if (t.Signal == signal)
    {
      return t.Name;
    }
  }
  return "a signal";
}

extern "C" void OnTerminatingSignal(int signal)
{
  const bool removed = HasPartial != 0 || !Held.empty();
  if (HasPartial != 0)
  {
    ::unlink(PartialPath);
  }
  for (const HeldOutput& held : Held)
  {
    ::unlink(held.Temporary.c_str());
  }
  // On a terminal the progress bar's line may be open: start a new one.
  Say(TerminalStderr ? "\nmcxray: error: " : "mcxray: error: ");
  if (signal == SIGXCPU)
  {
    // The CPU time limit (ulimit -t): exit 2 at once, before the hard
    // limit's SIGKILL, which could not be caught.
    Say("the CPU time limit was reached (SIGXCPU)");
    Say(removed ? "; the unfinished output was removed\n" : "\n");
    ::_exit(2);
  }
  Say("interrupted by ");
  Say(NameOf(signal));
  Say(removed ? "; the unfinished output was removed\n" : "\n");
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}
}

void InstallInterruptHandlers()
{
  TerminalStderr = ::isatty(STDERR_FILENO) == 1;
  for (const Terminating& t : Signals)
  {
    struct sigaction action;
    std::memset(&action, 0, sizeof(action));
    action.sa_handler = &OnTerminatingSignal;
    // The other terminating signals wait while one is handled: one line.
    sigemptyset(&action.sa_mask);
    for (const Terminating& other : Signals)
    {
      sigaddset(&action.sa_mask, other.Signal);
    }
    sigaction(t.Signal, &action, nullptr);
  }
  std::signal(SIGXFSZ, SIG_IGN); // the write fails with EFBIG and is reported
  std::signal(SIGPIPE, SIG_IGN); // the write fails with EPIPE and is reported
}

namespace
{
// Blocks the terminating signals for its lifetime: the held list changes
// only while no handler can read it.
class SignalsBlocked
{
public:
  SignalsBlocked()
  {
    sigset_t blocked;
    sigemptyset(&blocked);
    for (const Terminating& t : Signals)
    {
      sigaddset(&blocked, t.Signal);
    }
    sigprocmask(SIG_BLOCK, &blocked, &this->Saved);
  }
  ~SignalsBlocked() { sigprocmask(SIG_SETMASK, &this->Saved, nullptr); }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

private:
  sigset_t Saved;
};

// At exit (a failed run's Fail): the held temporaries go.
extern "C" void RemoveHeldOutputs()
{
  const SignalsBlocked blocked;
  for (const HeldOutput& held : Held)
  {
    std::remove(held.Temporary.c_str());
  }
  Held.clear();
}
}

void HoldOutputs()
{
  if (!Holding)
  {
    Holding = true;
    std::atexit(&RemoveHeldOutputs);
  }
}

bool OutputsHeld()
{
  return Holding;
}

void HoldOutput(const std::string& temporary, const std::string& path)
{
  const SignalsBlocked blocked;
  Held.push_back({ temporary, path });
}

bool CommitHeldOutputs(std::string& error)
{
  const SignalsBlocked blocked;
  std::size_t done = 0;
  for (; done < Held.size(); ++done)
  {
    if (std::rename(Held[done].Temporary.c_str(), Held[done].Path.c_str()) != 0)
    {
      error = "cannot write '" + Held[done].Path + "'";
      break;
    }
  }
  for (std::size_t i = done; i < Held.size(); ++i)
  {
    std::remove(Held[i].Temporary.c_str());
  }
  const bool committed = done == Held.size();
  Held.clear();
  return committed;
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
