// The header check of MetaImage files (.mha with the data attached, .mhd
// with a data file, a numbered pattern of files or LOCAL data): NDims,
// DimSize, ElementType and channels against the bytes the data hold
// (mcxHeaderCheck.h).
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include <map>
#include <string>
#include <vector>

namespace mcxio
{
using namespace check;

namespace
{
Bytes MetaElementBytes(const std::string& type)
{
  static const std::map<std::string, Bytes> sizes = { { "met_uchar", 1 }, { "met_char", 1 },
    { "met_ushort", 2 }, { "met_short", 2 }, { "met_uint", 4 }, { "met_int", 4 },
    { "met_ulong", 8 }, { "met_long", 8 }, { "met_ulong_long", 8 }, { "met_long_long", 8 },
    { "met_float", 4 }, { "met_double", 8 } };
  const auto found = sizes.find(Lower(type));
  return found == sizes.end() ? 0 : found->second;
}
}

bool CheckMetaImageHeader(const std::string& path, Bytes& claimed, std::string& error)
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
  if (!Product(
        dims, element * static_cast<Bytes>(channels.empty() ? 1 : channels[0]), claimed, error))
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

} // namespace mcxio
