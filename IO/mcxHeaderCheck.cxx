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
  // The files the reader opens, from the same parse as the check (a header
  // the check refuses is never read: what it names so far is returned).
  const bool nrrd = EndsWith(header, ".nhdr") || EndsWith(header, ".nrrd");
  if (!nrrd && !EndsWith(header, ".mhd") && !EndsWith(header, ".mha"))
  {
    return {};
  }
  std::vector<DataRun> runs;
  std::vector<long long> dims;
  Bytes claimed = 0;
  std::string error;
  if (nrrd)
  {
    NrrdRuns(header, runs, claimed, dims, error);
  }
  else
  {
    MetaImageRuns(header, runs, claimed, dims, error);
  }
  std::vector<std::string> files;
  for (const DataRun& run : runs)
  {
    if (run.File != header)
    {
      files.push_back(run.File);
    }
  }
  return files;
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
