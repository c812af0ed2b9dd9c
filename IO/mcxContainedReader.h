// Reads a volume in a child process, so that a reader fault that slips past
// every header check (VTK 9.1's readers trust their headers) cannot take the
// tool down or hang it: the child reads under a memory limit, hands the
// volume back through shared memory and ends; a crash, a hang past the time
// limit or an allocation beyond the budget becomes one line of error.
#ifndef mcxContainedReader_h
#define mcxContainedReader_h

#include "mcxVolumeReader.h"
#include "vtkSmartPointer.h"

#include <functional>
#include <string>

class vtkImageData;

namespace mcxio
{

struct ReadLimits
{
  double Seconds = 300.0;             // the reader is stopped after this long
  unsigned long long MemoryBytes = 0; // the child's address-space limit; 0: none
  // How the caller's user sets Seconds, named in the message of a reader
  // stopped by it (vtkMCXVolumeReader's setter; the command line's option).
  std::string SecondsName = "SetTimeLimit";
  // How the caller's user sets MemoryBytes (named where a volume exceeds it).
  std::string MemoryBytesName = "SetMemoryBudget";
  // Where a file-size limit (ulimit -f, which holds for shared memory too)
  // keeps the child from handing the volume over: read again in this
  // process (true), or fail with an error that says so (false: a read that
  // must never run here, a DICOM series').
  bool ReadHereWhenNotHandedOver = true;
  // Called every few milliseconds while the child reads, with the progress
  // it reports (0 to 1); false stops the read (the caller's user aborted):
  // null and no error. Empty: the read runs to its end or its limits.
  std::function<bool(double)> Progress;
};

/// A read to run in the child: the volume, or null with error set to one
/// line; note is text for the caller besides the volume (a DICOM folder's
/// list of series, say), handed back either way; progress(fraction) tells
/// the caller how far it is.
using ContainedRead = std::function<vtkSmartPointer<vtkImageData>(
  std::string& error, std::string& note, const std::function<void(double)>& progress)>;

/// read run in a child process within limits, as below: its volume and
/// note, or null with error set to one line (its own, its signal's, the
/// time limit's), or null and no error where limits.Progress stopped it.
vtkSmartPointer<vtkImageData> RunContained(const std::string& path, const ContainedRead& read,
  const ReadLimits& limits, std::string& error, std::string& note);

/// ReadVolume (checked headers first, then the VTK reader) in a child
/// process within limits (options.MemoryBudget is limits.MemoryBytes; POSIX
/// only: fork, memfd_create, setrlimit): the
/// scalars with their geometry (spacing, origin, direction), or null with
/// error set to one line that says what went wrong (the reader's own
/// message, its signal, or the time limit). A child that cannot be started
/// (a process limit, no file descriptor or shared memory left) is an error
/// too: the reader never runs unguarded in this process.
vtkSmartPointer<vtkImageData> ReadVolumeContained(const std::string& path,
  const VolumeReadOptions& options, const ReadLimits& limits, std::string& error);

} // namespace mcxio

#endif
