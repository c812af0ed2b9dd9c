#include "mcxPartialFileGuard.h"

#include <algorithm>
#include <cerrno>
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

// HoldOutputs' temporaries and their paths, room reserved up front: the
// vector never reallocates, so a handler (on any thread: TBB's do not block
// signals) reads entries [HeldFirst, HeldCount) that no one moves; the
// bounds change only once an entry is complete, and drop to 0 before any
// entry is destroyed.
struct HeldOutput
{
  std::string Temporary;
  std::string Path;
};
std::vector<HeldOutput> Held;
volatile std::sig_atomic_t HeldFirst = 0; // entries before it are renamed already
volatile std::sig_atomic_t HeldCount = 0;
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
  const bool removed = HasPartial != 0 || HeldFirst < HeldCount;
  if (HasPartial != 0)
  {
    ::unlink(PartialPath);
  }
  for (std::sig_atomic_t i = HeldFirst; i < HeldCount; ++i)
  {
    ::unlink(Held[static_cast<std::size_t>(i)].Temporary.c_str());
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
// Forgets the held entries (their files renamed or removed): the handlers
// see none before any is destroyed.
void ForgetHeld()
{
  HeldCount = 0;
  HeldFirst = 0;
  Held.clear();
}

// At exit (a failed run's Fail): the held temporaries go.
extern "C" void RemoveHeldOutputs()
{
  const std::size_t count = static_cast<std::size_t>(HeldCount);
  for (std::size_t i = static_cast<std::size_t>(HeldFirst); i < count; ++i)
  {
    std::remove(Held[i].Temporary.c_str());
  }
  ForgetHeld();
}
}

void HoldOutputs(std::size_t most)
{
  ForgetHeld();
  Held.reserve(most);
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

bool HoldOutput(const std::string& temporary, const std::string& path)
{
  if (Held.size() >= Held.capacity())
  {
    return false; // beyond the room reserved: the caller renames it now
  }
  Held.push_back({ temporary, path });
  HeldCount = static_cast<std::sig_atomic_t>(Held.size());
  return true;
}

bool CommitHeldOutputs(std::string& error)
{
  // In order: a signal during the commit removes only the temporaries not
  // renamed yet.
  const std::size_t count = static_cast<std::size_t>(HeldCount);
  std::size_t done = 0;
  for (; done < count; ++done)
  {
    if (std::rename(Held[done].Temporary.c_str(), Held[done].Path.c_str()) != 0)
    {
      error = "cannot write '" + Held[done].Path + "': " + std::strerror(errno);
      break;
    }
    HeldFirst = static_cast<std::sig_atomic_t>(done + 1);
  }
  for (std::size_t i = done; i < count; ++i)
  {
    std::remove(Held[i].Temporary.c_str());
  }
  ForgetHeld();
  return done == count;
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
