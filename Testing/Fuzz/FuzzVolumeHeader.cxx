// libFuzzer target: the header checks of every volume format (and the
// detached-header data file lookup) on arbitrary bytes. The first byte
// picks the file's extension; the rest is the file.
#include "mcxHeaderCheck.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 1)
  {
    return 0;
  }
  static const char* const extensions[] = { ".nii", ".nii.gz", ".mha", ".mhd", ".nrrd", ".nhdr",
    ".vtk", ".slc", ".vti" };
  const std::string path = "/tmp/mcxray-fuzz-header-" + std::to_string(::getpid()) +
    extensions[data[0] % (sizeof(extensions) / sizeof(extensions[0]))];
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  unsigned long long claimed = 0;
  std::string error;
  const bool valid = mcxio::CheckVolumeHeader(path, claimed, error);
  if (!valid && error.empty())
  {
    __builtin_trap(); // a refusal must say why (Fail makes it one line)
  }
  mcxio::DataFiles(path);
  std::remove(path.c_str());
  return 0;
}
