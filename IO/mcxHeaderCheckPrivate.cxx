// The helpers the per-format header checks share (mcxHeaderCheckPrivate.h):
// sizes and their messages, and the text headers of MetaImage and NRRD with
// the data files they name.
#include "mcxHeaderCheckPrivate.h"

#include "mcxHeaderCheck.h"

#include "mcxByteSize.h"

#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <sys/stat.h>

namespace mcxio
{
namespace check
{

std::string Lower(std::string text)
{
  std::transform(
    text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

std::string Trim(const std::string& text)
{
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  const std::size_t last = text.find_last_not_of(" \t\r\n");
  return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
}

bool EndsWith(const std::string& text, const std::string& suffix)
{
  const std::string lower = Lower(text);
  return lower.size() >= suffix.size() &&
    lower.compare(lower.size() - suffix.size(), suffix.size(), suffix) == 0;
}

Bytes FileSize(const std::string& path)
{
  return static_cast<Bytes>(vtksys::SystemTools::FileLength(path));
}

bool RegularFile(const std::string& path, const std::string& what, std::string& error)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
  {
    error = (what.empty() ? std::string("it") : what) + " cannot be opened";
    return false;
  }
  if (!S_ISREG(info.st_mode))
  {
    error = (what.empty() ? std::string("it") : what) +
      " is not a regular file (a pipe, device or socket cannot be read as a volume)";
    return false;
  }
  return true;
}

std::string Dimensions(const std::vector<long long>& dims)
{
  std::string text;
  for (std::size_t a = 0; a < dims.size(); ++a)
  {
    text += (a ? "x" : "") + std::to_string(dims[a]);
  }
  return text;
}

// dims' product times elementBytes, without overflow; false (error set)
// for a side below 1 or above LargestSide, or a product beyond 2^63.
bool Product(
  const std::vector<long long>& dims, Bytes elementBytes, Bytes& bytes, std::string& error)
{
  if (dims.empty())
  {
    error = "the header gives no dimensions";
    return false;
  }
  double product = static_cast<double>(elementBytes);
  bytes = elementBytes;
  for (long long side : dims)
  {
    if (side < 1 || side > LargestSide)
    {
      error = "the header's dimensions " + Dimensions(dims) + " are not all between 1 and 2^31";
      return false;
    }
    product *= static_cast<double>(side);
    bytes *= static_cast<Bytes>(side);
  }
  if (elementBytes == 0 || product >= 9.2e18)
  {
    error = "the header's dimensions " + Dimensions(dims) + " overflow";
    return false;
  }
  return true;
}

// Raw data must be all there; compressed data within deflate's ratio.
bool CheckAvailable(Bytes claimed, Bytes available, bool compressed,
  const std::vector<long long>& dims, std::string& error)
{
  if (!compressed && available < claimed)
  {
    error = "truncated: the header claims " + Dimensions(dims) + " voxels (" +
      mcx::DescribeBytes(static_cast<double>(claimed)) + "), the file holds " +
      mcx::DescribeBytes(static_cast<double>(available)) + " of data";
    return false;
  }
  if (compressed && static_cast<double>(claimed) > LargestCompressionRatio * (available + 64.0))
  {
    error = "the header claims " + Dimensions(dims) + " voxels (" +
      mcx::DescribeBytes(static_cast<double>(claimed)) + ") from " +
      mcx::DescribeBytes(static_cast<double>(available)) +
      " of compressed data, more than deflate can hold";
    return false;
  }
  return true;
}

bool ParseIntegers(const std::string& text, std::vector<long long>& values)
{
  std::istringstream in(text);
  long long v = 0;
  values.clear();
  while (in >> v)
  {
    values.push_back(v);
  }
  return in.eof() && !values.empty();
}

// MetaImage: lines up to and including ElementDataFile; NRRD: lines up to
// the first blank line (comments '#' skipped, the magic line first).
bool ReadTextHeader(const std::string& path, bool nrrd, TextHeader& header, std::string& error)
{
  if (!RegularFile(path, std::string(), error))
  {
    return false;
  }
  // At most LargestHeader bytes, whatever the lines (one huge line included).
  std::ifstream file(path, std::ios::binary);
  std::string text(
    static_cast<std::size_t>(std::min<Bytes>(FileSize(path), LargestHeader + 1)), '\0');
  file.read(&text[0], static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(file.gcount()));
  std::istringstream in(text);
  std::string line;
  bool first = true;
  while (std::getline(in, line))
  {
    header.End += line.size() + 1;
    if (header.End > LargestHeader)
    {
      error = "the header is longer than 1 MiB";
      return false;
    }
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    if (line.find('\0') != std::string::npos)
    {
      // VTK's NRRD reader loops forever on one (what fuzzing found).
      error = "the header holds a NUL byte";
      return false;
    }
    if (nrrd && first)
    {
      first = false;
      if (line.compare(0, 4, "NRRD") != 0)
      {
        error = "not a NRRD file (no NRRD magic)";
        return false;
      }
      continue;
    }
    if (nrrd && line.empty())
    {
      return true;
    }
    if (nrrd && line[0] == '#')
    {
      continue;
    }
    const std::size_t separator = line.find(nrrd ? ":" : "=");
    if (separator == std::string::npos)
    {
      continue;
    }
    std::string key = Lower(Trim(line.substr(0, separator)));
    std::string value = line.substr(separator + 1);
    if (nrrd && !value.empty() && value[0] == '=')
    {
      continue; // a key/value pair ("key:=value"), not a field
    }
    header.Fields[key] = Trim(value);
    if (!nrrd && key == "elementdatafile")
    {
      return true;
    }
  }
  if (nrrd)
  {
    return true; // a detached header may end without a blank line
  }
  error = "the MetaImage header has no ElementDataFile";
  return false;
}

// A data file named relative to its header's folder.
std::string Beside(const std::string& header, const std::string& name)
{
  return vtksys::SystemTools::CollapseFullPath(
    name, vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::CollapseFullPath(header)));
}

// A printf pattern with exactly one integer conversion: %d, %Nd or %0Nd
// (N at most two digits) and no other '%'.
static bool IsNumberPattern(const std::string& pattern)
{
  const std::size_t at = pattern.find('%');
  if (at == std::string::npos || pattern.find('%', at + 1) != std::string::npos)
  {
    return false;
  }
  std::size_t i = at + 1;
  if (i < pattern.size() && pattern[i] == '0')
  {
    ++i;
  }
  const std::size_t digits = i;
  while (
    i < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[i])) && i - digits < 2)
  {
    ++i;
  }
  return i < pattern.size() && pattern[i] == 'd';
}

// The files of a printf pattern ("name%03d.raw first last step"), at most
// LargestPatternFiles of them, each of which must exist.
bool PatternFiles(const std::string& header, const std::string& spec,
  std::vector<std::string>& files, std::string& error)
{
  std::istringstream in(spec);
  std::string pattern;
  long long first = 0, last = 0, step = 1;
  in >> pattern >> first >> last;
  if (!(in >> step))
  {
    step = 1;
  }
  // Numbers within int (what %d prints), so that the count cannot overflow.
  const bool small = first >= INT_MIN && first <= INT_MAX && last >= INT_MIN && last <= INT_MAX &&
    step >= INT_MIN && step <= INT_MAX;
  const long long count = small && step != 0 ? (last - first) / step + 1 : 0;
  if (count < 1 || count > LargestPatternFiles || !IsNumberPattern(pattern))
  {
    error = "the file-name pattern '" + spec + "' is not a bounded list of numbered files";
    return false;
  }
  files.clear();
  for (long long i = 0; i < count; ++i)
  {
    char name[4096];
    std::snprintf(name, sizeof(name), pattern.c_str(), static_cast<int>(first + i * step));
    files.push_back(Beside(header, name));
    if (!vtksys::SystemTools::FileExists(files.back(), true))
    {
      error = "the data file '" + files.back() + "' is missing";
      return false;
    }
    if (!RegularFile(files.back(), "the data file '" + files.back() + "'", error))
    {
      return false;
    }
  }
  return true;
}

// The sizes of a pattern's files added up (PatternFiles), or false.
static bool PatternSize(
  const std::string& header, const std::string& spec, Bytes& total, std::string& error)
{
  std::vector<std::string> files;
  if (!PatternFiles(header, spec, files, error))
  {
    return false;
  }
  total = 0;
  for (const std::string& file : files)
  {
    total += FileSize(file);
  }
  return true;
}

// The data file field of a header's fields: NRRD spells it two ways.
std::string DataFileField(std::map<std::string, std::string>& fields, bool nrrd)
{
  return nrrd ? (fields.count("data file") ? fields["data file"] : fields["datafile"])
              : fields["elementdatafile"];
}

// The bytes of voxel data a text header's data field gives: after the
// header itself (data empty), in the files of a pattern, or in one data
// file beside the header; a list is refused with listRefusal.
bool AvailableData(const std::string& path, const TextHeader& header, const std::string& data,
  const char* listRefusal, Bytes& available, std::string& error)
{
  if (data.empty())
  {
    const Bytes file = FileSize(path);
    available = file > header.End ? file - header.End : 0;
    return true;
  }
  if (Lower(data).compare(0, 4, "list") == 0)
  {
    error = listRefusal;
    return false;
  }
  if (data.find('%') != std::string::npos)
  {
    return PatternSize(path, data, available, error);
  }
  const std::string file = Beside(path, data);
  if (!vtksys::SystemTools::FileExists(file, true))
  {
    error = "the data file '" + file + "' is missing";
    return false;
  }
  if (!RegularFile(file, "the data file '" + file + "'", error))
  {
    return false;
  }
  available = FileSize(file);
  return true;
}

} // namespace check
} // namespace mcxio
