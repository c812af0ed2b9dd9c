#include "mcxProcesses.h"

#include "mcxFail.h"

#include "vtkMPIController.h"
#include "vtkMultiProcessController.h"
#include "vtkSmartPointer.h"

#include <cstdlib>

namespace mcxapp
{

namespace
{
vtkSmartPointer<vtkMPIController> Controller;

// Variables that Open MPI, MPICH and PMIx-based launchers set for the
// processes they start.
bool LaunchedByMPI()
{
  for (const char* name : { "OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS" })
  {
    if (std::getenv(name))
    {
      return true;
    }
  }
  return false;
}
}

void StartProcesses(int* argc, char*** argv)
{
  if (!LaunchedByMPI())
  {
    return;
  }
  Controller = vtkSmartPointer<vtkMPIController>::New();
  Controller->Initialize(argc, argv);
  vtkMultiProcessController::SetGlobalController(Controller);
  // The processes fail alike (errors in the filters are agreed on and name
  // the process they come from), so the first one says it; the launcher
  // ends the others (no MPI_Finalize: it would wait for a process still at
  // work).
  SilenceFailures(Controller->GetLocalProcessId() != 0);
}

void FinishProcesses()
{
  if (Controller)
  {
    Controller->Finalize();
    vtkMultiProcessController::SetGlobalController(nullptr);
    Controller = nullptr;
  }
}

vtkMultiProcessController* DistributedController()
{
  return Controller && Controller->GetNumberOfProcesses() > 1 ? Controller.GetPointer() : nullptr;
}

bool IsFirstProcess()
{
  return !Controller || Controller->GetLocalProcessId() == 0;
}

int NumberOfProcesses()
{
  return Controller ? Controller->GetNumberOfProcesses() : 1;
}

} // namespace mcxapp
