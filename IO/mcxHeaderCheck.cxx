// The header checks' dispatch by file extension, and the data files a
// detached header names (what the command line's output guard compares
// against); each format's check lives in its own mcx*HeaderCheck.cxx.
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include "vtksys/SystemTools.hxx"

#include <map>
#include <string>
#include <vector>

namespace mcxio
{
using namespace check;

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

bool CheckVolumeHeader(
  const std::string& path, unsigned long long& claimedBytes, std::string& error)
{
  claimedBytes = 0;
  if (vtksys::SystemTools::FileIsDirectory(path))
  {
    return true;
  }
  if (EndsWith(path, ".nii") || EndsWith(path, ".nii.gz"))
  {
    return CheckNiftiHeader(path, claimedBytes, error);
  }
  if (EndsWith(path, ".mha") || EndsWith(path, ".mhd"))
  {
    return CheckMetaImageHeader(path, claimedBytes, error);
  }
  if (EndsWith(path, ".nrrd") || EndsWith(path, ".nhdr"))
  {
    return CheckNrrdHeader(path, claimedBytes, error);
  }
  if (EndsWith(path, ".vtk"))
  {
    return CheckLegacyVTKHeader(path, claimedBytes, error);
  }
  if (EndsWith(path, ".slc"))
  {
    return CheckSLCHeader(path, claimedBytes, error);
  }
  if (EndsWith(path, ".vti"))
  {
    return CheckXMLImageHeader(path, claimedBytes, error);
  }
  return true; // an unknown format is the reader's to refuse
}

} // namespace mcxio
