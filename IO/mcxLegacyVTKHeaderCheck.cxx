// The header check of legacy VTK files (.vtk, structured points): the
// DataFile line, ASCII or BINARY, DIMENSIONS, POINT_DATA and the SCALARS
// type against the bytes the file holds; FIELD data before DIMENSIONS
// skipped as VTK's writer puts them there (mcxHeaderCheck.h).
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include "mcxByteSize.h"

#include <fstream>
#include <istream>
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
      in.seekg(
        static_cast<std::streamoff>(values) * static_cast<std::streamoff>(element), std::ios::cur);
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

// The version line, the title, then (after any blank lines, as VTK's reader
// allows) ASCII or BINARY: false (error set) when they are not there.
bool ReadPreamble(std::ifstream& in, Bytes& consumed, bool& binary, std::string& error)
{
  std::string line;
  std::vector<std::string> lines;
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
  binary = Lower(Trim(lines[2])) == "binary";
  return true;
}

// What the keywords before the scalars' data say.
struct LegacyHeader
{
  std::vector<long long> Dims;
  long long Points = -1;
  long long Components = 1;
  Bytes Element = 0;
  bool OtherDataFirst = false; // other data before the scalars: their place is unknown
};

// Reads the keywords up to the scalars' data (LOOKUP_TABLE) or to other data
// that come first; false (error set) for a header that is no volume's.
bool ReadKeywords(std::ifstream& in, const std::string& path, bool binary, Bytes consumed,
  LegacyHeader& header, std::string& error)
{
  std::string keyword, line;
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
      header.Dims.assign(3, 0);
      in >> header.Dims[0] >> header.Dims[1] >> header.Dims[2];
    }
    else if (key == "point_data")
    {
      in >> header.Points;
    }
    else if (key == "scalars")
    {
      std::string name, type;
      in >> name >> type;
      header.Element = LegacyElementBytes(type);
      std::getline(in, line);
      std::vector<long long> n;
      if (ParseIntegers(line, n) && n.size() == 1)
      {
        header.Components = n[0];
      }
    }
    else if (key == "lookup_table")
    {
      std::getline(in, line);
      return true; // the data follow
    }
    else if (key == "field" && header.Dims.empty())
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
      header.OtherDataFirst = true;
      return true;
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
  return true;
}
}

bool CheckLegacyVTKHeader(const std::string& path, Bytes& claimed, std::string& error)
{
  if (!RegularFile(path, std::string(), error))
  {
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  Bytes consumed = 0;
  bool binary = false;
  LegacyHeader header;
  if (!ReadPreamble(in, consumed, binary, error) ||
    !ReadKeywords(in, path, binary, consumed, header, error))
  {
    return false;
  }
  const std::vector<long long>& dims = header.Dims;
  if (header.OtherDataFirst)
  {
    // Other data come first (VTK's writer puts FIELD and CELL_DATA before
    // POINT_DATA): the scalars' place is not known without reading those;
    // check the dimensions alone.
    if (dims.size() != 3)
    {
      error = "the legacy VTK header gives no DIMENSIONS before its data";
      return false;
    }
    const bool valid = Product(dims, 1, claimed, error);
    claimed = 0;
    return valid;
  }
  const Bytes element = header.Element;
  if (dims.size() != 3 || element == 0 || header.Components < 1 || header.Components > 4)
  {
    error = "the legacy VTK header gives no DIMENSIONS, no known SCALARS type, or not 1 to 4 "
            "components";
    return false;
  }
  if (!Product(dims, element * static_cast<Bytes>(header.Components), claimed, error))
  {
    return false;
  }
  if (header.Points != dims[0] * dims[1] * dims[2])
  {
    error = "the legacy VTK header's POINT_DATA " + std::to_string(header.Points) +
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

} // namespace mcxio
