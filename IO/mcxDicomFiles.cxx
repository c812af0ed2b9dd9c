// The files of a DICOM folder and their pixel data checked against their
// headers, before vtk-dicom trusts them (mcxDicomFiles.h).
#include "mcxDicomFiles.h"

#include "mcxByteSize.h"
#include "mcxChildProcess.h"
#include "mcxHeaderCheck.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDICOMDictHash.h"
#include "vtkDICOMImageCodec.h"
#include "vtkDICOMMetaData.h"
#include "vtkDICOMParser.h"
#include "vtkDICOMValue.h"
#include "vtkNew.h"
#include "vtksys/Directory.hxx"
#include "vtksys/SystemTools.hxx"

#ifdef MCXRAY_IO_GDCM
#include "gdcmImageReader.h"
#include "gdcmTrace.h"
#endif

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <new>
#include <set>
#include <sstream>
#include <utility>

#include <poll.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#ifdef __linux__
#include <linux/magic.h>
#include <sys/vfs.h>
#endif

namespace mcxio
{

namespace
{
using Inode = std::pair<unsigned long long, unsigned long long>; // device, inode

bool Identity(const std::string& path, struct stat& info, Inode& id)
{
  if (::stat(path.c_str(), &info) != 0)
  {
    return false;
  }
  id = Inode(
    static_cast<unsigned long long>(info.st_dev), static_cast<unsigned long long>(info.st_ino));
  return true;
}

// Whether folder lies on a kernel's pseudo file system (/proc, /sys, ...):
// its files are no images, and reading some of them blocks.
bool OnPseudoFileSystem(const std::string& folder)
{
#ifdef __linux__
  struct statfs info;
  if (::statfs(folder.c_str(), &info) != 0)
  {
    return false;
  }
  const unsigned long type = static_cast<unsigned long>(info.f_type);
  for (unsigned long pseudo :
    { static_cast<unsigned long>(PROC_SUPER_MAGIC), static_cast<unsigned long>(SYSFS_MAGIC),
      static_cast<unsigned long>(DEBUGFS_MAGIC), static_cast<unsigned long>(TRACEFS_MAGIC),
      static_cast<unsigned long>(SECURITYFS_MAGIC), static_cast<unsigned long>(CGROUP_SUPER_MAGIC),
      static_cast<unsigned long>(CGROUP2_SUPER_MAGIC),
      static_cast<unsigned long>(DEVPTS_SUPER_MAGIC), static_cast<unsigned long>(BPF_FS_MAGIC) })
  {
    if (type == pseudo)
    {
      return true;
    }
  }
#else
  (void)folder;
#endif
  return false;
}

struct Walk
{
  std::set<Inode> Folders, Files;
  std::vector<std::string>* Found = nullptr;
  std::size_t Limit = 0;

  bool Visit(const std::string& folder, int depth, std::string& error)
  {
    vtksys::Directory directory;
    if (!directory.Load(folder))
    {
      return true; // unreadable below the top: vtk-dicom skips it too
    }
    for (unsigned long i = 0; i < directory.GetNumberOfFiles(); ++i)
    {
      const std::string name = directory.GetFile(i);
      if (name.empty() || name[0] == '.' || name == "DICOMDIR")
      {
        continue; // hidden, as vtk-dicom skips them (and '.' and '..')
      }
      const std::string path = folder + "/" + name;
      struct stat info;
      Inode id;
      if (!Identity(path, info, id))
      {
        continue; // a broken link
      }
      if (S_ISDIR(info.st_mode))
      {
        if (OnPseudoFileSystem(path))
        {
          continue; // a link into /proc or /sys: no images there
        }
        // Each folder once: a link back to it or above adds nothing.
        if (depth > 0 && this->Folders.insert(id).second && !this->Visit(path, depth - 1, error))
        {
          return false;
        }
        continue;
      }
      if (S_ISREG(info.st_mode) && this->Files.insert(id).second)
      {
        if (this->Found->size() >= this->Limit)
        {
          error = "it holds more than " + std::to_string(this->Limit) + " files";
          return false;
        }
        this->Found->push_back(path);
      }
    }
    return true;
  }
};

const char* const NativeSyntaxes[] = { "1.2.840.10008.1.2", "1.2.840.10008.1.20",
  "1.2.840.10008.1.2.1", "1.2.840.10008.1.2.2", "1.2.840.113619.5.2", "" };
const char* const RLE = "1.2.840.10008.1.2.5";
const char* const Deflate = "1.2.840.10008.1.2.1.99";

// The first bytes of one frame's data in the transfer syntax, or null for
// a syntax this build cannot decode.
const char* FrameMarker(const std::string& syntax, std::size_t& size)
{
  const std::string jpeg = "1.2.840.10008.1.2.4.";
  if (syntax.compare(0, jpeg.size(), jpeg) != 0)
  {
    return nullptr;
  }
  const std::string kind = syntax.substr(jpeg.size());
  if (kind == "50" || kind == "51" || kind == "57" || kind == "70" || kind == "80" || kind == "81")
  {
    size = 2;
    return "\xff\xd8"; // JPEG and JPEG-LS: start of image
  }
  if (kind == "90" || kind == "91")
  {
    size = 2;
    return "\xff\x4f"; // JPEG 2000 codestream: start of codestream
  }
  return nullptr;
}

struct Fragment
{
  std::uint64_t Offset = 0;
  std::uint64_t Length = 0;
};

std::uint32_t Little32(const unsigned char* p)
{
  return p[0] | (p[1] << 8) | (p[2] << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

// The items of encapsulated pixel data from offset: the offset table, then
// the fragments; false (error set) where the items leave the file.
bool Fragments(std::ifstream& in, std::uint64_t offset, std::uint64_t fileSize,
  std::vector<Fragment>& fragments, std::string& error)
{
  bool table = true;
  while (offset + 8 <= fileSize)
  {
    unsigned char item[8];
    in.clear();
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(reinterpret_cast<char*>(item), 8);
    const std::uint32_t tag = Little32(item), length = Little32(item + 4);
    offset += 8;
    if (tag == 0xE0DDFFFEu)
    {
      return true;
    }
    if (tag != 0xE000FFFEu || length > fileSize - offset)
    {
      error = "its encapsulated pixel data are malformed or truncated";
      return false;
    }
    if (!table)
    {
      fragments.push_back({ offset, length });
    }
    table = false;
    offset += length;
  }
  return true; // no delimiter: vtk-dicom reads to the end of the file
}

std::string ReadAt(std::ifstream& in, std::uint64_t offset, std::uint64_t length)
{
  std::string bytes(static_cast<std::size_t>(length), '\0');
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(&bytes[0], static_cast<std::streamsize>(length));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

// One file: "" or why its pixel data cannot be what its header says.
// "" when GDCM, the decoder vtk-dicom delegates JPEG, JPEG-LS and JPEG 2000
// to, decodes path's pixel data, else why: vtk-dicom ignores the decoder's
// failure and leaves zeros (a slice of garbage after a valid marker). The
// price: compressed files are decoded twice. Without GDCM's headers ""
// (the marker checks above still hold).
std::string DecodeProblem(const std::string& path, const std::string& syntax)
{
#ifdef MCXRAY_IO_GDCM
  std::ostringstream reports; // GDCM's own warnings and errors, kept off stderr
  gdcm::Trace::SetErrorStream(reports);
  gdcm::Trace::SetWarningStream(reports);
  gdcm::ImageReader reader;
  reader.SetFileName(path.c_str());
  bool decoded = reader.Read();
  if (decoded)
  {
    const gdcm::Image& image = reader.GetImage();
    std::vector<char> buffer(image.GetBufferLength());
    decoded = image.GetBuffer(buffer.data());
  }
  gdcm::Trace::SetErrorStream(std::cerr);
  gdcm::Trace::SetWarningStream(std::cerr);
  return decoded ? std::string() : "its compressed pixel data (" + syntax + ") do not decode";
#else
  (void)path;
  (void)syntax;
  return std::string();
#endif
}

std::string CheckFile(const std::string& path, double& claimed)
{
  vtkNew<vtkDICOMMetaData> meta;
  vtkNew<vtkDICOMParser> parser;
  vtkNew<vtkCallbackCommand> quiet; // vtk-dicom reports a bad file itself
  parser->AddObserver(vtkCommand::ErrorEvent, quiet);
  parser->SetMetaData(meta);
  parser->SetFileName(path.c_str());
  parser->Update();
  if (parser->GetErrorCode() || !parser->GetPixelDataFound())
  {
    return std::string();
  }
  const double frames = std::max(1.0, meta->Get(DC::NumberOfFrames).AsDouble());
  const double rows = meta->Get(DC::Rows).AsDouble(), columns = meta->Get(DC::Columns).AsDouble();
  const double samples = std::max(1.0, meta->Get(DC::SamplesPerPixel).AsDouble());
  const double bits = meta->Get(DC::BitsAllocated).AsDouble();
  const double frameBytes = rows * columns * samples * bits / 8.0;
  const double bytes = frames * frameBytes;
  claimed += bytes;
  const std::string syntax = meta->Get(DC::TransferSyntaxUID).AsString();
  const std::uint64_t offset = static_cast<std::uint64_t>(parser->GetFileOffset());
  const std::uint64_t fileSize = static_cast<std::uint64_t>(parser->GetFileSize());
  const std::uint64_t held = fileSize > offset ? fileSize - offset : 0;
  const std::string claim = "its header claims " + std::to_string(static_cast<long long>(frames)) +
    (frames == 1 ? " frame of " : " frames of ") + std::to_string(static_cast<long long>(columns)) +
    "x" + std::to_string(static_cast<long long>(rows)) + " (" + mcx::DescribeBytes(bytes) + ")";
  if (std::find(std::begin(NativeSyntaxes), std::end(NativeSyntaxes), syntax) !=
    std::end(NativeSyntaxes))
  {
    return bytes <= static_cast<double>(held)
      ? std::string()
      : "truncated: " + claim + ", the file holds " + mcx::DescribeBytes(double(held));
  }
  if (bytes > LargestCompressionRatio * (static_cast<double>(held) + 64.0))
  {
    return claim + " from " + mcx::DescribeBytes(double(held)) +
      " of compressed data, more than any decoder can make of them";
  }
  std::size_t markerSize = 0;
  const char* marker = FrameMarker(syntax, markerSize);
  if (syntax == Deflate)
  {
    return std::string(); // deflated data set, bounded by the ratio above
  }
  if (syntax != RLE && !marker)
  {
    return "its transfer syntax " + syntax + " is not one this reader decodes";
  }
  std::ifstream in(path, std::ios::binary);
  std::vector<Fragment> fragments;
  std::string error;
  if (parser->GetPixelDataVL() != 0xffffffffu)
  {
    return "its compressed pixel data are not encapsulated";
  }
  if (!Fragments(in, offset, fileSize, fragments, error))
  {
    return error;
  }
  if (syntax == RLE)
  {
    // One fragment per frame, each decoded to its end: vtk-dicom leaves
    // zeros where a segment is short, and divides by a segment count of 0.
    if (static_cast<double>(fragments.size()) != frames)
    {
      return "its RLE data hold " + std::to_string(fragments.size()) + " fragments for " +
        std::to_string(static_cast<long long>(frames)) + " frames";
    }
    vtkDICOMImageCodec codec(syntax);
    vtkDICOMImageCodec::ImageFormat format(meta);
    const double segments = samples * std::ceil(bits / 8.0);
    std::vector<unsigned char> frame;
    for (std::size_t f = 0; f < fragments.size(); ++f)
    {
      const std::string data = ReadAt(in, fragments[f].Offset, fragments[f].Length);
      const auto* bytesIn = reinterpret_cast<const unsigned char*>(data.data());
      if (data.size() < 64 || segments < 1 || Little32(bytesIn) != segments ||
        frameBytes > 130.0 * static_cast<double>(data.size()))
      {
        return "its RLE fragment " + std::to_string(f + 1) + " is not RLE data of " +
          std::to_string(static_cast<long long>(segments)) + " segments";
      }
      frame.resize(static_cast<std::size_t>(frameBytes));
      if (codec.Decode(format, bytesIn, data.size(), frame.data(), frame.size()) !=
        vtkDICOMImageCodec::NoError)
      {
        return "its RLE fragment " + std::to_string(f + 1) + " does not decode to a whole frame";
      }
    }
    return std::string();
  }
  // JPEG, JPEG-LS, JPEG 2000: each frame's first fragment starts with the
  // format's marker (vtk-dicom's decoders leave zeros where they fail).
  std::size_t starts = 0;
  for (std::size_t f = 0; f < fragments.size(); ++f)
  {
    const std::string lead =
      ReadAt(in, fragments[f].Offset, std::min<std::uint64_t>(fragments[f].Length, 8));
    const bool jp2 = markerSize == 2 && marker[1] == '\x4f' && lead.size() >= 8 &&
      lead.compare(0, 8, std::string("\0\0\0\x0cjP  ", 8)) == 0;
    const bool start = jp2 || lead.compare(0, markerSize, std::string(marker, markerSize)) == 0;
    if (f == 0 && !start)
    {
      return "its compressed pixel data are not of its transfer syntax " + syntax +
        " (no start marker)";
    }
    starts += start ? 1 : 0;
  }
  if (static_cast<double>(starts) < frames)
  {
    return "its compressed pixel data hold " + std::to_string(starts) + " of its " +
      std::to_string(static_cast<long long>(frames)) + " frames";
  }
  return DecodeProblem(path, syntax);
}
}

bool DicomFolderFiles(const std::string& folder, int depth, std::size_t limit,
  std::vector<std::string>& files, std::string& error)
{
  if (OnPseudoFileSystem(folder))
  {
    error = "it lies on a pseudo file system of the kernel (/proc, /sys), which holds no images";
    return false;
  }
  Walk walk;
  walk.Found = &files;
  walk.Limit = limit;
  // The folder and those above it count as visited: a link to '..' leads
  // back, not out.
  std::string at = vtksys::SystemTools::GetRealPath(folder);
  for (int up = 0; up < 4096; ++up)
  {
    struct stat info;
    Inode id;
    if (Identity(at, info, id))
    {
      walk.Folders.insert(id);
    }
    const std::string parent = vtksys::SystemTools::GetParentDirectory(at);
    if (parent.empty() || parent == at)
    {
      break;
    }
    at = parent;
  }
  files.clear();
  return walk.Visit(folder, depth, error);
}

bool CheckDicomPixelData(
  const std::vector<std::string>& files, unsigned long long& claimed, std::string& error)
{
  double total = 0.0;
  for (const std::string& file : files)
  {
    std::string problem;
    try
    {
      problem = CheckFile(file, total);
    }
    catch (const std::bad_alloc&)
    {
      problem = "out of memory checking its pixel data";
    }
    if (!problem.empty())
    {
      error = "'" + file + "': " + problem;
      return false;
    }
  }
  claimed = total < 1.8e19 ? static_cast<unsigned long long>(total) : ~0ULL;
  return true;
}

bool ParseInChild(const std::function<std::string()>& parse, const std::string& parsed,
  std::string& answer, std::string& error, double seconds)
{
  answer.clear();
  int channel[2];
  if (::pipe(channel) != 0)
  {
    error =
      std::string("cannot check its files in a child process (pipe: ") + std::strerror(errno) + ")";
    return false;
  }
  const DefaultChildSignal childSignal;
  const pid_t parent = ::getpid();
  const pid_t child = ::fork();
  if (child < 0)
  {
    const int cause = errno;
    ::close(channel[0]);
    ::close(channel[1]);
    error =
      std::string("cannot check its files in a child process (fork: ") + std::strerror(cause) + ")";
    return false;
  }
  if (child == 0)
  {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    ::close(channel[0]);
    std::string said;
    try
    {
      said = ::getppid() == parent ? parse() : std::string();
    }
    catch (...) // never unwind into the parent's frames copied here
    {
      ::_exit(1);
    }
    const char* at = said.data();
    for (std::size_t left = said.size(); left > 0;)
    {
      const ssize_t wrote = ::write(channel[1], at, left);
      if (wrote <= 0)
      {
        break;
      }
      at += wrote;
      left -= static_cast<std::size_t>(wrote);
    }
    ::_exit(0); // no destructors, no atexit handlers of the parent's
  }
  ::close(channel[1]);
  // The answer until the child closes the pipe, or until the time is up.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  bool late = false;
  char buffer[4096];
  for (;;)
  {
    const long long left = std::chrono::duration_cast<std::chrono::milliseconds>(
      deadline - std::chrono::steady_clock::now())
                             .count();
    pollfd ready = { channel[0], POLLIN, 0 };
    const int wait = static_cast<int>(std::min<long long>(left, 1 << 30));
    const int polled = left > 0 ? ::poll(&ready, 1, wait) : 0;
    if (polled == 0)
    {
      late = true;
      ::kill(child, SIGKILL);
      break;
    }
    const ssize_t got = polled > 0 ? ::read(channel[0], buffer, sizeof(buffer)) : -1;
    if (got == 0 || (got < 0 && errno != EINTR))
    {
      break;
    }
    answer.append(buffer, got > 0 ? static_cast<std::size_t>(got) : 0);
  }
  ::close(channel[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR)
  {
  }
  if (late)
  {
    std::ostringstream limit;
    limit << std::setprecision(3) << seconds;
    error = "vtk-dicom's parser did not finish within " + limit.str() + " s on " + parsed;
    return false;
  }
  if (WIFSIGNALED(status))
  {
    error = "vtk-dicom's parser crashed (" + SignalName(WTERMSIG(status)) + ") on " + parsed;
    return false;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
  {
    // The child ends with 0 on its own; anything else is a fault's (an
    // exception, a sanitizer's report).
    error = "vtk-dicom's parser failed (exit status " +
      std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ") on " + parsed;
    return false;
  }
  return true;
}

bool ProbeDicomFiles(
  const std::vector<std::string>& files, const std::function<void()>& scan, std::string& error)
{
  std::string verdict;
  const bool ended = ParseInChild(
    [&]()
    {
      if (scan)
      {
        scan();
      }
      unsigned long long claimed = 0;
      std::string problem;
      CheckDicomPixelData(files, claimed, problem);
      return problem;
    },
    "one of its files", verdict, error);
  if (ended)
  {
    error = verdict;
  }
  return ended && verdict.empty();
}

} // namespace mcxio
