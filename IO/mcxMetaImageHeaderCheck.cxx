// The header check of MetaImage files (.mha with the data attached, .mhd
// with a data file, a numbered pattern of files or LOCAL data): the header
// parsed the way VTK's MetaIO parses it (MET_Read in metaUtils.cxx: keys in
// exact case, '=' or ':' between key and value, the last of a key kept,
// the header ended by ElementDataFile), then the data as MetaImage::Read
// consumes them (metaImage.cxx: HeaderSize, CompressedData, BinaryData, a
// pattern's files, a data file's ".gz" or ".Z" twin), each checked against
// its file (mcxHeaderCheck.h).
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace mcxio
{
using namespace check;

namespace
{
// How MetaIO reads a key's value: a string to the end of the line, or
// numbers (one, NDims, NDims^2 or four), which may run onto later lines.
enum class Kind
{
  String,
  Number,
  Array,
  Matrix,
  Four
};

// The keys MetaObject and MetaImage read (M_SetupReadFields).
const std::map<std::string, Kind>& Keys()
{
  static const std::map<std::string, Kind> keys = { { "Comment", Kind::String },
    { "AcquisitionDate", Kind::String }, { "ObjectType", Kind::String },
    { "ObjectSubType", Kind::String }, { "NDims", Kind::Number }, { "Name", Kind::String },
    { "ID", Kind::Number }, { "ParentID", Kind::Number }, { "CompressedData", Kind::String },
    { "CompressedDataSize", Kind::Number }, { "BinaryData", Kind::String },
    { "ElementByteOrderMSB", Kind::String }, { "BinaryDataByteOrderMSB", Kind::String },
    { "Color", Kind::Four }, { "Position", Kind::Array }, { "Origin", Kind::Array },
    { "Offset", Kind::Array }, { "TransformMatrix", Kind::Matrix }, { "Rotation", Kind::Matrix },
    { "Orientation", Kind::Matrix }, { "CenterOfRotation", Kind::Array },
    { "DistanceUnits", Kind::String }, { "AnatomicalOrientation", Kind::String },
    { "ElementSpacing", Kind::Array }, { "DimSize", Kind::Array }, { "HeaderSize", Kind::Number },
    { "Modality", Kind::String }, { "ImagePosition", Kind::Array }, { "SequenceID", Kind::Array },
    { "ElementMin", Kind::Number }, { "ElementMax", Kind::Number },
    { "ElementNumberOfChannels", Kind::Number }, { "ElementSize", Kind::Array },
    { "ElementNBits", Kind::Number }, { "ElementToIntensityFunctionSlope", Kind::Number },
    { "ElementToIntensityFunctionOffset", Kind::Number }, { "ElementType", Kind::String },
    { "ElementDataFile", Kind::String } };
  return keys;
}

// MetaIO reads a line into 500 characters; a longer one breaks its stream.
const std::size_t LongestLine = 499;

struct MetaHeader
{
  std::map<std::string, std::string> Strings;
  std::map<std::string, std::vector<double>> Numbers;
  Bytes End = 0; // after the ElementDataFile line: where LOCAL data begin
};

bool IsSeparator(char c)
{
  return c == '=' || c == ':';
}

// Whether the first key (up to a separator or a line's end, within 500
// bytes, where MetaIO stops) is text: printable ASCII and tabs. An empty
// header passes, for the checks that name what it lacks.
bool BeginsWithAKey(const std::string& text)
{
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  for (std::size_t at = first; at < text.size() && at - first < 500; ++at)
  {
    const unsigned char u = static_cast<unsigned char>(text[at]);
    if (IsSeparator(text[at]) || u == '\n' || u == '\r')
    {
      break;
    }
    if ((u < 0x20 && u != '\t') || u >= 0x7f)
    {
      return false;
    }
  }
  return true;
}

// The end of the line from at (its '\n' or the text's end); false when the
// line is longer than MetaIO reads.
bool LineEnd(const std::string& text, std::size_t at, std::size_t& end)
{
  end = text.find('\n', at);
  end = end == std::string::npos ? text.size() : end;
  return end - at <= LongestLine;
}

// count numbers from at as operator>> reads them (across lines); false for
// what is not one (MetaIO's stream would fail and read nothing more).
bool ReadNumbers(
  const std::string& text, std::size_t& at, std::size_t count, std::vector<double>& values)
{
  values.clear();
  for (std::size_t i = 0; i < count; ++i)
  {
    while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at])))
    {
      ++at;
    }
    const std::size_t start = at;
    while (at < text.size() && std::string("0123456789+-.eE").find(text[at]) != std::string::npos)
    {
      ++at;
    }
    const std::string token = text.substr(start, at - start);
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (token.empty() || end != token.c_str() + token.size())
    {
      return false;
    }
    values.push_back(value);
  }
  return true;
}

// MET_Read over the header's first bytes: false (error set) where MetaIO
// would fail, misread, or where its reading and a person's differ (a key
// of MetaIO's in another case, which MetaIO skips as an unknown one).
bool ParseHeader(const std::string& text, MetaHeader& header, std::string& error)
{
  if (!BeginsWithAKey(text))
  {
    // Another format's bytes (a NIfTI or DICOM file named .mha): say so
    // rather than what MetaIO would stumble on further in.
    error = "not a MetaImage header (it does not begin with a 'Key = Value' line)";
    return false;
  }
  std::size_t at = 0;
  int dims = 0;
  while (at < text.size())
  {
    while (at < text.size() && !IsSeparator(text[at]) &&
      std::isspace(static_cast<unsigned char>(text[at])))
    {
      ++at;
    }
    const std::size_t start = at;
    while (at < text.size() && !IsSeparator(text[at]) && text[at] != '\r' && text[at] != '\n' &&
      at - start < 500)
    {
      ++at;
    }
    if (at >= text.size() || at - start >= 500)
    {
      break; // where MetaIO stops reading
    }
    std::string key = text.substr(start, at - start);
    while (key.size() > 1 && (key.back() == ' ' || key.back() == '\t'))
    {
      key.pop_back();
    }
    if (key.size() > 254)
    {
      // MetaIO copies a key it does not know into a field's 255-byte name
      // (MET_InitReadField's strcpy): a longer one overruns it.
      error = "the MetaImage header's key of " + std::to_string(key.size()) +
        " characters is longer than MetaIO holds (254)";
      return false;
    }
    const auto known = Keys().find(key);
    if (known == Keys().end())
    {
      for (const auto& entry : Keys())
      {
        if (Lower(entry.first) == Lower(key))
        {
          error = "the MetaImage header's key '" + key + "' is '" + entry.first +
            "' in another letter case, which MetaIO skips as unknown";
          return false;
        }
      }
    }
    // MET_SkipToVal: on to the next separator (on a later line if need be),
    // then past separators and blanks.
    while (at < text.size() && !IsSeparator(text[at]))
    {
      ++at;
    }
    while (at < text.size() && (IsSeparator(text[at]) || text[at] == ' ' || text[at] == '\t'))
    {
      ++at;
    }
    std::size_t end = 0;
    if (at >= text.size())
    {
      break;
    }
    if (known == Keys().end() || known->second == Kind::String)
    {
      if (!LineEnd(text, at, end))
      {
        error = "the MetaImage header's line of '" + key + "' is longer than MetaIO reads (" +
          std::to_string(LongestLine) + " characters)";
        return false;
      }
      if (known != Keys().end())
      {
        header.Strings[key] = Trim(text.substr(at, end - at));
        if (header.Strings[key].size() > 254)
        {
          // MetaObject copies a string field (ObjectType, Name, Comment,
          // ...) into a 255-byte member: a longer value overruns it.
          error = "the MetaImage header's " + key + " of " +
            std::to_string(header.Strings[key].size()) +
            " characters is longer than MetaIO holds (254)";
          return false;
        }
      }
    }
    else
    {
      const Kind kind = known->second;
      if (kind != Kind::Number && kind != Kind::Four && dims == 0)
      {
        error = "the MetaImage header gives " + key + " before a valid NDims";
        return false;
      }
      const std::size_t count = kind == Kind::Number ? 1
        : kind == Kind::Four                         ? 4
        : kind == Kind::Array                        ? dims
                                                     : dims * dims;
      std::vector<double>& values = header.Numbers[key];
      if (!ReadNumbers(text, at, count, values))
      {
        error = "the MetaImage header's " + key + " is not " + std::to_string(count) + " number" +
          (count == 1 ? "" : "s");
        return false;
      }
      if (key == "NDims")
      {
        dims = values[0] >= 1 && values[0] <= 3 && values[0] == std::floor(values[0])
          ? static_cast<int>(values[0])
          : 0;
      }
      if (!LineEnd(text, at, end))
      {
        error = "the MetaImage header's line of '" + key + "' is longer than MetaIO reads";
        return false;
      }
    }
    at = end + 1;
    if (key == "ElementDataFile")
    {
      header.End = std::min<Bytes>(at, text.size());
      if (text.find('\0') < header.End)
      {
        error = "the MetaImage header holds a NUL byte"; // MetaIO's keys end there
        return false;
      }
      return true;
    }
  }
  if (text.size() > LargestHeader)
  {
    error = "the header is longer than 1 MiB";
    return false;
  }
  for (const char* required : { "NDims", "DimSize", "ElementType" })
  {
    if (!header.Numbers.count(required) && !header.Strings.count(required))
    {
      error = std::string("the MetaImage header has no ") + required;
      return false;
    }
  }
  error = "the MetaImage header has no ElementDataFile (MetaIO reads keys in exact case)";
  return false;
}

// The bytes of one element of an ElementType VTK's reader reads as MetaIO
// does; 0 for others (MET_LONG: MetaIO reads 4 bytes into VTK's 8).
Bytes ElementBytes(const std::string& type)
{
  static const std::map<std::string, Bytes> sizes = { { "MET_UCHAR", 1 }, { "MET_CHAR", 1 },
    { "MET_USHORT", 2 }, { "MET_SHORT", 2 }, { "MET_UINT", 4 }, { "MET_INT", 4 },
    { "MET_FLOAT", 4 }, { "MET_DOUBLE", 8 } };
  const auto found = sizes.find(type);
  return found == sizes.end() ? 0 : found->second;
}

// MetaIO's flags: true when the value starts with 'T', 't' or '1'.
bool Flag(const MetaHeader& header, const char* key, bool otherwise)
{
  const auto found = header.Strings.find(key);
  if (found == header.Strings.end())
  {
    return otherwise;
  }
  const char c = found->second.empty() ? '\0' : found->second[0];
  return c == 'T' || c == 't' || c == '1';
}

// An integer key's value (otherwise when absent); false for a fraction or
// one beyond [low, high].
bool Integer(const MetaHeader& header, const char* key, long long low, long long high,
  long long otherwise, long long& value, std::string& error)
{
  const auto found = header.Numbers.find(key);
  const double v =
    found == header.Numbers.end() ? static_cast<double>(otherwise) : found->second[0];
  if (!(v >= static_cast<double>(low) && v <= static_cast<double>(high) && v == std::floor(v)))
  {
    error = std::string("the MetaImage header's ") + key + " is not an integer from " +
      std::to_string(low) + " to " + std::to_string(high);
    return false;
  }
  value = static_cast<long long>(v);
  return true;
}

// The words of a pattern as MET_StringToWordArray splits them (spaces only).
std::vector<std::string> Words(const std::string& text)
{
  std::vector<std::string> words;
  std::size_t at = 0;
  while ((at = text.find_first_not_of(' ', at)) != std::string::npos)
  {
    const std::size_t end = std::min(text.find(' ', at), text.size());
    words.push_back(text.substr(at, end - at));
    at = end;
  }
  return words;
}

// The files of a pattern, as MetaImage::ReadStream numbers them: without
// numbers 1 to the last axis' size, with a first number that many from it,
// with a last one a step of (last - first) / size, with a step that one;
// five words or more keep their last three as numbers, the rest as a name
// with spaces. The files must give every slice.
bool PatternFiles(const std::string& path, const std::string& spec, long long slices,
  std::vector<std::string>& files, std::string& error)
{
  std::vector<std::string> words = Words(spec);
  std::vector<long long> numbers;
  const std::size_t named = words.size() >= 5 ? words.size() - 3 : 1;
  for (std::size_t w = named; w < words.size(); ++w)
  {
    std::vector<long long> n;
    if (!ParseIntegers(words[w], n) || n.size() != 1 || n[0] < INT32_MIN || n[0] > INT32_MAX)
    {
      error = "the MetaImage file-name pattern '" + spec + "' has a word '" + words[w] +
        "' that is no integer";
      return false;
    }
    numbers.push_back(n[0]);
  }
  std::string pattern = words[0];
  for (std::size_t w = 1; w < named; ++w)
  {
    pattern += " " + words[w];
  }
  long long first = numbers.size() >= 1 ? numbers[0] : 1;
  long long last = numbers.size() >= 2 ? numbers[1] : first + slices - 1;
  long long step = numbers.size() >= 3 ? numbers[2]
    : numbers.size() == 2              ? (last - first) / slices
                                       : 1;
  if (step < 1)
  {
    error = "the MetaImage file-name pattern '" + spec + "' steps by " + std::to_string(step) +
      " (MetaIO divides by it or never ends)";
    return false;
  }
  if (1 + (last - first) / step > slices)
  {
    last = (slices - 1) * step + first; // MetaIO reads no more than the slices
  }
  if (!NumberedFiles(path, pattern, first, last, step, files, error))
  {
    return false;
  }
  if (static_cast<long long>(files.size()) != slices)
  {
    error = "the MetaImage file-name pattern '" + spec + "' names " + std::to_string(files.size()) +
      " files for the " + std::to_string(slices) + " slices the header claims";
    return false;
  }
  return true;
}
}

namespace check
{
bool MetaImageRuns(const std::string& path, std::vector<DataRun>& runs, Bytes& claimed,
  std::vector<long long>& dims, std::string& error)
{
  std::string text;
  MetaHeader header;
  if (!ReadHead(path, text, error) || !ParseHeader(text, header, error))
  {
    return false;
  }
  long long rank = 0, channels = 1, headerSize = 0, compressedSize = 0;
  if (!Integer(header, "NDims", 1, 3, 0, rank, error) ||
    !Integer(header, "ElementNumberOfChannels", 1, 64, 1, channels, error) ||
    !Integer(header, "HeaderSize", -1, INT32_MAX, 0, headerSize, error) ||
    !Integer(header, "CompressedDataSize", 0, 1LL << 53, 0, compressedSize, error))
  {
    return false;
  }
  const std::vector<double>& sizes = header.Numbers["DimSize"];
  dims.clear();
  for (double size : sizes)
  {
    dims.push_back(
      size == std::floor(size) && std::fabs(size) <= 1e15 ? static_cast<long long>(size) : 0);
  }
  if (static_cast<long long>(dims.size()) != rank)
  {
    error = "the MetaImage header's DimSize does not give NDims sizes";
    return false;
  }
  for (long long side : dims)
  {
    if (side > INT32_MAX)
    {
      error = "the MetaImage header's DimSize " + Dimensions(dims) +
        " has a size beyond 2^31 - 1 (MetaIO keeps sizes in an int)";
      return false;
    }
  }
  const std::string type = header.Strings["ElementType"];
  const Bytes element = ElementBytes(type) * static_cast<Bytes>(channels);
  if (element == 0)
  {
    error = "the MetaImage header's ElementType '" + type +
      "' is not one VTK's reader reads (MET_CHAR, MET_UCHAR, MET_SHORT, MET_USHORT, MET_INT, "
      "MET_UINT, MET_FLOAT, MET_DOUBLE)";
    return false;
  }
  if (!Product(dims, element, claimed, error))
  {
    return false;
  }
  bool compressed = Flag(header, "CompressedData", false);
  bool binary = Flag(header, "BinaryData", true);
  const std::string data = header.Strings["ElementDataFile"];
  // Where the data are and how many voxels each place holds.
  std::vector<std::string> files;
  Bytes start = 0, voxels = claimed / element;
  if (data.empty())
  {
    error = "the MetaImage header's ElementDataFile is empty";
    return false;
  }
  if (data == "Local" || data == "LOCAL" || data == "local")
  {
    files.push_back(path);
    start = header.End;
  }
  else if (data.compare(0, 4, "LIST") == 0)
  {
    error = "MetaImage file lists (ElementDataFile = LIST) are not supported";
    return false;
  }
  else if (data.find('%') != std::string::npos)
  {
    if (!PatternFiles(path, data, dims.back(), files, error))
    {
      return false;
    }
    voxels /= static_cast<Bytes>(dims.back());
  }
  else
  {
    // MetaIO opens the name, else the name with ".gz", else with ".Z"
    // (then compressed binary data).
    std::string file, first;
    for (const char* suffix : { "", ".gz", ".Z" })
    {
      if (ExistingDataFile(path, data + suffix, file, error))
      {
        compressed = compressed || *suffix;
        binary = binary || *suffix;
        error.clear();
        break;
      }
      if (error.find("is missing") == std::string::npos &&
        error.find("cannot be read") == std::string::npos)
      {
        return false; // there but not a regular file: MetaIO would open it
      }
      first = first.empty() ? error : first;
      file.clear();
    }
    if (file.empty())
    {
      error = first; // the name's own reason
      return false;
    }
    files.push_back(file);
  }
  if (!binary && channels > 1)
  {
    error = "MetaIO reads one value of text per voxel, not " + std::to_string(channels);
    return false;
  }
  // M_ReadElements for each place.
  const Bytes bytes = voxels * element;
  for (const std::string& file : files)
  {
    DataRun run;
    run.File = file;
    run.Offset = headerSize > 0 ? static_cast<Bytes>(headerSize) : start;
    if (headerSize == -1)
    {
      // The data end the file.
      if (compressed || !binary || FileSize(file) < bytes)
      {
        error = "the MetaImage header's HeaderSize = -1 (the data end the file) does not fit " +
          std::string(compressed || !binary ? "compressed or text data" : "'" + file + "'");
        return false;
      }
      run.Offset = FileSize(file) - bytes;
    }
    run.Needed = bytes;
    run.Dims = files.size() == 1 ? dims : std::vector<long long>();
    if (binary && compressed)
    {
      run.Encoding = DataRun::Zlib;
      run.Offset = compressedSize == 0 ? 0 : run.Offset; // MetaIO reads the whole file then
      run.Source = static_cast<Bytes>(compressedSize);
      if (run.Source > 0 &&
        (FileSize(file) < run.Offset || FileSize(file) - run.Offset < run.Source))
      {
        error = "the MetaImage header's CompressedDataSize " + std::to_string(compressedSize) +
          " is more than '" + file + "' holds";
        return false;
      }
    }
    else if (!binary)
    {
      run.Encoding = DataRun::Ascii;
      run.Needed = voxels;
    }
    runs.push_back(run);
  }
  return true;
}
}

bool CheckMetaImageHeader(const std::string& path, Bytes& claimed, std::string& error)
{
  std::vector<DataRun> runs;
  std::vector<long long> dims;
  if (!MetaImageRuns(path, runs, claimed, dims, error))
  {
    return false;
  }
  for (const DataRun& run : runs)
  {
    if (!CheckDataRun(run, error))
    {
      return false;
    }
  }
  return true;
}

} // namespace mcxio
