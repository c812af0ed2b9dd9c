// What vtkMCXDICOMSeriesReader checks before vtk-dicom trusts a series:
// the files of a folder, each folder and file once (by device and inode,
// so that a link to a parent or to the folder itself adds nothing), and
// each file's pixel data against what its header claims (frames x rows x
// columns x samples x bits: uncompressed data all there, encapsulated data
// in fragments of the transfer syntax's format, RLE decoded to the end).
// vtk-dicom allocates per frame before it reads, and leaves zeros where a
// decoder fails. Uses vtk-dicom; stays inside IO/.
#ifndef mcxDicomFiles_h
#define mcxDicomFiles_h

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace mcxio
{

/// How deep and how many: what vtkMCXDICOMSeriesReader walks and what the
/// files a read of a folder may open (mcxVolumeReader.h's InputFiles) are.
constexpr int DicomScanDepth = 4; // series in subfolders too, as exports nest them
constexpr std::size_t DicomFileLimit = 1000000;

/// The files under folder, subfolders depth levels deep, hidden names
/// skipped, each file and folder once however many links lead to it; false
/// (error set) past limit files.
bool DicomFolderFiles(const std::string& folder, int depth, std::size_t limit,
  std::vector<std::string>& files, std::string& error);

/// parse run in a forked child, its answer handed back through a pipe:
/// true with answer set to what it returned, false with error set to
/// "vtk-dicom's parser crashed (SIGSEGV) on " + parsed (or failed: an
/// exception, an exit status; or did not finish within `seconds`, when the
/// child is killed) or to why no child could be started. For what parses a file with
/// vtk-dicom whose parser reads past its buffer on some damaged files (into what the heap held: a
/// parse that passed in one process can fault in another), so that the caller's process never
/// parses it. POSIX: fork and a pipe.
bool ParseInChild(const std::function<std::string()>& parse, const std::string& parsed,
  std::string& answer, std::string& error, double seconds = 300.0);

/// CheckDicomPixelData over files in a forked child (ParseInChild) first, so
/// that a file that crashes vtk-dicom's parser is named as such: false with
/// error set to the child's verdict, to "vtk-dicom's parser crashed
/// (SIGSEGV) on one of its files", or to why no child could be started. The
/// series reader probes so where it reads in its own process (in its
/// contained child by default). The child first runs scan (the caller's own
/// next step, the series reader's vtkDICOMDirectory update).
bool ProbeDicomFiles(
  const std::vector<std::string>& files, const std::function<void()>& scan, std::string& error);

/// Checks each file's pixel data against its header (see above); claimed is
/// set to the bytes of the decoded voxels (all files, as stored). False
/// with error "'file': reason" for the first file that lies.
bool CheckDicomPixelData(
  const std::vector<std::string>& files, unsigned long long& claimed, std::string& error);

} // namespace mcxio

#endif
