#include "mcxProcesses.h"

#include "mcxFail.h"

#ifdef MCXRAY_MPI
#include "vtkMPIController.h"
#else
#include "vtkMultiProcessController.h" // a build without MPI: never started
#endif
#include "vtkSmartPointer.h"

#include <cstdlib>

namespace mcxapp
{

namespace
{
#ifdef MCXRAY_MPI
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
#else
vtkSmartPointer<vtkMultiProcessController> Controller; // a build without MPI: never set
#endif
}

void StartProcesses(int* argc, char*** argv)
{
#ifndef MCXRAY_MPI
  // A build without MPI runs as one process even under a launcher.
  static_cast<void>(argc);
  static_cast<void>(argv);
#else
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
#endif
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

int ProcessRank()
{
  return Controller ? Controller->GetLocalProcessId() : 0;
}

} // namespace mcxapp
