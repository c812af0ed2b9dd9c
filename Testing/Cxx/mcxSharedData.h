// The real volumes of ../shared/data (MCXRAY_DATA_DIR) and tools a test
// needs: a missing one skips the test on a developer's machine, but fails it
// in CI and wherever the data were asked for, so that a skip cannot pass
// for a success.
#ifndef mcxSharedData_h
#define mcxSharedData_h

#include "vtksys/SystemTools.hxx"

#include <cstdlib>
#include <string>

namespace mcxtest
{

/// The folder of the shared volumes: $MCXRAY_DATA_DIR if set, else the
/// build's MCXRAY_DATA_DIR.
inline std::string SharedDataDirectory()
{
  const char* environment = std::getenv("MCXRAY_DATA_DIR");
  return environment && *environment ? std::string(environment)
                                     : std::string(MCXRAY_SHARED_DATA_DIR);
}

inline std::string SharedDataPath(const std::string& name)
{
  return SharedDataDirectory() + "/" + name;
}

/// Whether a missing file fails (true, with the reason) or skips.
inline bool SharedDataRequired(std::string& why)
{
  const char* ci = std::getenv("CI");
  const char* environment = std::getenv("MCXRAY_DATA_DIR");
  if (ci && std::string(ci) == "true")
  {
    why = "CI=true";
  }
  else if (environment && *environment)
  {
    why = "the environment sets MCXRAY_DATA_DIR";
  }
  else if (MCXRAY_REQUIRE_DATA)
  {
    why = "the build requires it (MCXRAY_REQUIRE_DATA=ON)";
  }
  return !why.empty();
}
}

/// Skips the test when `available` is false, or fails it when the data are
/// required; `what` names the missing file or tool.
#define MCXTEST_NEED(available, what)                                                              \
  do                                                                                               \
  {                                                                                                \
    if (!(available))                                                                              \
    {                                                                                              \
      std::string mcxtestWhy;                                                                      \
      if (mcxtest::SharedDataRequired(mcxtestWhy))                                                 \
      {                                                                                            \
        FAIL() << "missing: " << (what) << " (required: " << mcxtestWhy                            \
               << "; see README.md, Testing)";                                                     \
      }                                                                                            \
      GTEST_SKIP() << "missing: " << (what)                                                        \
                   << " (skipped here; it fails in CI or when MCXRAY_DATA_DIR is given)";          \
    }                                                                                              \
  } while (false)

/// MCXTEST_NEED for a file of the shared data.
#define MCXTEST_NEED_FILE(path) MCXTEST_NEED(vtksys::SystemTools::FileExists(path), path)

#endif
