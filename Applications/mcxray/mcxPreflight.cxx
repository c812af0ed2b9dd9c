#include "mcxPreflight.h"

#include "mcxFail.h"
#include "mcxTransferFunctionSpec.h"
#include "mcxVolumeReader.h"

#include "vtkPiecewiseFunction.h"
#include "vtksys/SystemTools.hxx"

#include <vector>

#include <sys/stat.h>

namespace mcxapp
{

namespace
{
bool SameFile(const struct stat& a, const std::string& path)
{
  struct stat b;
  return ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}
}

void CheckOutputIsNotInput(
  const std::string& output, const std::string& input, const std::string& option)
{
  struct stat written;
  if (::stat(output.c_str(), &written) != 0)
  {
    return; // not there yet: it cannot be the input
  }
  // Exactly what the read may open, as the reader decides it.
  const std::vector<std::string> inputs = mcxio::InputFiles(input);
  for (const std::string& file : inputs)
  {
    if (SameFile(written, file))
    {
      Fail("the output '" + output + "' is the input" +
        (file == input ? std::string() : " volume's file '" + file + "'") +
        "; refusing to overwrite it (choose another " + option + ")");
    }
  }
}

void CheckOutputDirectory(const std::string& path)
{
  const std::string directory =
    vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::CollapseFullPath(path));
  if (!vtksys::SystemTools::FileIsDirectory(directory) ||
    !vtksys::SystemTools::TestFileAccess(directory, vtksys::TEST_FILE_WRITE))
  {
    Fail("cannot write '" + path + "': directory '" + directory + "' is missing or not writable");
  }
  if (vtksys::SystemTools::FileIsDirectory(path))
  {
    Fail("cannot write '" + path + "': it is a directory");
  }
  // The image is written beside the output and renamed over it: over a
  // device, pipe or socket (/dev/null, /dev/stdout's link, a FIFO) that
  // would replace the node itself, as root even /dev's.
  struct stat info;
  if (::stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode))
  {
    Fail("cannot write '" + path +
      "': it is not a regular file (a device, pipe or socket); refusing to replace it");
  }
}

// Whether a spec parses does not depend on the data range, so any range will do.
void CheckTransferFunction(const std::string& spec)
{
  const double probeRange[2] = { 0.0, 1.0 };
  std::string error;
  if (!MakeTransferFunction(spec, probeRange, error))
  {
    Fail(error);
  }
}

} // namespace mcxapp
