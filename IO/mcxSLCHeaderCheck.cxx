// The header check of SLC files (.slc): the magic number, 8 bits per voxel
// and dimensions the file can hold, run-length encoded at best
// (mcxHeaderCheck.h).
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mcxio
{
using namespace check;

bool CheckSLCHeader(const std::string& path, Bytes& claimed, std::string& error)
{
  if (!RegularFile(path, std::string(), error))
  {
    return false;
  }
  // The header's numbers lie in its first line: 4 KiB bound what a token
  // may grow to (a file of one long run of digits would otherwise be read
  // whole into one number's text).
  std::ifstream file(path, std::ios::binary);
  std::string head(4096, '\0');
  file.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(file.gcount()));
  std::istringstream in(head);
  long long magic = 0, bits = 0;
  std::vector<long long> dims(3, 0);
  in >> magic >> dims[0] >> dims[1] >> dims[2] >> bits;
  if (!in || magic != 11111)
  {
    error = "not an SLC file (no magic number 11111)";
    return false;
  }
  if (bits != 8)
  {
    error = "the SLC header's " + std::to_string(bits) + " bits per voxel are not supported (8)";
    return false;
  }
  if (!Product(dims, 1, claimed, error))
  {
    return false;
  }
  // Slices may be run-length encoded (at most 127 voxels from 2 bytes).
  return CheckAvailable(claimed, FileSize(path) * 64, false, dims, error);
}

} // namespace mcxio
