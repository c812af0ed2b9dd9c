// The header check of NIfTI-1 and NIfTI-2 files (.nii, and gzipped .nii.gz:
// the stream is decompressed to count its bytes): sizeof_hdr, dim, datatype
// and vox_offset against the bytes the file holds (mcxHeaderCheck.h).
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include "vtk_zlib.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

namespace mcxio
{
using namespace check;

namespace
{
template <typename T>
T Field(const unsigned char* header, std::size_t offset, bool swap)
{
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, header + offset, sizeof(T));
  if (swap)
  {
    std::reverse(raw, raw + sizeof(T));
  }
  T value;
  std::memcpy(&value, raw, sizeof(T));
  return value;
}

Bytes NiftiElementBytes(int datatype)
{
  switch (datatype)
  {
    case 2:
    case 256:
      return 1; // uint8, int8
    case 4:
    case 512:
      return 2; // int16, uint16
    case 8:
    case 16:
    case 768:
      return 4; // int32, float32, uint32
    case 64:
    case 1024:
    case 1280:
      return 8; // float64, int64, uint64
    case 128:
      return 3; // RGB24
    case 2304:
      return 4; // RGBA32
    case 32:
      return 8; // complex64
    case 1792:
      return 16; // complex128
    default:
      return 0;
  }
}

// The uncompressed size of a gzip stream, counted up to limit + 1 bytes.
Bytes GzipLength(const std::string& path, Bytes limit)
{
  gzFile in = gzopen(path.c_str(), "rb");
  if (!in)
  {
    return 0;
  }
  std::vector<char> buffer(1 << 20);
  Bytes total = 0;
  int n = 0;
  while (
    total <= limit && (n = gzread(in, buffer.data(), static_cast<unsigned>(buffer.size()))) > 0)
  {
    total += static_cast<Bytes>(n);
  }
  gzclose(in);
  return total;
}

// The first 540 bytes of the file (decompressed): how many were read, and
// zlib's complaint about a gzip stream that ended or broke before them.
int ReadHeaderBytes(
  const std::string& path, bool compressed, unsigned char (&header)[540], std::string& broken)
{
  if (compressed)
  {
    gzFile in = gzopen(path.c_str(), "rb");
    const int got = in ? gzread(in, header, sizeof(header)) : -1;
    if (in)
    {
      int code = Z_OK;
      const char* message = gzerror(in, &code);
      broken = code != Z_OK && code != Z_STREAM_END && message ? message : "";
      if (broken.compare(0, path.size() + 2, path + ": ") == 0)
      {
        broken.erase(0, path.size() + 2); // zlib names the file, the message does already
      }
      gzclose(in);
    }
    return got;
  }
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(header), sizeof(header));
  return static_cast<int>(in.gcount());
}
}

bool CheckNiftiHeader(const std::string& path, Bytes& claimed, std::string& error)
{
  claimed = 0;
  if (!RegularFile(path, std::string(), error))
  {
    return false;
  }
  const bool compressed = EndsWith(path, ".gz");
  unsigned char header[540] = { 0 };
  std::string broken;
  const int got = ReadHeaderBytes(path, compressed, header, broken);
  if (got < 348)
  {
    error = broken.empty() ? "not a NIfTI file (shorter than its 348-byte header)"
                           : "its gzip stream is truncated or corrupt (zlib: " + broken + ")";
    return false;
  }
  const int size = Field<std::int32_t>(header, 0, false);
  const bool swap = size != 348 && size != 540;
  const int version = Field<std::int32_t>(header, 0, swap) == 348 ? 1 : 2;
  if (Field<std::int32_t>(header, 0, swap) != (version == 1 ? 348 : 540) ||
    (version == 2 && got < 540))
  {
    error = "not a NIfTI file (sizeof_hdr is neither 348 nor 540)";
    return false;
  }
  std::vector<long long> dims;
  long long rank = 0;
  int datatype = 0;
  double offset = 0;
  if (version == 1)
  {
    rank = Field<std::int16_t>(header, 40, swap);
    for (long long a = 1; a <= std::min<long long>(rank, 7); ++a)
    {
      dims.push_back(Field<std::int16_t>(header, 40 + 2 * static_cast<std::size_t>(a), swap));
    }
    datatype = Field<std::int16_t>(header, 70, swap);
    offset = Field<float>(header, 108, swap);
  }
  else
  {
    rank = Field<std::int64_t>(header, 16, swap);
    for (long long a = 1; a <= std::min<long long>(rank, 7); ++a)
    {
      dims.push_back(Field<std::int64_t>(header, 16 + 8 * static_cast<std::size_t>(a), swap));
    }
    datatype = Field<std::int16_t>(header, 12, swap);
    offset = static_cast<double>(Field<std::int64_t>(header, 168, swap));
  }
  if (rank < 1 || rank > 7)
  {
    error = "the NIfTI header's dim[0] is " + std::to_string(rank) + " (expected 1 to 7)";
    return false;
  }
  if (rank >= 4 && dims[3] > 1)
  {
    error = "the NIfTI file holds " + std::to_string(dims[3]) +
      " volumes along dim[4] (a time series): extract the one to render first";
    return false;
  }
  const double scale[2] = { version == 1 ? Field<float>(header, 112, swap)
                                         : Field<double>(header, 176, swap),
    version == 1 ? Field<float>(header, 116, swap) : Field<double>(header, 184, swap) };
  if (!std::isfinite(scale[0]) || !std::isfinite(scale[1]))
  {
    error = "the NIfTI header's scl_slope or scl_inter is not a finite number";
    return false;
  }
  const Bytes element = NiftiElementBytes(datatype);
  if (element == 0)
  {
    error = "the NIfTI header's datatype " + std::to_string(datatype) + " is unknown";
    return false;
  }
  if (!Product(dims, element, claimed, error))
  {
    return false;
  }
  if (!(offset >= (version == 1 ? 348 : 540)) || !std::isfinite(offset) || offset > 1e15)
  {
    error = "the NIfTI header's vox_offset is not past the header";
    return false;
  }
  const Bytes start = static_cast<Bytes>(offset);
  if (!compressed)
  {
    const Bytes file = FileSize(path);
    return CheckAvailable(claimed, file > start ? file - start : 0, false, dims, error);
  }
  if (!CheckAvailable(claimed, FileSize(path), true, dims, error))
  {
    return false;
  }
  const Bytes length = GzipLength(path, start + claimed);
  return CheckAvailable(claimed, length > start ? length - start : 0, false, dims, error);
}

} // namespace mcxio
