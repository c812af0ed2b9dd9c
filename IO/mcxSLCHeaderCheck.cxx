// The check of SLC files (.slc): the whole file walked as vtkSLCReader
// (VTK 9.1) walks it, with the same scanf conversions, so that the check
// and the reader agree on every number: the magic number, 8 bits per
// voxel, dimensions whose slices fit the reader's int arithmetic, the icon
// it reads three times, and every slice present; a run-length encoded
// slice must decode to exactly one slice inside its stated size. The reader
// trusts all of these (a run that overflows its slice corrupts the heap; a
// slice that ends early leaves uninitialised voxels) (mcxHeaderCheck.h).
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include <cctype>
#include <climits>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace mcxio
{
using namespace check;

namespace
{
struct FileCloser
{
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// Skips count bytes; false when the file ends first.
bool Skip(std::FILE* in, long long count)
{
  for (long long i = 0; i < count; ++i)
  {
    if (std::getc(in) == EOF)
    {
      return false;
    }
  }
  return true;
}

// True when the next count numbers from the file's position (separated by
// whitespace or the format's "X") each have at most 64 characters, read from at most 4 KiB, the
// position kept: scanf would otherwise gather a run of a billion digits
// into one number's text (its buffer grows with it), as the reader's would.
bool ShortTokensAhead(std::FILE* in, int count)
{
  const long at = std::ftell(in);
  char text[4096];
  const std::size_t got = std::fread(text, 1, sizeof(text), in);
  std::fseek(in, at, SEEK_SET);
  std::size_t i = 0;
  for (int token = 0; token < count; ++token)
  {
    while (i < got && std::isspace(static_cast<unsigned char>(text[i])))
    {
      ++i;
    }
    const std::size_t start = i;
    while (i < got && !std::isspace(static_cast<unsigned char>(text[i])) && text[i] != 'X')
    {
      ++i;
    }
    if (i - start > 64 || (i == got && got == sizeof(text)))
    {
      return false;
    }
  }
  return true;
}

// Decodes one run-length encoded slice of compressedSize bytes as
// vtkSLCReader::Decode8BitData does (a byte's low 7 bits count the run;
// the high bit: that many literal bytes follow, else one value repeated;
// a count of 0 ends the slice), without writing: the runs must give
// exactly planeSize voxels and end inside the slice's bytes.
bool CheckRunLengthSlice(
  std::FILE* in, long long compressedSize, long long planeSize, long long z, std::string& error)
{
  long long read = 0, voxels = 0;
  const std::string slice = "the SLC file's run-length encoded slice " + std::to_string(z);
  while (true)
  {
    if (read >= compressedSize)
    {
      error = slice + " does not end within its " + std::to_string(compressedSize) + " bytes";
      return false;
    }
    const int code = std::getc(in);
    ++read;
    if (code == EOF)
    {
      error = slice + " is cut short";
      return false;
    }
    const long long run = code & 0x7f;
    if (run == 0)
    {
      break;
    }
    const long long bytes = (code & 0x80) ? run : 1;
    if (voxels + run > planeSize || read + bytes > compressedSize || !Skip(in, bytes))
    {
      error = slice +
        (voxels + run > planeSize ? " decodes to more voxels than a slice holds" : " is cut short");
      return false;
    }
    read += bytes;
    voxels += run;
  }
  if (voxels != planeSize)
  {
    error = slice + " decodes to " + std::to_string(voxels) + " of its " +
      std::to_string(planeSize) + " voxels";
    return false;
  }
  return Skip(in, compressedSize - read) || (error = slice + " is cut short", false);
}

// The slices after the header: raw (compression 0) or run-length encoded.
bool CheckSlices(
  std::FILE* in, int compression, long long planeSize, long long slices, std::string& error)
{
  for (long long z = 0; z < slices; ++z)
  {
    if (compression == 0)
    {
      if (!Skip(in, planeSize))
      {
        error = "truncated: the SLC file ends in slice " + std::to_string(z) + " of " +
          std::to_string(slices);
        return false;
      }
      continue;
    }
    int compressedSize = 0;
    if (!ShortTokensAhead(in, 1) || std::fscanf(in, "%d X", &compressedSize) != 1 ||
      compressedSize < 1)
    {
      error = "the SLC file's slice " + std::to_string(z) + " of " + std::to_string(slices) +
        " has no positive compressed size";
      return false;
    }
    if (!CheckRunLengthSlice(in, compressedSize, planeSize, z, error))
    {
      return false;
    }
  }
  return true;
}
}

bool CheckSLCHeader(const std::string& path, Bytes& claimed, std::string& error)
{
  if (!RegularFile(path, std::string(), error))
  {
    return false;
  }
  File file(std::fopen(path.c_str(), "rb"));
  std::FILE* in = file.get();
  int magic = 0, bits = 0, size[3] = { 0, 0, 0 }, unit = 0, origin = 0, modified = 0;
  int compression = -1, iconWidth = 0, iconHeight = 0;
  double spacing[3] = { 0, 0, 0 };
  // The header's 14 numbers: magic, sizes, bits, spacing, units, origin,
  // modification, compression and icon size (its "X" and bytes follow).
  if (in && !ShortTokensAhead(in, 14))
  {
    error = "the SLC header holds a token longer than 64 characters or exceeds 4 KiB";
    return false;
  }
  if (!in || std::fscanf(in, "%d", &magic) != 1 || magic != 11111)
  {
    error = "not an SLC file (no magic number 11111)";
    return false;
  }
  if (std::fscanf(in, "%d %d %d %d", size, size + 1, size + 2, &bits) != 4)
  {
    error = "the SLC header's dimensions are not three integers and bits per voxel";
    return false;
  }
  if (bits != 8)
  {
    error = "the SLC header's " + std::to_string(bits) + " bits per voxel are not supported (8)";
    return false;
  }
  const std::vector<long long> dims = { size[0], size[1], size[2] };
  if (!Product(dims, 1, claimed, error))
  {
    return false;
  }
  const long long planeSize = static_cast<long long>(size[0]) * size[1];
  if (planeSize > INT_MAX)
  {
    error = "the SLC header's slices of " + Dimensions(dims) + " voxels exceed 2^31 voxels";
    return false;
  }
  if (std::fscanf(in, "%lf %lf %lf %d %d %d %d\n", spacing, spacing + 1, spacing + 2, &unit,
        &origin, &modified, &compression) != 7 ||
    (compression != 0 && compression != 1))
  {
    error = "the SLC header's spacing, units or compression (0 or 1) cannot be read";
    return false;
  }
  // The icon: read three times (red, green, blue planes) before the slices.
  if (std::fscanf(in, "%d %d X", &iconWidth, &iconHeight) != 2 || iconWidth < 1 || iconHeight < 1 ||
    static_cast<long long>(iconWidth) * iconHeight > INT_MAX / 3 ||
    !Skip(in, 3LL * iconWidth * iconHeight))
  {
    error = "the SLC file's icon has no positive size or is cut short";
    return false;
  }
  return CheckSlices(in, compression, planeSize, size[2], error);
}

} // namespace mcxio
