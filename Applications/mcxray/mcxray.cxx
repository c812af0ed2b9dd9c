// mcxray: simulated X-ray images of CT and MRI volumes by hybrid Monte Carlo
// volume rendering, from the command line. Each command lives in its own
// file (mcxRenderCommand, mcxViewCommand); this only picks one.
#include "mcxFail.h"
#include "mcxPartialFileGuard.h"
#include "mcxProcesses.h"
#include "mcxRenderCommand.h"
#include "mcxViewCommand.h"

#include <string>

#include <cerrno>
#include <fcntl.h>
#include <unistd.h>

namespace
{
// A standard stream closed by the caller (mcxray render >&-) is /dev/null:
// else the next file opened takes its number and the log, or an error line,
// would be written into it (an output's temporary, the reader's memory).
void OpenClosedStandardStreams()
{
  // In order: the lowest free number is the one being filled.
  for (int fd = STDIN_FILENO; fd <= STDERR_FILENO; ++fd)
  {
    if (::fcntl(fd, F_GETFD) == -1 && errno == EBADF)
    {
      ::open("/dev/null", fd == STDIN_FILENO ? O_RDONLY : O_WRONLY);
    }
  }
}
}

int main(int argc, char* argv[])
{
  OpenClosedStandardStreams();
  mcxapp::InstallInterruptHandlers();
  mcxapp::StartProcesses(&argc, &argv);
  const std::string command = argc >= 2 ? argv[1] : "";
  if (command == "render")
  {
    const int status = mcxapp::RunRender(argc, argv);
    mcxapp::FinishProcesses();
    return status;
  }
  if (command == "view")
  {
    if (mcxapp::NumberOfProcesses() > 1)
    {
      mcxapp::Fail("mcxray view is interactive: run it as one process (mcxray render runs under "
                   "mpirun)");
    }
    const int status = mcxapp::RunView(argc, argv);
    mcxapp::FinishProcesses();
    return status;
  }
  // No command, or --help: the main help (an error without any arguments).
  if (argc < 2 || command == "--help" || command == "-h")
  {
    if (mcxapp::IsFirstProcess())
    {
      mcxapp::PrintRenderUsage();
    }
    mcxapp::FinishProcesses();
    return argc < 2 ? 2 : 0;
  }
  mcxapp::Fail(
    "unknown command '" + command + "' (expected render or view; try: mcxray render --help)");
}
