#include "mcxImageOutput.h"

#include "mcxPartialFileGuard.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkImageShiftScale.h"
#include "vtkMetaImageWriter.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkXMLImageDataWriter.h"
#include "vtksys/SystemInformation.hxx"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

namespace mcxapp
{

namespace
{
std::string Extension(const std::string& path)
{
  std::string ext = vtksys::SystemTools::GetFilenameLastExtension(path);
  std::transform(
    ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Portable float map: header, then float32 rows from the bottom row up,
// which is the order of VTK's image rows.
bool WritePFM(vtkImageData* image, const std::string& path)
{
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* values = image->GetPointData()->GetScalars();
  std::ofstream out(path, std::ios::binary);
  out << "Pf\n" << dims[0] << " " << dims[1] << "\n-1.0\n"; // negative scale: little endian
  std::vector<float> row(static_cast<std::size_t>(dims[0]));
  for (int j = 0; j < dims[1]; ++j)
  {
    for (int i = 0; i < dims[0]; ++i)
    {
      row[static_cast<std::size_t>(i)] =
        static_cast<float>(values->GetTuple1(static_cast<vtkIdType>(j) * dims[0] + i));
    }
    out.write(reinterpret_cast<const char*>(row.data()),
      static_cast<std::streamsize>(row.size() * sizeof(float)));
  }
  out.close(); // the last buffer's write can fail too (a full disk, a file-size limit)
  return static_cast<bool>(out);
}

// libpng reports a failed write on stderr by itself ("libpng error: Write
// Error"); the writer's error code is what the caller reports, in one line.
bool WritePNGQuietly(vtkPNGWriter* writer)
{
  std::fflush(stderr);
  const int saved = ::dup(STDERR_FILENO);
  const int quiet = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (saved >= 0 && quiet >= 0)
  {
    ::dup2(quiet, STDERR_FILENO);
  }
  writer->Write();
  std::fflush(stderr);
  if (saved >= 0 && quiet >= 0)
  {
    ::dup2(saved, STDERR_FILENO);
  }
  for (int fd : { saved, quiet })
  {
    if (fd >= 0)
    {
      ::close(fd);
    }
  }
  return writer->GetErrorCode() == 0;
}

bool WritePNG(vtkImageData* image, const std::string& path, const PngWindow& window)
{
  double low = window.Low, high = window.High;
  if (window.Automatic)
  {
    double range[2];
    image->GetPointData()->GetScalars()->GetRange(range);
    low = 0.0;
    high = range[1] > 0 ? range[1] : 1.0;
  }
  const double top = window.Bits == 16 ? 65535.0 : 255.0;
  vtkNew<vtkImageShiftScale> scale;
  scale->SetInputData(image);
  scale->SetShift(-low);
  scale->SetScale(top / (high - low));
  scale->SetOutputScalarType(window.Bits == 16 ? VTK_UNSIGNED_SHORT : VTK_UNSIGNED_CHAR);
  scale->ClampOverflowOn();
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(scale->GetOutputPort());
  writer->SetFileName(path.c_str());
  return WritePNGQuietly(writer);
}
}

bool IsSupportedOutput(const std::string& path)
{
  const std::string ext = Extension(path);
  return ext == ".vti" || ext == ".mha" || ext == ".png" || ext == ".pfm";
}

namespace
{
// The name a file is written under before it is renamed to path: the
// process id keeps concurrent runs writing the same path apart.
std::string TemporaryName(const std::string& path)
{
  return path + ".part-" + std::to_string(vtksys::SystemInformation().GetProcessId()) +
    Extension(path);
}

// Runs write(temporary) and renames the result to path only if it succeeded.
// (std::rename: VTK 9.1's kwsys has no RenameFile.)
template <typename Write>
bool WriteAtomically(const std::string& path, const Write& write, std::string& error,
  const BeforeRename& beforeRename = BeforeRename())
{
  const std::string temporary = TemporaryName(path);
  const PartialFileGuard guard(temporary);
  errno = 0;
  const bool written = write(temporary);
  const std::string refused = written && beforeRename ? beforeRename() : std::string();
  if (!refused.empty())
  {
    std::remove(temporary.c_str());
    error = refused;
    return false;
  }
  if (written && OutputsHeld() && HoldOutput(temporary, path))
  {
    return true; // renamed with the run's other outputs
  }
  if (!written || std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    // Only the causes a write itself has (a stale errno of some other call
    // would mislead).
    const int cause = errno;
    const bool known = cause == ENOSPC || cause == EFBIG || cause == EDQUOT || cause == EIO ||
      cause == EACCES || cause == EROFS;
    std::remove(temporary.c_str());
    error = "cannot write '" + path + "'" + (known ? ": " + std::string(std::strerror(cause)) : "");
    return false;
  }
  return true;
}
}

std::string OutputNameProblem(const std::string& path, const std::string& option)
{
  const std::string full = vtksys::SystemTools::CollapseFullPath(path);
  const std::string directory = vtksys::SystemTools::GetFilenamePath(full);
  errno = 0;
  const long limit = ::pathconf(directory.c_str(), _PC_NAME_MAX);
  const std::size_t longest = limit > 0 ? static_cast<std::size_t>(limit) : 255;
  const std::size_t name = vtksys::SystemTools::GetFilenameName(full).size();
  const std::size_t temporary = vtksys::SystemTools::GetFilenameName(TemporaryName(full)).size();
  if (temporary <= longest)
  {
    return std::string();
  }
  return "the file name of " + option + " is too long: " + std::to_string(name) + " bytes, " +
    std::to_string(temporary) + " with the suffix of its temporary (.part-PID" + Extension(path) +
    "), more than the " + std::to_string(longest) + " bytes a name may have here";
}

bool WriteImage(vtkImageData* image, const std::string& path, const PngWindow& window,
  std::string& error, const BeforeRename& beforeRename)
{
  const std::string ext = Extension(path);
  if (!IsSupportedOutput(path))
  {
    error = "unknown output format '" + ext + "' (expected .vti, .mha, .png or .pfm)";
    return false;
  }
  return WriteAtomically(
    path,
    [&](const std::string& temporary)
    {
      if (ext == ".vti")
      {
        vtkNew<vtkXMLImageDataWriter> writer;
        writer->SetInputData(image);
        writer->SetFileName(temporary.c_str());
        writer->SetDataModeToAppended();
        writer->SetCompressorTypeToZLib();
        return writer->Write() == 1 && writer->GetErrorCode() == 0;
      }
      if (ext == ".mha")
      {
        // One file, header and float64 data; no field data (the matrices:
        // --output-geometry).
        vtkNew<vtkMetaImageWriter> writer;
        writer->SetInputData(image);
        writer->SetFileName(temporary.c_str());
        writer->SetCompression(false);
        writer->Write();
        return writer->GetErrorCode() == 0;
      }
      return ext == ".png" ? WritePNG(image, temporary, window) : WritePFM(image, temporary);
    },
    error, beforeRename);
}

bool WriteFileAtomically(
  const std::string& path, const std::function<bool(const std::string&)>& write, std::string& error)
{
  return WriteAtomically(path, write, error);
}

bool WriteScreenshot(vtkImageData* image, const std::string& path, std::string& error)
{
  if (Extension(path) != ".png")
  {
    error = "a screenshot is written as .png, not '" + path + "'";
    return false;
  }
  return WriteAtomically(
    path,
    [&](const std::string& temporary)
    {
      vtkNew<vtkPNGWriter> writer;
      writer->SetInputData(image);
      writer->SetFileName(temporary.c_str());
      return WritePNGQuietly(writer);
    },
    error);
}

} // namespace mcxapp
