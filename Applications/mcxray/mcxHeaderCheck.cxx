#include "mcxHeaderCheck.h"

#include "mcxByteSize.h"

#include "vtk_zlib.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include <sys/stat.h>

namespace mcxapp
{

namespace
{
using Bytes = unsigned long long;

// Headers are text of bounded length: a line or header longer than these is
// not one of ours.
const std::size_t LargestHeader = 1 << 20;
const long long LargestSide = 1LL << 31;      // voxels along one axis
const long long LargestPatternFiles = 100000; // files a name pattern or list may name

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
bool Product(const std::vector<long long>& dims, Bytes elementBytes, Bytes& bytes, std::string& error)
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
bool CheckAvailable(Bytes claimed, Bytes available, bool compressed, const std::vector<long long>& dims,
  std::string& error)
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

// ---- NIfTI-1 and NIfTI-2 ----

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
    case 2: case 256: return 1;                    // uint8, int8
    case 4: case 512: return 2;                    // int16, uint16
    case 8: case 16: case 768: return 4;           // int32, float32, uint32
    case 64: case 1024: case 1280: return 8;       // float64, int64, uint64
    case 128: return 3;                            // RGB24
    case 2304: return 4;                           // RGBA32
    case 32: return 8;                             // complex64
    case 1792: return 16;                          // complex128
    default: return 0;
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
  while (total <= limit && (n = gzread(in, buffer.data(), static_cast<unsigned>(buffer.size()))) > 0)
  {
    total += static_cast<Bytes>(n);
  }
  gzclose(in);
  return total;
}

bool CheckNifti(const std::string& path, Bytes& claimed, std::string& error)
{
  const bool compressed = EndsWith(path, ".gz");
  unsigned char header[540] = { 0 };
  int got = 0;
  if (compressed)
  {
    gzFile in = gzopen(path.c_str(), "rb");
    got = in ? gzread(in, header, sizeof(header)) : -1;
    if (in)
    {
      gzclose(in);
    }
  }
  else
  {
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(header), sizeof(header));
    got = static_cast<int>(in.gcount());
  }
  if (got < 348)
  {
    error = "not a NIfTI file (shorter than its 348-byte header)";
    return false;
  }
  const int size = Field<std::int32_t>(header, 0, false);
  const bool swap = size != 348 && size != 540;
  const int version = Field<std::int32_t>(header, 0, swap) == 348 ? 1 : 2;
  if (Field<std::int32_t>(header, 0, swap) != (version == 1 ? 348 : 540) || (version == 2 && got < 540))
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

// ---- "key = value" (MetaImage) and "key: value" (NRRD) headers ----

struct TextHeader
{
  std::map<std::string, std::string> Fields; // keys in lower case
  Bytes End = 0;                              // where the data of an attached header begin
};

// MetaImage: lines up to and including ElementDataFile; NRRD: lines up to
// the first blank line (comments '#' skipped, the magic line first).
bool ReadTextHeader(const std::string& path, bool nrrd, TextHeader& header, std::string& error)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode))
  {
    error = "not a regular file"; // a FIFO, say, would block the reading
    return false;
  }
  // At most LargestHeader bytes, whatever the lines (one huge line included).
  std::ifstream file(path, std::ios::binary);
  std::string text(static_cast<std::size_t>(std::min<Bytes>(FileSize(path), LargestHeader + 1)), '\0');
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
bool IsNumberPattern(const std::string& pattern)
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
  while (i < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[i])) && i - digits < 2)
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
  }
  return true;
}

// The sizes of a pattern's files added up (PatternFiles), or false.
bool PatternSize(const std::string& header, const std::string& spec, Bytes& total, std::string& error)
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
  available = FileSize(file);
  return true;
}

Bytes MetaElementBytes(const std::string& type)
{
  static const std::map<std::string, Bytes> sizes = { { "met_uchar", 1 }, { "met_char", 1 },
    { "met_ushort", 2 }, { "met_short", 2 }, { "met_uint", 4 }, { "met_int", 4 },
    { "met_ulong", 8 }, { "met_long", 8 }, { "met_ulong_long", 8 }, { "met_long_long", 8 },
    { "met_float", 4 }, { "met_double", 8 } };
  const auto found = sizes.find(Lower(type));
  return found == sizes.end() ? 0 : found->second;
}

bool CheckMetaImage(const std::string& path, Bytes& claimed, std::string& error)
{
  TextHeader header;
  if (!ReadTextHeader(path, false, header, error))
  {
    return false;
  }
  std::map<std::string, std::string>& f = header.Fields;
  std::vector<long long> dims, channels, rank;
  if (!ParseIntegers(f["ndims"], rank) || rank.size() != 1 || rank[0] < 1 || rank[0] > 4)
  {
    error = "the MetaImage header's NDims is not 1 to 4";
    return false;
  }
  if (!ParseIntegers(f["dimsize"], dims) || static_cast<long long>(dims.size()) != rank[0])
  {
    error = "the MetaImage header's DimSize does not give NDims sizes";
    return false;
  }
  const Bytes element = MetaElementBytes(f["elementtype"]);
  if (element == 0)
  {
    error = "the MetaImage header's ElementType '" + f["elementtype"] + "' is unknown";
    return false;
  }
  if (f.count("elementnumberofchannels") &&
    (!ParseIntegers(f["elementnumberofchannels"], channels) || channels.size() != 1 ||
      channels[0] < 1 || channels[0] > 64))
  {
    error = "the MetaImage header's ElementNumberOfChannels is not 1 to 64";
    return false;
  }
  if (!Product(dims, element * static_cast<Bytes>(channels.empty() ? 1 : channels[0]), claimed, error))
  {
    return false;
  }
  const bool compressed = Lower(f["compresseddata"]) == "true";
  const std::string data = DataFileField(f, false);
  if (data.empty())
  {
    error = "the MetaImage header's ElementDataFile is empty";
    return false;
  }
  const bool local = Lower(data) == "local";
  Bytes available = 0;
  if (!AvailableData(path, header, local ? std::string() : data,
        "MetaImage file lists (ElementDataFile = LIST) are not supported", available, error))
  {
    return false;
  }
  std::vector<long long> skip;
  if (!local && data.find('%') == std::string::npos && ParseIntegers(f["headersize"], skip) &&
    skip.size() == 1 && skip[0] > 0)
  {
    available = available > static_cast<Bytes>(skip[0]) ? available - skip[0] : 0;
  }
  return CheckAvailable(claimed, available, compressed, dims, error);
}

Bytes NrrdElementBytes(const std::string& type)
{
  static const std::map<std::string, Bytes> sizes = { { "signed char", 1 }, { "int8", 1 },
    { "int8_t", 1 }, { "uchar", 1 }, { "unsigned char", 1 }, { "uint8", 1 }, { "uint8_t", 1 },
    { "short", 2 }, { "short int", 2 }, { "signed short", 2 }, { "signed short int", 2 },
    { "int16", 2 }, { "int16_t", 2 }, { "ushort", 2 }, { "unsigned short", 2 },
    { "unsigned short int", 2 }, { "uint16", 2 }, { "uint16_t", 2 }, { "int", 4 },
    { "signed int", 4 }, { "int32", 4 }, { "int32_t", 4 }, { "uint", 4 }, { "unsigned int", 4 },
    { "uint32", 4 }, { "uint32_t", 4 }, { "longlong", 8 }, { "long long", 8 },
    { "long long int", 8 }, { "signed long long", 8 }, { "signed long long int", 8 },
    { "int64", 8 }, { "int64_t", 8 }, { "ulonglong", 8 }, { "unsigned long long", 8 },
    { "unsigned long long int", 8 }, { "uint64", 8 }, { "uint64_t", 8 }, { "float", 4 },
    { "double", 8 } };
  const auto found = sizes.find(Lower(type));
  return found == sizes.end() ? 0 : found->second;
}

bool CheckNrrd(const std::string& path, Bytes& claimed, std::string& error)
{
  TextHeader header;
  if (!ReadTextHeader(path, true, header, error))
  {
    return false;
  }
  std::map<std::string, std::string>& f = header.Fields;
  std::vector<long long> dims, rank;
  if (!ParseIntegers(f["dimension"], rank) || rank.size() != 1 || rank[0] < 1 || rank[0] > 4)
  {
    error = "the NRRD header's dimension is not 1 to 4";
    return false;
  }
  if (!ParseIntegers(f["sizes"], dims) || static_cast<long long>(dims.size()) != rank[0])
  {
    error = "the NRRD header's sizes do not give dimension sizes";
    return false;
  }
  const Bytes element = NrrdElementBytes(f["type"]);
  if (element == 0)
  {
    error = "the NRRD header's type '" + f["type"] + "' is unknown";
    return false;
  }
  if (!Product(dims, element, claimed, error))
  {
    return false;
  }
  const std::string encoding = Lower(f["encoding"]);
  const bool compressed = encoding == "gzip" || encoding == "gz" || encoding == "bzip2" ||
    encoding == "bz2";
  const bool text = encoding == "ascii" || encoding == "text" || encoding == "txt";
  if (!compressed && !text && encoding != "raw")
  {
    error = "the NRRD encoding '" + f["encoding"] + "' is not supported (raw, ascii or gzip)";
    return false;
  }
  Bytes available = 0;
  if (!AvailableData(path, header, DataFileField(f, true),
        "NRRD data file lists (data file: LIST) are not supported", available, error))
  {
    return false;
  }
  std::vector<long long> skip;
  if (ParseIntegers(f["byte skip"], skip) && skip.size() == 1 && skip[0] > 0)
  {
    available = available > static_cast<Bytes>(skip[0]) ? available - skip[0] : 0;
  }
  // Text: at least one digit and one separator per value (the last one
  // needs none).
  const Bytes needed = text ? claimed / element * 2 - 1 : claimed;
  if (text && available < needed)
  {
    error = "truncated: the header claims " + Dimensions(dims) + " voxels as text, the file holds " +
      mcx::DescribeBytes(static_cast<double>(available));
    return false;
  }
  return text || CheckAvailable(claimed, available, compressed, dims, error);
}

// ---- legacy VTK (structured points) ----

Bytes LegacyElementBytes(const std::string& type)
{
  static const std::map<std::string, Bytes> sizes = { { "bit", 1 }, { "unsigned_char", 1 },
    { "char", 1 }, { "signed_char", 1 }, { "unsigned_short", 2 }, { "short", 2 },
    { "unsigned_int", 4 }, { "int", 4 }, { "unsigned_long", 8 }, { "long", 8 },
    { "vtktypeint64", 8 }, { "vtktypeuint64", 8 }, { "float", 4 }, { "double", 8 } };
  const auto found = sizes.find(Lower(type));
  return found == sizes.end() ? 0 : found->second;
}

// Skips a FIELD block ("FIELD name n", then n arrays "name components
// tuples type" each followed by its values); false when it is malformed or
// longer than the file.
bool SkipFieldData(std::istream& in, bool binary, Bytes fileSize)
{
  std::string name;
  long long arrays = 0;
  if (!(in >> name >> arrays) || arrays < 0 || arrays > 10000)
  {
    return false;
  }
  for (long long a = 0; a < arrays; ++a)
  {
    std::string type;
    long long components = 0, tuples = 0;
    if (!(in >> name >> components >> tuples >> type) || components < 1 || components > 1024 ||
      tuples < 0)
    {
      return false;
    }
    const Bytes element = Lower(type) == "string" ? 1 : LegacyElementBytes(type);
    const double values = static_cast<double>(components) * static_cast<double>(tuples);
    if (element == 0 || values * static_cast<double>(element) > static_cast<double>(fileSize))
    {
      return false;
    }
    if (binary)
    {
      std::string rest;
      std::getline(in, rest); // the end of the array's line
      in.seekg(static_cast<std::streamoff>(values) * static_cast<std::streamoff>(element), std::ios::cur);
    }
    else
    {
      std::string value;
      for (double v = 0; v < values && in >> value; ++v)
      {
      }
    }
    if (!in)
    {
      return false;
    }
  }
  return true;
}

bool CheckLegacy(const std::string& path, Bytes& claimed, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::vector<std::string> lines;
  Bytes consumed = 0;
  // The version line, the title, then (after any blank lines, as VTK's
  // reader allows) ASCII or BINARY.
  while (lines.size() < 3 && consumed < LargestHeader && std::getline(in, line))
  {
    consumed += line.size() + 1;
    if (lines.size() < 2 || !Trim(line).empty())
    {
      lines.push_back(line);
    }
  }
  if (lines.size() < 3 || lines[0].find("vtk DataFile") == std::string::npos)
  {
    error = "not a legacy VTK file (no '# vtk DataFile' line)";
    return false;
  }
  const bool binary = Lower(Trim(lines[2])) == "binary";
  std::vector<long long> dims;
  long long points = -1, components = 1;
  Bytes element = 0;
  std::string keyword;
  while (consumed < LargestHeader && in >> keyword)
  {
    const std::string key = Lower(keyword);
    if (key == "dataset")
    {
      std::string type;
      in >> type;
      if (Lower(type) != "structured_points")
      {
        error = "a legacy VTK " + type + " dataset is not a volume (expected STRUCTURED_POINTS)";
        return false;
      }
    }
    else if (key == "dimensions")
    {
      dims.assign(3, 0);
      in >> dims[0] >> dims[1] >> dims[2];
    }
    else if (key == "point_data")
    {
      in >> points;
    }
    else if (key == "scalars")
    {
      std::string name, type;
      in >> name >> type;
      element = LegacyElementBytes(type);
      std::getline(in, line);
      std::vector<long long> n;
      if (ParseIntegers(line, n) && n.size() == 1)
      {
        components = n[0];
      }
    }
    else if (key == "lookup_table")
    {
      std::getline(in, line);
      break; // the data follow
    }
    else if (key == "field" && dims.empty())
    {
      // VTK's writer puts field data (TimeValue, say) before DIMENSIONS.
      if (!SkipFieldData(in, binary, FileSize(path)))
      {
        error = "the legacy VTK file's FIELD data are malformed or longer than the file";
        return false;
      }
    }
    else if (key == "vectors" || key == "normals" || key == "tensors" || key == "field" ||
      key == "color_scalars" || key == "texture_coordinates" || key == "cell_data")
    {
      // Other data come first (VTK's writer puts FIELD and CELL_DATA before
      // POINT_DATA): the scalars' place is not known without reading
      // those; check the dimensions alone.
      if (dims.size() != 3)
      {
        error = "the legacy VTK header gives no DIMENSIONS before its data";
        return false;
      }
      const bool valid = Product(dims, 1, claimed, error);
      claimed = 0;
      return valid;
    }
    else
    {
      std::getline(in, line); // SPACING, ORIGIN, ASPECT_RATIO, ...
    }
    if (!in)
    {
      error = "the legacy VTK header is cut short";
      return false;
    }
  }
  if (dims.size() != 3 || element == 0 || components < 1 || components > 4)
  {
    error = "the legacy VTK header gives no DIMENSIONS, no known SCALARS type, or not 1 to 4 "
            "components";
    return false;
  }
  if (!Product(dims, element * static_cast<Bytes>(components), claimed, error))
  {
    return false;
  }
  if (points != dims[0] * dims[1] * dims[2])
  {
    error = "the legacy VTK header's POINT_DATA " + std::to_string(points) +
      " is not the product of its DIMENSIONS " + Dimensions(dims);
    return false;
  }
  const std::streamoff at = in.tellg();
  const Bytes file = FileSize(path);
  const Bytes available = at > 0 && file > static_cast<Bytes>(at) ? file - at : 0;
  if (!binary)
  {
    const Bytes values = claimed / element;
    if (available < values * 2 - 1)
    {
      error = "truncated: the header claims " + Dimensions(dims) +
        " voxels as text, the file holds " + mcx::DescribeBytes(static_cast<double>(available));
      return false;
    }
    return true;
  }
  return CheckAvailable(claimed, available, false, dims, error);
}

// ---- SLC ----

bool CheckSLC(const std::string& path, Bytes& claimed, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
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

// ---- VTK XML image data ----

std::string Attribute(const std::string& tag, const std::string& name)
{
  const std::size_t at = tag.find(" " + name + "=\"");
  if (at == std::string::npos)
  {
    return std::string();
  }
  const std::size_t begin = at + name.size() + 3;
  const std::size_t end = tag.find('"', begin);
  return end == std::string::npos ? std::string() : tag.substr(begin, end - begin);
}

Bytes XMLElementBytes(const std::string& type)
{
  static const std::map<std::string, Bytes> sizes = { { "Int8", 1 }, { "UInt8", 1 },
    { "Int16", 2 }, { "UInt16", 2 }, { "Int32", 4 }, { "UInt32", 4 }, { "Int64", 8 },
    { "UInt64", 8 }, { "Float32", 4 }, { "Float64", 8 } };
  const auto found = sizes.find(type);
  return found == sizes.end() ? 0 : found->second;
}

// One header word of raw appended data (UInt32 or UInt64, in the file's
// byte order); false past the end of the file.
bool ReadWord(std::ifstream& in, Bytes at, int size, bool bigEndian, Bytes& word)
{
  unsigned char raw[8] = { 0 };
  in.clear();
  in.seekg(static_cast<std::streamoff>(at));
  in.read(reinterpret_cast<char*>(raw), size);
  if (in.gcount() != size)
  {
    return false;
  }
  word = 0;
  for (int b = 0; b < size; ++b)
  {
    word |= static_cast<Bytes>(raw[bigEndian ? size - 1 - b : b]) << (8 * b);
  }
  return true;
}

// The first array's raw appended data: its size word (uncompressed) or its
// block table (compressed: block count, block size, last block size, then
// each block's compressed size) must describe exactly the claimed bytes and
// fit in the file; a lying table sends VTK's reader into a loop over
// billions of blocks or past its buffers.
bool CheckAppendedData(const std::string& path, const std::string& head, const std::string& tag,
  Bytes claimed, std::string& error)
{
  const std::size_t appended = head.find("<AppendedData");
  std::vector<long long> offset;
  if (Attribute(tag, "format") != "appended" || appended == std::string::npos ||
    Attribute(head.substr(appended, head.find('>', appended) - appended), "encoding") != "raw" ||
    !ParseIntegers(Attribute(tag, "offset"), offset) || offset.size() != 1 || offset[0] < 0)
  {
    return true; // base64 or inline data: bounded by the ratio check alone
  }
  // As VTK reads it: after the tag, whitespace, then one marker character
  // (normally '_'), whatever it is.
  const std::size_t underscore = head.find_first_not_of(" \t\r\n", head.find('>', appended) + 1);
  if (underscore == std::string::npos)
  {
    error = "the image's appended data have no marker";
    return false;
  }
  const std::string file = head.substr(0, head.find('>'));
  const int word = Attribute(file, "header_type") == "UInt64" ? 8 : 4;
  const bool bigEndian = Attribute(file, "byte_order") == "BigEndian";
  const bool compressed = !Attribute(file, "compressor").empty();
  const Bytes size = FileSize(path);
  const Bytes start = underscore + 1 + static_cast<Bytes>(offset[0]);
  std::ifstream in(path, std::ios::binary);
  Bytes first = 0;
  if (!ReadWord(in, start, word, bigEndian, first))
  {
    error = "truncated: the image's appended data end before their header";
    return false;
  }
  if (!compressed)
  {
    if (first != claimed || size - std::min(size, start + word) < claimed)
    {
      error = "the image's appended data hold " + mcx::DescribeBytes(double(first)) +
        " (the file " + mcx::DescribeBytes(double(size - std::min(size, start + word))) +
        ") where its extent needs " + mcx::DescribeBytes(double(claimed));
      return false;
    }
    return true;
  }
  Bytes blockSize = 0, lastSize = 0;
  const Bytes blocks = first;
  if (!ReadWord(in, start + word, word, bigEndian, blockSize) ||
    !ReadWord(in, start + 2 * word, word, bigEndian, lastSize) || blocks > size / word)
  {
    error = "truncated: the image's compressed data end inside their block table";
    return false;
  }
  const double total = blocks == 0
    ? 0.0
    : static_cast<double>(blocks - 1) * blockSize + static_cast<double>(lastSize ? lastSize : blockSize);
  if (total != static_cast<double>(claimed))
  {
    error = "the image's compressed blocks hold " + mcx::DescribeBytes(total) +
      " where its extent needs " + mcx::DescribeBytes(double(claimed));
    return false;
  }
  Bytes compressedTotal = 0;
  for (Bytes b = 0; b < blocks; ++b)
  {
    Bytes block = 0;
    if (!ReadWord(in, start + (3 + b) * word, word, bigEndian, block) || block > size)
    {
      error = "truncated: the image's compressed data end inside their block table";
      return false;
    }
    compressedTotal += block;
  }
  if (compressedTotal > size - std::min(size, start + (3 + blocks) * word))
  {
    error = "truncated: the image's compressed blocks need " +
      mcx::DescribeBytes(double(compressedTotal)) + ", the file holds " +
      mcx::DescribeBytes(double(size - std::min(size, start + (3 + blocks) * word)));
    return false;
  }
  return true;
}

// An extent attribute's six integers, each side from -2^31 to 2^31.
bool ParseExtent(const std::string& text, std::vector<long long>& extent)
{
  if (!ParseIntegers(text, extent) || extent.size() != 6)
  {
    return false;
  }
  for (long long e : extent)
  {
    if (e < -LargestSide || e > LargestSide)
    {
      return false;
    }
  }
  return true;
}

bool CheckVTI(const std::string& path, Bytes& claimed, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  std::string head(65536, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  auto tagAt = [&](std::size_t at)
  { return at == std::string::npos ? std::string() : head.substr(at, head.find('>', at) - at); };
  const std::size_t image = head.find("<ImageData");
  if (head.find("<VTKFile") == std::string::npos || image == std::string::npos)
  {
    error = "not a VTK XML image (no <VTKFile> with <ImageData>)";
    return false;
  }
  std::vector<long long> whole, piece;
  const std::string wholeText = Attribute(tagAt(image), "WholeExtent");
  if (!ParseExtent(wholeText, whole))
  {
    error = "the image's WholeExtent '" + wholeText + "' is not six integers within 2^31";
    return false;
  }
  std::vector<long long> dims(3), pieceDims(3);
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = whole[2 * a + 1] - whole[2 * a] + 1;
  }
  // The first piece's extent lies in the whole extent; its point data's
  // first array is what the header checks size (field data may come first).
  const std::size_t pieceAt = head.find("<Piece", image);
  const std::string pieceText = Attribute(tagAt(pieceAt), "Extent");
  if (pieceAt != std::string::npos && !pieceText.empty())
  {
    bool inside = ParseExtent(pieceText, piece);
    for (int a = 0; inside && a < 3; ++a)
    {
      pieceDims[a] = piece[2 * a + 1] - piece[2 * a] + 1;
      inside = piece[2 * a] >= whole[2 * a] && piece[2 * a + 1] <= whole[2 * a + 1] &&
        pieceDims[a] >= 0;
    }
    if (!inside)
    {
      error = "the piece extent '" + pieceText + "' does not lie in the WholeExtent '" + wholeText + "'";
      return false;
    }
  }
  else
  {
    pieceDims = dims;
  }
  const std::size_t pointData = head.find("<PointData", pieceAt == std::string::npos ? image : pieceAt);
  const std::size_t pointDataEnd = head.find("</PointData", pointData == std::string::npos ? 0 : pointData);
  std::size_t array = pointData == std::string::npos ? std::string::npos : head.find("<DataArray", pointData);
  if (array != std::string::npos && pointDataEnd != std::string::npos && array > pointDataEnd)
  {
    array = std::string::npos;
  }
  Bytes element = 1;
  std::vector<long long> components;
  const std::string tag = tagAt(array);
  if (!tag.empty())
  {
    element = XMLElementBytes(Attribute(tag, "type"));
    if (element == 0)
    {
      error = "the image's data type '" + Attribute(tag, "type") + "' is unknown";
      return false;
    }
    if (ParseIntegers(Attribute(tag, "NumberOfComponents"), components) &&
      (components.size() != 1 || components[0] < 1 || components[0] > 64))
    {
      error = "the image's NumberOfComponents is not 1 to 64";
      return false;
    }
  }
  const Bytes value = element * static_cast<Bytes>(components.empty() ? 1 : components[0]);
  if (!Product(dims, value, claimed, error))
  {
    return false;
  }
  // Raw appended data must all be there; base64, text and compression make
  // the data larger or smaller: bound those by what deflate can hold.
  const std::string file = head.substr(0, head.find('>'));
  const bool raw = Attribute(file, "compressor").empty() &&
    head.find("encoding=\"raw\"") != std::string::npos &&
    head.find("format=\"ascii\"") == std::string::npos &&
    head.find("format=\"binary\"") == std::string::npos;
  Bytes pieceBytes = 0;
  const bool emptyPiece = pieceDims[0] < 1 || pieceDims[1] < 1 || pieceDims[2] < 1;
  return CheckAvailable(claimed, FileSize(path), !raw, dims, error) &&
    (tag.empty() || emptyPiece || (Product(pieceDims, value, pieceBytes, error) &&
      CheckAppendedData(path, head, tag, pieceBytes, error)));
}
}

std::vector<std::string> DataFiles(const std::string& header)
{
  const bool nrrd = EndsWith(header, ".nhdr") || EndsWith(header, ".nrrd");
  if (!nrrd && !EndsWith(header, ".mhd") && !EndsWith(header, ".mha"))
  {
    return {};
  }
  TextHeader fields;
  std::string ignored;
  if (!ReadTextHeader(header, nrrd, fields, ignored))
  {
    return {};
  }
  std::map<std::string, std::string>& f = fields.Fields;
  const std::string name = DataFileField(f, nrrd);
  if (name.empty() || Lower(name) == "local" || Lower(name).compare(0, 4, "list") == 0)
  {
    return {}; // in the header itself, or a list (refused by the checks)
  }
  if (name.find('%') == std::string::npos)
  {
    return { Beside(header, name) };
  }
  // A numbered pattern: its files, when it is a bounded one.
  std::vector<std::string> files;
  std::string error;
  return PatternFiles(header, name, files, error) ? files : std::vector<std::string>();
}

bool CheckVolumeHeader(const std::string& path, unsigned long long& claimedBytes, std::string& error)
{
  claimedBytes = 0;
  if (vtksys::SystemTools::FileIsDirectory(path))
  {
    return true;
  }
  if (EndsWith(path, ".nii") || EndsWith(path, ".nii.gz"))
  {
    return CheckNifti(path, claimedBytes, error);
  }
  if (EndsWith(path, ".mha") || EndsWith(path, ".mhd"))
  {
    return CheckMetaImage(path, claimedBytes, error);
  }
  if (EndsWith(path, ".nrrd") || EndsWith(path, ".nhdr"))
  {
    return CheckNrrd(path, claimedBytes, error);
  }
  if (EndsWith(path, ".vtk"))
  {
    return CheckLegacy(path, claimedBytes, error);
  }
  if (EndsWith(path, ".slc"))
  {
    return CheckSLC(path, claimedBytes, error);
  }
  if (EndsWith(path, ".vti"))
  {
    return CheckVTI(path, claimedBytes, error);
  }
  return true; // an unknown format is the reader's to refuse
}

} // namespace mcxapp
