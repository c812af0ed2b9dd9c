// The processes of one mcxray run: MPI when an MPI launcher started it
// (mpirun -np N mcxray render ...), a single process with no MPI otherwise.
// Under MPI each process renders its z-slab of the volume and every one holds
// the whole image (vtkMCXProjector adds the processes' exact sums); the first
// process alone prints and writes, so the output file is the same for any N.
#ifndef mcxProcesses_h
#define mcxProcesses_h

class vtkMultiProcessController;

namespace mcxapp
{

/// Starts MPI when the environment is an MPI launcher's, with a
/// vtkMPIController as VTK's global controller; else does nothing.
void StartProcesses(int* argc, char*** argv);

/// Ends MPI after a run that succeeded on every process (no-op without MPI).
void FinishProcesses();

/// The global controller of a run with more than one process, else null.
vtkMultiProcessController* DistributedController();

/// True for the process that prints and writes (the only one without MPI).
bool IsFirstProcess();

/// Number of processes (1 without MPI).
int NumberOfProcesses();

/// This process's rank (0 without MPI).
int ProcessRank();

} // namespace mcxapp

#endif
