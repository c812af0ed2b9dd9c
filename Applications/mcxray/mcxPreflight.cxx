#include "mcxPreflight.h"

#include "mcxFail.h"
#include "mcxTransferFunctionSpec.h"

#include "vtkPiecewiseFunction.h"
#include "vtksys/SystemTools.hxx"

namespace mcxapp
{

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
