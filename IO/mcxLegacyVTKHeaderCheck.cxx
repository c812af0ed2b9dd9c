// The header check of legacy VTK files (.vtk, structured points): the file
// walked the way vtkStructuredPointsReader reads it (RequestData and
// vtkDataReader's ReadPointData, ReadCellData, ReadFieldData, ReadArray):
// keywords in any case, DIMENSIONS, FIELD, POINT_DATA and CELL_DATA, and
// every attribute array (SCALARS, COLOR_SCALARS, LOOKUP_TABLE, VECTORS,
// NORMALS, TENSORS, TEXTURE_COORDINATES, ids, FIELD arrays), each array's
// values required in the file, binary bytes by size and text counted,
// before the reader allocates for it. Tokens are read as VTK reads them
// (at most 255 characters); a longer one is an error, so that no line of
// the file is ever held whole (mcxHeaderCheck.h).
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace mcxio
{
using namespace check;

namespace
{
Bytes LegacyElementBytes(const std::string& type)
{
  static const std::map<std::string, Bytes> sizes = { { "unsigned_char", 1 }, { "char", 1 },
    { "signed_char", 1 }, { "unsigned_short", 2 }, { "short", 2 }, { "unsigned_int", 4 },
    { "int", 4 }, { "unsigned_long", 8 }, { "long", 8 }, { "vtktypeint64", 8 },
    { "vtktypeuint64", 8 }, { "vtkidtype", 8 }, { "float", 4 }, { "double", 8 } };
  const auto found = sizes.find(Lower(type));
  return found == sizes.end() ? 0 : found->second;
}

// A whole number as operator>> reads one (no "nan", no "inf").
bool IsNumber(const std::string& token)
{
  char* end = nullptr;
  std::strtod(token.c_str(), &end);
  return !token.empty() && end == token.c_str() + token.size() &&
    token.find_first_not_of("0123456789+-.eE") == std::string::npos;
}

// VTK's ReadString reads at most 255 characters, ReadLine lines of 255.
const std::size_t LongestToken = 255;

// The file as vtkDataReader's stream sees it, with tokens and lines of
// bounded length.
class Scanner
{
public:
  Scanner(const std::string& path)
    : In(path, std::ios::binary)
    , Size(FileSize(path))
  {
  }

  // The next whitespace-separated token; false at the end (error empty)
  // or for one longer than VTK reads (error set).
  bool Token(std::string& token, std::string& error)
  {
    token.clear();
    int c = this->In.get();
    while (c != EOF && std::isspace(c))
    {
      c = this->In.get();
    }
    while (c != EOF && !std::isspace(c))
    {
      if (token.size() == LongestToken)
      {
        error = "the legacy VTK file holds a token longer than " + std::to_string(LongestToken) +
          " characters";
        return false;
      }
      token += static_cast<char>(c);
      c = this->In.get();
    }
    if (c != EOF)
    {
      this->In.unget();
    }
    return !token.empty();
  }

  // A line of at most 255 characters (without its '\n'); false at the end
  // or for a longer one (error set), unless cut: then its first 255
  // characters, the rest skipped unread (vtkDataReader::ReadLine).
  bool Line(std::string& line, std::string& error, bool cut = false)
  {
    line.clear();
    int c = this->In.get();
    if (c == EOF)
    {
      return false;
    }
    while (c != EOF && c != '\n')
    {
      if (line.size() == LongestToken && cut)
      {
        // The rest skipped, up to a bound: a title of a megabyte is no title.
        this->In.ignore(static_cast<std::streamsize>(LargestHeader), '\n');
        if (this->In.gcount() == static_cast<std::streamsize>(LargestHeader))
        {
          error = "the legacy VTK file's title line is longer than 1 MiB";
          return false;
        }
        return true;
      }
      if (line.size() == LongestToken)
      {
        error = "the legacy VTK file holds a line longer than " + std::to_string(LongestToken) +
          " characters where VTK reads one";
        return false;
      }
      line += static_cast<char>(c);
      c = this->In.get();
    }
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    return true;
  }

  // Skips bytes bytes of binary data, which must be in the file.
  bool Skip(Bytes bytes)
  {
    const std::streamoff at = this->In.tellg();
    if (at < 0 || static_cast<Bytes>(at) > this->Size || this->Size - at < bytes)
    {
      return false;
    }
    this->In.seekg(static_cast<std::streamoff>(bytes), std::ios::cur);
    return static_cast<bool>(this->In);
  }

  Bytes Left()
  {
    const std::streamoff at = this->In.tellg();
    return at < 0 || static_cast<Bytes>(at) > this->Size ? 0 : this->Size - at;
  }

  std::ifstream In;
  Bytes Size;
};

struct Walk
{
  Scanner& Scan;
  bool Binary;
  std::string& Error;
  bool HaveScalars = false; // the first SCALARS or COLOR_SCALARS of the points: the volume
  Bytes Element = 0;
  long long Components = 0;

  bool Fail(const std::string& message)
  {
    if (this->Error.empty())
    {
      this->Error = message;
    }
    return false;
  }

  bool Integer(long long& value, long long low, long long high, const char* what)
  {
    std::string token;
    std::vector<long long> n;
    if (!this->Scan.Token(token, this->Error) || !ParseIntegers(token, n) || n.size() != 1 ||
      n[0] < low || n[0] > high)
    {
      return this->Fail(std::string("the legacy VTK file's ") + what + " '" + token +
        "' is not an integer from " + std::to_string(low) + " to " + std::to_string(high));
    }
    value = n[0];
    return true;
  }

  // ReadArray: tuples x components values of type, binary after the rest
  // of the keyword's line, or as text; then an optional METADATA block.
  bool Array(const std::string& type, long long tuples, long long components, const char* what)
  {
    const std::string lower = Lower(type);
    const bool bit = lower.compare(0, 3, "bit") == 0;
    const Bytes element = bit ? 1 : LegacyElementBytes(lower);
    if (element == 0)
    {
      return this->Fail("the legacy VTK file's " + std::string(what) + " type '" + type +
        "' is not a numeric one VTK reads");
    }
    const double values = static_cast<double>(tuples) * static_cast<double>(components);
    const double bytes = bit ? (values + 7) / 8 : values * static_cast<double>(element);
    const std::string claim = std::string(what) + " of " + std::to_string(tuples) + " x " +
      std::to_string(components) + " values";
    if (values > 0 && this->Binary)
    {
      std::string rest;
      if (!this->Scan.Line(rest, this->Error))
      {
        return this->Fail("the legacy VTK file ends before its " + claim);
      }
      if (bytes > static_cast<double>(this->Scan.Left()) ||
        !this->Scan.Skip(static_cast<Bytes>(bytes)))
      {
        return this->Fail("truncated: the legacy VTK file's " + claim + " need " +
          std::to_string(static_cast<Bytes>(bytes)) + " bytes, the file holds " +
          std::to_string(this->Scan.Left()));
      }
    }
    else if (values > 0)
    {
      // Text: at least two characters a value, so the count is bounded by
      // the file before it is counted.
      if (values * 2 - 1 > static_cast<double>(this->Scan.Left()))
      {
        return this->Fail("truncated: the legacy VTK file's " + claim +
          " as text need more than "
          "the file holds");
      }
      std::string token;
      for (double v = 0; v < values; ++v)
      {
        if (!this->Scan.Token(token, this->Error) || !IsNumber(token))
        {
          return this->Fail("truncated: the legacy VTK file's " + claim + " as text hold " +
            std::to_string(static_cast<Bytes>(v)) + " numbers" +
            (token.empty() ? std::string() : ", then '" + token + "'"));
        }
      }
    }
    return this->Metadata();
  }

  // An array's METADATA block: lines up to a blank one.
  bool Metadata()
  {
    const std::streampos at = this->Scan.In.tellg();
    std::string token, line;
    if (!this->Scan.Token(token, this->Error) || Lower(token).compare(0, 8, "metadata") != 0)
    {
      this->Scan.In.clear();
      this->Scan.In.seekg(at);
      return this->Error.empty();
    }
    this->Scan.Line(line, this->Error); // the rest of the METADATA line
    while (this->Scan.Line(line, this->Error) && !Trim(line).empty())
    {
    }
    return this->Error.empty();
  }

  // ReadFieldData: "name arrays", then per array "name components tuples type".
  bool Field()
  {
    std::string name, type;
    long long arrays = 0;
    if (!this->Scan.Token(name, this->Error) || !this->Integer(arrays, 0, 10000, "FIELD count"))
    {
      return this->Fail("the legacy VTK file's FIELD header is malformed");
    }
    for (long long a = 0; a < arrays; ++a)
    {
      long long components = 0, tuples = 0;
      if (!this->Scan.Token(name, this->Error))
      {
        return this->Fail("the legacy VTK file ends inside its FIELD data");
      }
      if (name == "NULL_ARRAY")
      {
        continue;
      }
      if (!this->Integer(components, 1, 1 << 20, "FIELD array components") ||
        !this->Integer(tuples, 0, 1LL << 40, "FIELD array tuples") ||
        !this->Scan.Token(type, this->Error) ||
        !this->Array(type, tuples, components, "FIELD array"))
      {
        return false;
      }
    }
    return true;
  }

  // ReadPointData / ReadCellData: attributes to the end of the file, each
  // array of count tuples; POINT_DATA and CELL_DATA change the count.
  bool Attributes(long long count, bool points)
  {
    std::string keyword, name, type, token;
    while (this->Scan.Token(keyword, this->Error))
    {
      const std::string key = Lower(keyword);
      long long components = 1;
      auto is = [&key](const char* word) { return key.compare(0, std::strlen(word), word) == 0; };
      if (is("scalars"))
      {
        if (!this->Scan.Token(name, this->Error) || !this->Scan.Token(type, this->Error) ||
          !this->Scan.Token(token, this->Error))
        {
          return this->Fail("the legacy VTK file's SCALARS header is cut short");
        }
        if (Lower(token) != "lookup_table")
        {
          components = std::atoi(token.c_str());
          if (components < 1 || !this->Scan.Token(token, this->Error) ||
            Lower(token) != "lookup_table")
          {
            return this->Fail("the legacy VTK file's SCALARS have no LOOKUP_TABLE or a bad "
                              "component count");
          }
        }
        if (!this->Scan.Token(token, this->Error))
        {
          return this->Fail("the legacy VTK file's SCALARS header is cut short");
        }
        this->Volume(points, LegacyElementBytes(type), components);
        if (!this->Array(type, count, components, "SCALARS"))
        {
          return false;
        }
      }
      else if (is("color_scalars"))
      {
        if (!this->Scan.Token(name, this->Error) ||
          !this->Integer(components, 1, 1 << 20, "COLOR_SCALARS component count"))
        {
          return false;
        }
        type = this->Binary ? "unsigned_char" : "float";
        this->Volume(points, 1, components); // text floats become unsigned chars
        if (!this->Array(type, count, components, "COLOR_SCALARS"))
        {
          return false;
        }
      }
      else if (is("lookup_table"))
      {
        long long size = 0;
        if (!this->Scan.Token(name, this->Error) ||
          !this->Integer(size, 0, 1LL << 31, "LOOKUP_TABLE size") ||
          !this->Array(this->Binary ? "unsigned_char" : "float", size, 4, "LOOKUP_TABLE"))
        {
          return false;
        }
      }
      else if (is("vectors") || is("normals") || is("tensors") || is("global_ids") ||
        is("pedigree_ids") || is("edge_flags") || is("texture_coordinates"))
      {
        components = is("tensors6")        ? 6
          : is("tensors")                  ? 9
          : is("vectors") || is("normals") ? 3
                                           : 1;
        if (!this->Scan.Token(name, this->Error) ||
          (is("texture_coordinates") &&
            !this->Integer(components, 1, 3, "TEXTURE_COORDINATES dimension")) ||
          !this->Scan.Token(type, this->Error) ||
          !this->Array(type, count, components, keyword.c_str()))
        {
          return this->Fail("the legacy VTK file's " + keyword + " header is cut short");
        }
      }
      else if (is("field"))
      {
        if (!this->Field())
        {
          return false;
        }
      }
      else if (is("point_data") || is("cell_data"))
      {
        if (is("point_data") == points)
        {
          // ReadPointData takes CELL_DATA, ReadCellData POINT_DATA; not their own.
          return this->Fail("the legacy VTK file gives " + keyword +
            " twice in a row, which VTK's "
            "reader refuses");
        }
        points = is("point_data");
        if (!this->Integer(count, 0, 1LL << 40, "POINT_DATA or CELL_DATA count"))
        {
          return false;
        }
      }
      else
      {
        return this->Fail("the legacy VTK file's attribute '" + keyword + "' is not one VTK reads");
      }
    }
    return this->Error.empty();
  }

  void Volume(bool points, Bytes element, long long components)
  {
    if (points && !this->HaveScalars)
    {
      this->HaveScalars = true;
      this->Element = element;
      this->Components = components;
    }
  }
};

// The version line, the title, then (after any blank lines, as VTK's reader
// allows) ASCII or BINARY: false (error set) when they are not there.
bool ReadPreamble(Scanner& scan, bool& binary, std::string& error)
{
  std::string version, title, format;
  if (!scan.Line(version, error) || version.find("vtk DataFile") == std::string::npos ||
    !scan.Line(title, error, true))
  {
    if (error.empty())
    {
      error = "not a legacy VTK file (no '# vtk DataFile' line)";
    }
    return false;
  }
  if (!scan.Token(format, error))
  {
    error = error.empty() ? "the legacy VTK file says neither ASCII nor BINARY" : error;
    return false;
  }
  binary = Lower(format) == "binary";
  if (!binary && Lower(format) != "ascii")
  {
    error = "the legacy VTK file says '" + format + "', neither ASCII nor BINARY";
    return false;
  }
  return true;
}
}

namespace
{
bool CheckLegacy(const std::string& path, Bytes& claimed, std::string& error)
{
  if (!RegularFile(path, std::string(), error))
  {
    return false;
  }
  Scanner scan(path);
  bool binary = false;
  if (!ReadPreamble(scan, binary, error))
  {
    return false;
  }
  std::string token;
  if (!scan.Token(token, error) || Lower(token).compare(0, 7, "dataset") != 0 ||
    !scan.Token(token, error) || Lower(token).compare(0, 17, "structured_points") != 0)
  {
    error = error.empty()
      ? "a legacy VTK " + token + " dataset is not a volume (expected DATASET STRUCTURED_POINTS)"
      : error;
    return false;
  }
  Walk walk{ scan, binary, error };
  std::vector<long long> dims;
  long long count = 0;
  bool points = true;
  // vtkStructuredPointsReader::RequestData's loop up to the data.
  while (scan.Token(token, error))
  {
    const std::string key = Lower(token);
    auto is = [&key](const char* word) { return key.compare(0, std::strlen(word), word) == 0; };
    long long value = 0;
    if (is("field"))
    {
      if (!walk.Field())
      {
        return false;
      }
    }
    else if (is("dimensions") || is("extent"))
    {
      const int n = is("extent") ? 6 : 3;
      std::vector<long long> numbers;
      for (int i = 0; i < n; ++i)
      {
        if (!walk.Integer(value, INT32_MIN, INT32_MAX, "DIMENSIONS or EXTENT"))
        {
          return false;
        }
        numbers.push_back(value);
      }
      dims = numbers;
      if (n == 6)
      {
        dims = { numbers[1] - numbers[0] + 1, numbers[3] - numbers[2] + 1,
          numbers[5] - numbers[4] + 1 };
      }
    }
    else if (is("aspect_ratio") || is("spacing") || is("origin"))
    {
      for (int i = 0; i < 3; ++i)
      {
        if (!scan.Token(token, error))
        {
          return walk.Fail("the legacy VTK header is cut short");
        }
      }
    }
    else if (is("point_data") || is("cell_data"))
    {
      points = is("point_data");
      if (!walk.Integer(count, 0, 1LL << 62, "POINT_DATA or CELL_DATA count"))
      {
        return false;
      }
      break;
    }
    else
    {
      return walk.Fail("the legacy VTK header's keyword '" + token + "' is not one VTK reads");
    }
  }
  if (!error.empty())
  {
    return false;
  }
  if (dims.size() != 3 || !Product(dims, 1, claimed, error))
  {
    return walk.Fail("the legacy VTK header gives no DIMENSIONS before its data");
  }
  const long long cells = (dims[0] > 1 ? dims[0] - 1 : 1) * (dims[1] > 1 ? dims[1] - 1 : 1) *
    (dims[2] > 1 ? dims[2] - 1 : 1);
  if (count != (points ? dims[0] * dims[1] * dims[2] : cells))
  {
    error = "the legacy VTK header's " + std::string(points ? "POINT_DATA " : "CELL_DATA ") +
      std::to_string(count) + " does not match its DIMENSIONS " + Dimensions(dims);
    return false;
  }
  if (!walk.Attributes(count, points))
  {
    return false;
  }
  if (!walk.HaveScalars || walk.Element == 0 || walk.Components < 1 || walk.Components > 4)
  {
    error = "the legacy VTK file has no point SCALARS of a known type with 1 to 4 components";
    return false;
  }
  return Product(dims, walk.Element * static_cast<Bytes>(walk.Components), claimed, error);
}
}

bool CheckLegacyVTKHeader(const std::string& path, Bytes& claimed, std::string& error)
{
  error.clear();
  if (CheckLegacy(path, claimed, error))
  {
    return true;
  }
  if (error.empty())
  {
    error = "the legacy VTK file ends inside its header or data"; // a token missing
  }
  return false;
}

} // namespace mcxio
