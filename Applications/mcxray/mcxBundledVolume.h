// Where the real CT bundled with the project lies (the input of mcxray
// render and view when none is given).
#ifndef mcxBundledVolume_h
#define mcxBundledVolume_h

#include <string>

namespace mcxapp
{

/// The real CT bundled with the project (VTK's headsq, quarter resolution):
/// the installed copy where there is one, else the source tree's.
std::string BundledVolumePath();

} // namespace mcxapp

#endif
