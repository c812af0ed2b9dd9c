// The contained read (mcxContainedReader.h): the child that reads under an
// address-space limit and hands the volume over through a memfd, and the
// parent that waits within the time limit and takes the volume over.
#include "mcxContainedReader.h"

#include "mcxByteSize.h"
#include "mcxChildProcess.h"
#include "mcxHeaderCheck.h"
#include "mcxVolumeReader.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkPointData.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iomanip>
#include <new>
#include <sstream>
#include <thread>

#include <csignal>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace mcxio
{

namespace
{
// What the child hands back, at the start of the shared file: a message on
// failure, the read's note, then the scalars (name, then data at
// DataOffset) and geometry.
struct Handover
{
  char Magic[8] = { 'M', 'C', 'X', 'V', 'O', 'L', '1', 0 };
  std::int32_t Failed = 1; // 0: the volume follows; NotHandedOver: read it in the parent
  std::int32_t ScalarType = 0;
  std::int32_t Components = 0;
  // Not only the size: the start places the volume.
  std::int32_t Extent[6] = { 0, -1, 0, -1, 0, -1 };
  double Spacing[3] = { 1, 1, 1 };
  double Origin[3] = { 0, 0, 0 };
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  std::uint64_t MessageBytes = 0;
  std::uint64_t NoteBytes = 0;
  std::uint64_t NameBytes = 0;
  std::uint64_t DataOffset = 0;
  std::uint64_t DataBytes = 0;
};

// Address space a reader may map besides its data (stacks, small buffers).
const unsigned long long AddressSpaceAllowance = 1ULL << 30;

// This process's address space now (/proc/self/statm, in pages).
unsigned long long MappedBytes()
{
  unsigned long long pages = 0;
  if (FILE* statm = std::fopen("/proc/self/statm", "r"))
  {
    if (std::fscanf(statm, "%llu", &pages) != 1)
    {
      pages = 0;
    }
    std::fclose(statm);
  }
  return pages * static_cast<unsigned long long>(::sysconf(_SC_PAGESIZE));
}

// The child read the volume but a file-size limit (ulimit -f, which holds
// for shared memory files too) kept it from handing it over: the parent
// reads it itself, its headers checked again.
const std::int32_t NotHandedOver = 2;

bool WriteAll(int fd, const void* data, std::uint64_t bytes)
{
  const auto* p = static_cast<const char*>(data);
  while (bytes > 0)
  {
    const ssize_t n =
      ::write(fd, p, static_cast<std::size_t>(std::min<std::uint64_t>(bytes, 1 << 30)));
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      return false;
    }
    p += n;
    bytes -= static_cast<std::uint64_t>(n);
  }
  return true;
}

void HandOverFailure(
  int fd, const std::string& message, const std::string& note, std::int32_t failure = 1)
{
  Handover header;
  header.Failed = failure;
  header.MessageBytes = message.size();
  header.NoteBytes = note.size();
  WriteAll(fd, &header, sizeof(header));
  WriteAll(fd, message.data(), message.size());
  WriteAll(fd, note.data(), note.size());
}

// False (errno set) when the volume could not be written whole.
bool HandOverVolume(int fd, vtkImageData* volume, const std::string& note)
{
  vtkDataArray* scalars = volume->GetPointData()->GetScalars();
  Handover header;
  header.Failed = 0;
  header.ScalarType = scalars->GetDataType();
  header.Components = scalars->GetNumberOfComponents();
  volume->GetExtent(header.Extent);
  volume->GetSpacing(header.Spacing);
  volume->GetOrigin(header.Origin);
  std::copy(volume->GetDirectionMatrix()->GetData(), volume->GetDirectionMatrix()->GetData() + 9,
    header.Direction);
  const std::string name = scalars->GetName() ? scalars->GetName() : "";
  header.NoteBytes = note.size();
  header.NameBytes = name.size();
  header.DataOffset = sizeof(header) + note.size() + name.size();
  header.DataBytes = static_cast<std::uint64_t>(scalars->GetNumberOfValues()) *
    static_cast<std::uint64_t>(scalars->GetDataTypeSize());
  return WriteAll(fd, &header, sizeof(header)) && WriteAll(fd, note.data(), note.size()) &&
    WriteAll(fd, name.data(), name.size()) &&
    WriteAll(fd, scalars->GetVoidPointer(0), header.DataBytes);
}

// The child: silent (stderr to /dev/null), under the memory limit, killed
// with its parent; it reads, hands over and ends without running any
// destructor (a reader fault may have left the heap in any state).
[[noreturn]] void ReadInChild(const std::string& path, const ContainedRead& read,
  const ReadLimits& limits, int fd, pid_t parent, std::atomic<std::uint64_t>* progress)
{
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent)
  {
    ::_exit(1); // the parent ended before the request took hold
  }
  const int quiet = ::open("/dev/null", O_WRONLY);
  if (quiet >= 0)
  {
    ::dup2(quiet, STDERR_FILENO);
    ::dup2(quiet, STDOUT_FILENO);
  }
  if (limits.MemoryBytes > 0)
  {
    // The budget is for data: what is mapped already (libraries, and a
    // sanitizer's shadow memory) and an allowance for stacks come on top.
    const rlim_t space = MappedBytes() + limits.MemoryBytes + AddressSpaceAllowance;
    const rlimit memory = { space, space };
    ::setrlimit(RLIMIT_AS, &memory);
  }
  std::string error;
  std::string note;
  try
  {
    vtkSmartPointer<vtkImageData> volume = read(error, note,
      [progress](double fraction)
      {
        std::uint64_t bits = 0;
        std::memcpy(&bits, &fraction, sizeof(bits));
        progress->store(bits, std::memory_order_relaxed);
      });
    if (volume && HandOverVolume(fd, volume, note))
    {
      ::_exit(0);
    }
    if (volume)
    {
      const bool fileSizeLimit = errno == EFBIG;
      error = "cannot read '" + path + "': the volume cannot be handed over from the reader (" +
        std::strerror(errno) +
        (fileSizeLimit ? ": the file-size limit, ulimit -f, holds for its shared memory" : "") +
        ")";
      ::ftruncate(fd, 0);
      ::lseek(fd, 0, SEEK_SET);
      HandOverFailure(fd, error, note, fileSizeLimit ? NotHandedOver : 1);
      ::_exit(0);
    }
  }
  catch (const std::bad_alloc&)
  {
    error = "cannot read '" + path + "': out of memory while reading";
  }
  HandOverFailure(fd, error, note);
  ::_exit(0);
}

// The read refused when its child cannot be started (a process limit, no
// file descriptor left): one line with errno's words.
std::string NotStarted(const std::string& path, const std::string& what, int cause)
{
  return "cannot read '" + path + "': the reader's child process could not be started (" + what +
    ": " + std::strerror(cause) + ")";
}

enum class Waited
{
  Finished,
  TimedOut,
  Stopped
};

// Waits for the child at most limits.Seconds, passing its progress on to
// limits.Progress; the child is killed past the time or when told to stop.
Waited WaitFor(
  pid_t child, const ReadLimits& limits, const std::atomic<std::uint64_t>& progress, int& status)
{
  const auto deadline =
    std::chrono::steady_clock::now() + std::chrono::duration<double>(limits.Seconds);
  std::chrono::milliseconds pause(1);
  for (;;)
  {
    const pid_t done = ::waitpid(child, &status, WNOHANG);
    if (done == child || (done < 0 && errno != EINTR))
    {
      return Waited::Finished;
    }
    double fraction = 0.0;
    const std::uint64_t bits = progress.load(std::memory_order_relaxed);
    std::memcpy(&fraction, &bits, sizeof(fraction));
    const bool stopped = limits.Progress && !limits.Progress(fraction);
    if (stopped || std::chrono::steady_clock::now() >= deadline)
    {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      return stopped ? Waited::Stopped : Waited::TimedOut;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(20));
  }
}

// The handed-over volume (the header's voxels, consistent with its data
// bytes) copied out of the shared file; null with error set when its sizes
// disagree, it exceeds the budget or cannot be allocated.
vtkSmartPointer<vtkImageData> CopyVolume(const char* bytes, Handover& header, std::uint64_t voxels,
  const std::string& path, const ReadLimits& limits, std::string& error)
{
  auto scalars =
    vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(header.ScalarType));
  std::uint64_t values = 0;
  std::uint64_t dataBytes = 0;
  if (!scalars ||
    __builtin_mul_overflow(voxels, static_cast<std::uint64_t>(header.Components), &values) ||
    __builtin_mul_overflow(
      values, static_cast<std::uint64_t>(scalars->GetDataTypeSize()), &dataBytes) ||
    dataBytes != header.DataBytes)
  {
    error = "cannot read '" + path + "': the reader handed back an inconsistent volume";
    return nullptr;
  }
  if (limits.MemoryBytes > 0 && header.DataBytes > limits.MemoryBytes)
  {
    error = "cannot read '" + path + "': the volume needs " +
      mcx::DescribeBytes(double(header.DataBytes)) + ", more than the memory budget of " +
      mcx::DescribeBytes(double(limits.MemoryBytes)) + " (" + limits.MemoryBytesName + ")";
    return nullptr;
  }
  scalars->SetNumberOfComponents(header.Components);
  if (!scalars->Allocate(static_cast<vtkIdType>(values)))
  {
    error =
      "cannot read '" + path + "': cannot allocate " + mcx::DescribeBytes(double(header.DataBytes));
    return nullptr;
  }
  scalars->SetNumberOfTuples(static_cast<vtkIdType>(voxels));
  std::memcpy(scalars->GetVoidPointer(0), bytes + header.DataOffset,
    static_cast<std::size_t>(header.DataBytes));
  scalars->SetName(std::string(
    bytes + header.DataOffset - header.NameBytes, static_cast<std::size_t>(header.NameBytes))
                     .c_str());
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->SetExtent(header.Extent);
  volume->SetSpacing(header.Spacing);
  volume->SetOrigin(header.Origin);
  volume->SetDirectionMatrix(header.Direction);
  volume->GetPointData()->SetScalars(scalars);
  return volume;
}

// The volume from the shared file, its sizes checked against each other.
vtkSmartPointer<vtkImageData> TakeOver(int fd, const std::string& path, const ReadLimits& limits,
  bool& readHere, std::string& error, std::string& note)
{
  readHere = false;
  struct stat info;
  if (::fstat(fd, &info) != 0 || static_cast<std::uint64_t>(info.st_size) < sizeof(Handover))
  {
    error = "cannot read '" + path + "': the reader ended without a result";
    return nullptr;
  }
  const std::uint64_t size = static_cast<std::uint64_t>(info.st_size);
  void* mapped = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
  if (mapped == MAP_FAILED)
  {
    error = "cannot read '" + path + "': cannot map the volume (" +
      mcx::DescribeBytes(double(size)) + ")";
    return nullptr;
  }
  const auto* bytes = static_cast<const char*>(mapped);
  Handover header;
  std::memcpy(&header, bytes, sizeof(header));
  vtkSmartPointer<vtkImageData> volume;
  std::uint64_t voxels = 1; // 0 where the product of the sides would wrap
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t side =
      static_cast<std::int64_t>(header.Extent[2 * a + 1]) - header.Extent[2 * a] + 1;
    if (__builtin_mul_overflow(
          voxels, static_cast<std::uint64_t>(std::max<std::int64_t>(side, 0)), &voxels))
    {
      voxels = 0;
      break;
    }
  }
  const std::uint64_t texts = size - sizeof(header);
  if (std::memcmp(header.Magic, "MCXVOL1", 8) != 0 || header.MessageBytes > texts ||
    header.NoteBytes > texts - header.MessageBytes)
  {
    error = "cannot read '" + path + "': the reader ended without a result";
    ::munmap(mapped, size);
    return nullptr;
  }
  note.assign(bytes + sizeof(header) + (header.Failed ? header.MessageBytes : 0),
    static_cast<std::size_t>(header.NoteBytes));
  if (header.Failed == NotHandedOver)
  {
    readHere = true;
    error.assign(bytes + sizeof(header), static_cast<std::size_t>(header.MessageBytes));
  }
  else if (header.Failed)
  {
    error.assign(bytes + sizeof(header), static_cast<std::size_t>(header.MessageBytes));
    if (error.empty())
    {
      error = "cannot read '" + path + "'";
    }
  }
  else if (header.MessageBytes != 0 || header.NameBytes > size ||
    header.DataOffset != sizeof(header) + header.NoteBytes + header.NameBytes ||
    header.DataOffset > size || header.DataBytes > size - header.DataOffset ||
    header.Components < 1 || voxels == 0)
  {
    error = "cannot read '" + path + "': the reader handed back an inconsistent volume";
  }
  else
  {
    volume = CopyVolume(bytes, header, voxels, path, limits, error);
  }
  ::munmap(mapped, size);
  return volume;
}
}

vtkSmartPointer<vtkImageData> RunContained(const std::string& path, const ContainedRead& read,
  const ReadLimits& limits, std::string& error, std::string& note)
{
  note.clear();
  int fd = ::memfd_create("mcxray-volume", MFD_CLOEXEC);
  if (fd >= 0 && fd <= STDERR_FILENO)
  {
    // stdin, stdout or stderr was closed: the child's redirections would
    // close the shared file.
    const int moved = ::fcntl(fd, F_DUPFD_CLOEXEC, STDERR_FILENO + 1);
    ::close(fd);
    fd = moved;
  }
  if (fd < 0)
  {
    // No fallback in this process: a reader that containment exists for
    // would run unguarded (a known-bad file would end mcxray).
    error = NotStarted(path, "no shared memory for the volume", errno);
    return nullptr;
  }
  const DefaultChildSignal childSignal;
  // The child's progress, a double's bits in a page both processes share.
  void* page = ::mmap(nullptr, sizeof(std::atomic<std::uint64_t>), PROT_READ | PROT_WRITE,
    MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (page == MAP_FAILED)
  {
    const int cause = errno;
    ::close(fd);
    error = NotStarted(path, "no shared memory for its progress", cause);
    return nullptr;
  }
  auto* progress = new (page) std::atomic<std::uint64_t>(0);
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0)
  {
    const int cause = errno;
    ::munmap(page, sizeof(*progress));
    ::close(fd);
    error = NotStarted(path, "cannot start a process", cause);
    return nullptr;
  }
  if (child == 0)
  {
    ReadInChild(path, read, limits, fd, parent, progress);
  }
  int status = 0;
  vtkSmartPointer<vtkImageData> volume;
  const Waited waited = WaitFor(child, limits, *progress, status);
  ::munmap(page, sizeof(*progress));
  if (waited == Waited::Stopped)
  {
    error.clear(); // the caller's user asked for it: no error
  }
  else if (waited == Waited::TimedOut)
  {
    std::ostringstream seconds;
    seconds << std::setprecision(3) << limits.Seconds;
    error = "cannot read '" + path + "': the reader did not finish within " + seconds.str() +
      " s (a corrupt file? " + limits.SecondsName + " sets the limit)";
  }
  else if (WIFSIGNALED(status))
  {
    error = "cannot read '" + path + "': the reader crashed (" + SignalName(WTERMSIG(status)) +
      "): the file is corrupt, does not match its header, or needs more memory than the budget" +
      (limits.MemoryBytes > 0 ? " of " + mcx::DescribeBytes(double(limits.MemoryBytes))
                              : std::string());
  }
  else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
  {
    // The child ends with 0 on its own; anything else is a fault's (a
    // sanitizer's report, say).
    error = "cannot read '" + path + "': the reader crashed (exit status " +
      std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
      "): the file is corrupt or does not match its header";
  }
  else
  {
    bool readHere = false;
    volume = TakeOver(fd, path, limits, readHere, error, note);
    if (readHere && limits.ReadHereWhenNotHandedOver)
    {
      volume = read(error, note,
        [&limits](double fraction)
        {
          if (limits.Progress)
          {
            limits.Progress(fraction); // no stop here: the read runs in this process
          }
        });
    }
  }
  ::close(fd);
  return volume;
}

vtkSmartPointer<vtkImageData> ReadVolumeContained(const std::string& path,
  const VolumeReadOptions& options, const ReadLimits& limits, std::string& error)
{
  VolumeReadOptions here = options;
  here.MemoryBudget = limits.MemoryBytes;
  here.DicomInThisProcess = true; // contained already
  ReadLimits named = limits;
  named.MemoryBytesName = options.MemoryBudgetName;
  // A DICOM series is never parsed here (mcxVolumeReader.h).
  named.ReadHereWhenNotHandedOver = !vtksys::SystemTools::FileIsDirectory(path);
  std::string note;
  return RunContained(
    path,
    [&](std::string& problem, std::string&, const std::function<void(double)>&)
    { return ReadVolume(path, here, problem); },
    named, error, note);
}

} // namespace mcxio
