// What the IO readers that extend a VTK reader share: its stages run with
// their reports caught, and a failure said once, naming the file.
#ifndef vtkMCXReaderErrorsPrivate_h
#define vtkMCXReaderErrorsPrivate_h

#include <functional>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkInformationVector;

namespace mcxio
{

/// Runs stage (a superclass's request) on reader, whose error reports (and
/// its executive's; with warningsAreErrors its warnings too, as the short
/// read of a data file) are kept instead of printed. Returns the first
/// report's message; else what problem() says afterwards; else "out of
/// memory" or the exception's text when stage threw, "the reader failed"
/// when it returned 0; else "".
std::string RunReaderStage(vtkAlgorithm* reader, const std::function<int()>& stage,
  const std::function<std::string()>& problem, bool warningsAreErrors = false);

/// Says "cannot read 'path': problem" once as reader's error and, given
/// outputVector, sets an empty whole extent: a failed request would make the
/// executive say it again. (The caller sets its error code.)
void ReportReaderFailure(vtkAlgorithm* reader, vtkInformationVector* outputVector, const char* path,
  const std::string& problem);

/// Where an extended image reader places its volume: its DataOrigin,
/// DataSpacing and DataDirection, in LPS.
struct Placement
{
  const double* Origin;
  const double* Spacing;
  const double* Direction;
};

/// Ends a reader's RequestInformation: with a problem, says it once
/// (ReportReaderFailure, empty extent) and returns false; else puts the
/// placement in the output information and returns true.
bool FinishInformation(vtkAlgorithm* reader, vtkInformationVector* outputVector, const char* path,
  const std::string& problem, const Placement& placement);

/// A reader's RequestData: an empty output after a failed information
/// request (said there), else read() (the superclass's request; a warning
/// counts as an error) and the placement set on the output. Returns false,
/// the output empty and the failure said once, when the read failed.
bool ReadPlaced(vtkAlgorithm* reader, vtkInformationVector* outputVector, const char* path,
  bool informationFailed, const std::function<int()>& read, const Placement& placement);

/// A format's header check (mcxHeaderCheck.h: CheckNrrdHeader, ...).
using HeaderCheck = bool (*)(const std::string&, unsigned long long&, std::string&);

/// "" when path's header passes check (or path names no file: the reader
/// says so itself), else the reason, the same text mcxray prints after
/// "cannot read 'path': ". Runs before a VTK reader trusts the header.
std::string DescribeHeaderProblem(const char* path, HeaderCheck check);

/// "" when the raw (uncompressed) data files hold the bytes a header
/// claims: files[0] from offset on holds total bytes, or, for several
/// files, each holds total / files.size() from offset on; else the reason
/// (a short read is only a warning of vtkImageReader2's, and leaves zeros).
std::string DescribeShortRawData(
  const std::vector<std::string>& files, unsigned long long offset, unsigned long long total);

} // namespace mcxio

#endif
