#include "mcxPreflight.h"

#include "mcxFail.h"
#include "mcxHeaderCheck.h"
#include "mcxTransferFunctionSpec.h"

#include "vtkPiecewiseFunction.h"
#include "vtksys/Directory.hxx"
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
  std::vector<std::string> inputs = { input };
  if (vtksys::SystemTools::FileIsDirectory(input))
  {
    vtksys::Directory folder;
    folder.Load(input);
    for (unsigned long f = 0; f < folder.GetNumberOfFiles(); ++f)
    {
      inputs.push_back(input + "/" + folder.GetFile(f));
    }
  }
  const std::string data = DetachedDataFile(input);
  if (!data.empty())
  {
    inputs.push_back(data);
  }
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
