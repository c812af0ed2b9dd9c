// mcxray: simulated X-ray images of CT and MRI volumes by hybrid Monte Carlo
// volume rendering, from the command line. Each command lives in its own
// file (mcxRenderCommand, mcxViewCommand); this only picks one.
#include "mcxFail.h"
#include "mcxPartialFileGuard.h"
#include "mcxRenderCommand.h"
#include "mcxViewCommand.h"

#include <string>

int main(int argc, char* argv[])
{
  mcxapp::InstallInterruptHandlers();
  const std::string command = argc >= 2 ? argv[1] : "";
  if (command == "render")
  {
    return mcxapp::RunRender(argc, argv);
  }
  if (command == "view")
  {
    return mcxapp::RunView(argc, argv);
  }
  // No command, or --help: the main help (an error without any arguments).
  if (argc < 2 || command == "--help" || command == "-h")
  {
    mcxapp::PrintRenderUsage();
    return argc < 2 ? 2 : 0;
  }
  mcxapp::Fail(
    "unknown command '" + command + "' (expected render or view; try: mcxray render --help)");
}
