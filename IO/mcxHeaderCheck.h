// The header checks of every volume format the project reads, plain C++
// (the standard library, vtksys and zlib; no VTK class), so that the fuzzer
// compiles them as they are. A volume file's header is checked against the
// file before a VTK reader trusts it: dimensions positive and their product
// without overflow, a known data type, raw data no shorter than the header
// claims (compressed MetaImage and NRRD data inflated to the claimed size,
// as a stream; other compressed data within deflate's largest ratio,
// 1032:1, of what the file holds; text data counted value by value), data
// files regular files, sane extents and bounded file-name patterns. The
// text formats' headers are parsed the way VTK's readers parse them. VTK's readers allocate and
// read whatever a header says; these checks turn a lying or truncated file into one line of error
// instead. The dispatch and the data-file lookup live in mcxHeaderCheck.cxx, one format per file
// beside it (mcx*HeaderCheck.cxx), their shared helpers in mcxHeaderCheckPrivate.
#ifndef mcxHeaderCheck_h
#define mcxHeaderCheck_h

#include <string>
#include <vector>

namespace mcxio
{

/// The data files VTK's reader opens for a header (.mha/.mhd, .nrrd/.nhdr),
/// as full paths: decided by the same parse as the format's check, which
/// parses as the reader does (key case, separators, a pattern's numbering,
/// a MetaImage data file's .gz/.Z twin), so that an output compared against
/// them by device and inode is never a file the read opens. None for other
/// formats and for data in the header itself; for a header its check
/// refuses (never read), possibly none.
std::vector<std::string> DataFiles(const std::string& header);

/// Deflate never compresses by more than this (zlib's technical note).
constexpr double LargestCompressionRatio = 1032.0;

/// Checks the header of path by its extension (.nii, .nii.gz, .mha, .mhd,
/// .nrrd, .nhdr, .vtk, .slc, .vti; a DICOM directory passes: its slices are
/// checked by the reader). Returns false with error set to the reason
/// (without the file name); on success claimedBytes is the size of the
/// voxel data the header claims (0 where the format does not say).
bool CheckVolumeHeader(
  const std::string& path, unsigned long long& claimedBytes, std::string& error);

///@{
/// One format's check, whatever path's extension (the format readers run
/// theirs): as CheckVolumeHeader. NIfTI-1 and NIfTI-2, gzipped when path
/// ends in .gz (mcxNiftiHeaderCheck.cxx); MetaImage, attached or detached
/// (mcxMetaImageHeaderCheck.cxx); NRRD, attached or detached
/// (mcxNrrdHeaderCheck.cxx); legacy VTK structured points
/// (mcxLegacyVTKHeaderCheck.cxx); SLC (mcxSLCHeaderCheck.cxx); VTK XML image
/// data (mcxXMLImageHeaderCheck.cxx).
bool CheckNiftiHeader(
  const std::string& path, unsigned long long& claimedBytes, std::string& error);
bool CheckMetaImageHeader(
  const std::string& path, unsigned long long& claimedBytes, std::string& error);
bool CheckNrrdHeader(const std::string& path, unsigned long long& claimedBytes, std::string& error);
bool CheckLegacyVTKHeader(
  const std::string& path, unsigned long long& claimedBytes, std::string& error);
bool CheckSLCHeader(const std::string& path, unsigned long long& claimedBytes, std::string& error);
bool CheckXMLImageHeader(
  const std::string& path, unsigned long long& claimedBytes, std::string& error);
///@}

} // namespace mcxio

#endif
