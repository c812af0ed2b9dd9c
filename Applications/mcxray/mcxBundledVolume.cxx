// Where the bundled CT lies (mcxBundledVolume.h).
#include "mcxBundledVolume.h"

#include "vtksys/SystemTools.hxx"

namespace mcxapp
{

std::string BundledVolumePath()
{
  const std::string installed = vtksys::SystemTools::CollapseFullPath(
    std::string(MCXRAY_INSTALLED_DATA_DIR) + "/ct_head_headsq.vti");
  if (vtksys::SystemTools::FileExists(installed, true))
  {
    return installed;
  }
  return std::string(MCXRAY_SOURCE_DATA_DIR) + "/ct_head_headsq.vti";
}

} // namespace mcxapp
