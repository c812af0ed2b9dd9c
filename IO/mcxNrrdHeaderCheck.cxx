// The header check of NRRD files (.nrrd with the data attached, .nhdr with
// a data file or a numbered pattern): dimension, sizes, type and encoding
// against the bytes the data hold (mcxHeaderCheck.h).
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include "mcxByteSize.h"

#include <map>
#include <string>
#include <vector>

namespace mcxio
{
using namespace check;

namespace
{
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
}

bool CheckNrrdHeader(const std::string& path, Bytes& claimed, std::string& error)
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
  const bool compressed =
    encoding == "gzip" || encoding == "gz" || encoding == "bzip2" || encoding == "bz2";
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
    error = "truncated: the header claims " + Dimensions(dims) +
      " voxels as text, the file holds " + mcx::DescribeBytes(static_cast<double>(available));
    return false;
  }
  return text || CheckAvailable(claimed, available, compressed, dims, error);
}

} // namespace mcxio
