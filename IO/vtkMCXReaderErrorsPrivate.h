// What the IO readers that extend a VTK reader share: its stages run with
// their reports caught, and a failure said once, naming the file.
#ifndef vtkMCXReaderErrorsPrivate_h
#define vtkMCXReaderErrorsPrivate_h

#include <functional>
#include <string>

class vtkAlgorithm;
class vtkInformationVector;

namespace mcxio
{

/// Runs stage (a superclass's request) on reader, whose error reports (and
/// its executive's) are kept instead of printed. Returns the first report's
/// message; else what problem() says afterwards; else "the reader failed"
/// when stage returned 0, "out of memory" when it threw std::bad_alloc;
/// else "".
std::string RunReaderStage(vtkAlgorithm* reader, const std::function<int()>& stage,
  const std::function<std::string()>& problem);

/// Says "cannot read 'path': problem" once as reader's error and, given
/// outputVector, sets an empty whole extent: a failed request would make the
/// executive say it again. (The caller sets its error code.)
void ReportReaderFailure(vtkAlgorithm* reader, vtkInformationVector* outputVector, const char* path,
  const std::string& problem);

} // namespace mcxio

#endif
