// A volume file's header checked against the file before a VTK reader
// trusts it: dimensions positive and their product without overflow, a
// known data type, raw data no shorter than the header claims (for
// compressed data a claim within deflate's largest ratio, 1032:1, of what
// the file holds), sane extents and bounded file-name patterns. VTK 9.1's
// readers allocate and read whatever a header says; these checks turn a
// lying or truncated file into one line of error instead.
#ifndef mcxHeaderCheck_h
#define mcxHeaderCheck_h

#include <string>
#include <vector>

namespace mcxapp
{

/// The data files a header names (.mha/.mhd: ElementDataFile, .nrrd/.nhdr:
/// data file; each file of a bounded numbered pattern), as full paths;
/// none for other formats and for data in the header itself.
std::vector<std::string> DataFiles(const std::string& header);

/// Deflate never compresses by more than this (zlib's technical note).
constexpr double LargestCompressionRatio = 1032.0;

/// Checks the header of path by its extension (.nii, .nii.gz, .mha, .mhd,
/// .nrrd, .nhdr, .vtk, .slc, .vti; a DICOM directory passes: its slices are
/// checked by the reader). Returns false with error set to the reason
/// (without the file name); on success claimedBytes is the size of the
/// voxel data the header claims (0 where the format does not say).
bool CheckVolumeHeader(const std::string& path, unsigned long long& claimedBytes, std::string& error);

} // namespace mcxapp

#endif
