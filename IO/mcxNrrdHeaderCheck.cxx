// The header check of NRRD files (.nrrd with the data attached, .nhdr with
// a data file or a numbered pattern): the header parsed the way VTK's
// vtkNrrdReader parses it (ReadHeaderInternal and ReadHeader: the header
// ends at the first blank line, "field: description" with fields in exact
// case, "data file" or "datafile" a file, a pattern of four words or more,
// or LIST), then dimension, sizes, type and encoding against the data as
// that reader consumes them: raw bytes, a gzip stream, or text
// (mcxHeaderCheck.h).
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include "mcxByteSize.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <sstream>
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
  const auto found = sizes.find(type); // vtkNrrdReader: exact, trimmed
  return found == sizes.end() ? 0 : found->second;
}
}

namespace
{
// The fields vtkNrrdReader reads or knowingly ignores (vtkNrrdReader.cxx).
const std::vector<std::string>& KnownFields()
{
  static const std::vector<std::string> fields = { "dimension", "sizes", "spacings", "type",
    "encoding", "data file", "datafile", "space", "labels", "space dimension", "space origin",
    "space directions", "endian", "line skip", "lineskip", "byte skip", "byteskip", "space units",
    "sample units", "sampleunits", "measurement frame", "block size", "blocksize", "content",
    "thicknesses", "axis mins", "axismins", "axis maxs", "axismaxs", "centers", "centerings",
    "units", "kinds", "min", "max", "old min", "oldmin", "old max", "oldmax", "number" };
  return fields;
}

struct NrrdHeader
{
  std::map<std::string, std::string> Fields; // the last description of each field
  std::vector<std::string> DataFiles;        // each "data file" line's description
  Bytes Size = 0;                            // where attached data begin
};

// ReadHeaderInternal and ReadHeader's loop over the first bytes of path.
bool ParseHeader(const std::string& text, NrrdHeader& header, std::string& error)
{
  if (text.compare(0, 4, "NRRD") != 0)
  {
    error = "not a NRRD file (no NRRD magic)"; // another format's bytes, before what they hold
    return false;
  }
  // The header ends after the first "\n\n" or "\n\r\n" past the first byte,
  // looked for as a C string (strchr): up to a NUL byte.
  const std::size_t nul = text.find('\0');
  const std::size_t limit = nul == std::string::npos ? text.size() : nul;
  header.Size = limit;
  bool ended = false;
  for (std::size_t at = text.find('\n', 1); at < limit; at = text.find('\n', at + 1))
  {
    if (at + 1 < limit && text[at + 1] == '\n')
    {
      header.Size = at + 2;
      ended = true;
      break;
    }
    if (at + 2 < limit && text[at + 1] == '\r' && text[at + 2] == '\n')
    {
      header.Size = at + 3;
      ended = true;
      break;
    }
  }
  if (!ended && nul != std::string::npos)
  {
    // VTK's reader loops forever on one (what fuzzing found).
    error = "the header holds a NUL byte";
    return false;
  }
  if (header.Size > LargestHeader)
  {
    error = "the header is longer than 1 MiB";
    return false;
  }
  std::istringstream in(text.substr(0, header.Size));
  std::string line;
  std::getline(in, line); // the magic
  while (std::getline(in, line) && !line.empty())
  {
    const std::size_t separator = line.find(": ");
    if (line[0] == '#' || separator == std::string::npos)
    {
      continue; // a comment, a "key:=value" pair or no field
    }
    const std::string field = line.substr(0, separator);
    const std::string description = Trim(line.substr(separator + 2));
    const auto& known = KnownFields();
    if (std::find(known.begin(), known.end(), field) == known.end())
    {
      for (const std::string& name : known)
      {
        if (Lower(name) == Lower(field))
        {
          error = "the NRRD header's field '" + field + "' is '" + name +
            "' in another letter case, which VTK's reader does not read";
          return false;
        }
      }
    }
    if (field == "data file" || field == "datafile")
    {
      header.DataFiles.push_back(description);
    }
    header.Fields[field] = description;
  }
  return true;
}

// The data files of a "data file" description as vtkNrrdReader lists them:
// "<format> <min> <max> <step> [<subdim>]" numbered, else one file by the
// whole description (a '%' in it included).
bool DataFileNames(const std::string& path, const std::string& description,
  std::vector<std::string>& files, std::string& error)
{
  std::istringstream in(description);
  std::vector<std::string> words;
  std::string word;
  while (in >> word)
  {
    words.push_back(word);
  }
  if (words.empty())
  {
    error = "the NRRD header's data file is empty";
    return false;
  }
  if (words[0] == "LIST")
  {
    error = "NRRD data file lists (data file: LIST) are not supported";
    return false;
  }
  if (words.size() < 4)
  {
    std::string file;
    if (!ExistingDataFile(path, description, file, error))
    {
      return false;
    }
    files.push_back(file);
    return true;
  }
  std::vector<long long> numbers;
  if (!ParseIntegers(words[1] + " " + words[2] + " " + words[3], numbers) || numbers.size() != 3)
  {
    error = "the NRRD file-name pattern '" + description + "' does not give integers";
    return false;
  }
  return NumberedFiles(path, words[0], numbers[0], numbers[1], numbers[2], files, error);
}
}

namespace check
{
bool NrrdRuns(const std::string& path, std::vector<DataRun>& runs, Bytes& claimed,
  std::vector<long long>& dims, std::string& error)
{
  std::string head;
  NrrdHeader header;
  if (!ReadHead(path, head, error) || !ParseHeader(head, header, error))
  {
    return false;
  }
  std::map<std::string, std::string>& f = header.Fields;
  std::vector<long long> rank;
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
  const bool gzip = encoding == "gzip" || encoding == "gz";
  const bool text = encoding == "ascii" || encoding == "text" || encoding == "txt";
  if (encoding.empty())
  {
    error = "the NRRD header gives no encoding (a field the format requires: a truncated header?)";
    return false;
  }
  if (!gzip && !text && encoding != "raw")
  {
    error = "the NRRD encoding '" + f["encoding"] + "' is not supported (raw, ascii or gzip)";
    return false;
  }
  for (const char* skip : { "byte skip", "byteskip", "line skip", "lineskip" })
  {
    if (f.count(skip) && std::atoi(f[skip].c_str()) != 0)
    {
      error = std::string("the NRRD header's ") + skip + " is not supported by VTK's reader";
      return false;
    }
  }
  if (header.DataFiles.size() > 1)
  {
    error = "the NRRD header names its data file " + std::to_string(header.DataFiles.size()) +
      " times (VTK's reader would read them all as one list)";
    return false;
  }
  std::vector<std::string> files;
  if (!header.DataFiles.empty() && !DataFileNames(path, header.DataFiles[0], files, error))
  {
    return false;
  }
  if (files.size() > 1 && static_cast<long long>(files.size()) != dims.back())
  {
    error = "the NRRD header names " + std::to_string(files.size()) + " data files for " +
      std::to_string(dims.back()) + " slices (VTK's reader reads one slice from each)";
    return false;
  }
  if (gzip && (files.size() > 1 || claimed > static_cast<Bytes>(INT32_MAX)))
  {
    error = files.size() > 1
      ? "gzip NRRD data in several files are not read by VTK's reader (it reads the first alone)"
      : "gzip NRRD data of more than 2 GiB are not read by VTK's reader (zlib's gzread)";
    return false;
  }
  if (text && (files.empty() || element == 1))
  {
    error = files.empty()
      ? "ASCII NRRD data attached to the header are not read by VTK's reader (it reads the "
        "header as values): detach them into a data file"
      : "8-bit ASCII NRRD data are read by VTK's reader as characters, not numbers";
    return false;
  }
  if (files.empty())
  {
    files.push_back(path);
  }
  for (const std::string& file : files)
  {
    DataRun run;
    run.File = file;
    run.Offset = file == path && header.DataFiles.empty() ? header.Size : 0;
    run.Needed = claimed / files.size();
    run.Dims = files.size() == 1 ? dims : std::vector<long long>();
    run.Encoding = gzip ? DataRun::Gzip : text ? DataRun::Ascii : DataRun::Raw;
    if (text)
    {
      run.Needed /= element;
    }
    runs.push_back(run);
  }
  return true;
}
}

bool CheckNrrdHeader(const std::string& path, Bytes& claimed, std::string& error)
{
  std::vector<DataRun> runs;
  std::vector<long long> dims;
  if (!NrrdRuns(path, runs, claimed, dims, error))
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
