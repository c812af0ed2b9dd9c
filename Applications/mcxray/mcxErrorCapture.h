// Catches VTK's error and warning messages so that a failed run ends with
// one line, "mcxray: error: ...", instead of VTK's multi-line reports.
// Watched algorithms report through observers; everything else VTK prints
// (an executive's "returned failure", say) is kept by a silent output
// window instead of being printed, and vtkLogger, which writes to stderr on
// its own, is turned off there and heard through a callback.
#ifndef mcxErrorCapture_h
#define mcxErrorCapture_h

#include "vtkLogger.h"
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkAlgorithm;
class vtkCallbackCommand;
class vtkObject;

namespace mcxapp
{

class SilentOutputWindow;

class ErrorCapture
{
public:
  /// Makes VTK's output window silent from now on, for the rest of the
  /// process: messages of the teardown stay unprinted too.
  ErrorCapture();
  ~ErrorCapture();
  ErrorCapture(const ErrorCapture&) = delete;
  ErrorCapture& operator=(const ErrorCapture&) = delete;

  /// Keeps the error and warning events of algorithm (and stops VTK from
  /// printing them).
  void Watch(vtkAlgorithm* algorithm);

  /// The warnings of the watched algorithms, one line each.
  const std::vector<std::string>& Warnings() const { return this->WarningLines; }

  /// Fails with the first error of a watched algorithm, if any.
  void FailOnWatchedError() const;

  /// Fails with the first error of a watched algorithm or, failing that,
  /// with the first message that reached the output window, if any.
  void FailOnAnyError() const;

  /// The first line of a VTK message, without its "vtkClass (0x...): " prefix.
  static std::string Clean(const char* text);

private:
  static void OnError(vtkObject*, unsigned long, void* self, void* text);
  static void OnWarning(vtkObject*, unsigned long, void* self, void* text);
  static void OnLog(void* self, const vtkLogger::Message& message);

  std::string Error;
  std::string LoggedError; // the first error vtkLogger reported
  std::vector<std::string> WarningLines;
  vtkSmartPointer<vtkCallbackCommand> ErrorCommand;
  vtkSmartPointer<vtkCallbackCommand> WarningCommand;
  vtkSmartPointer<SilentOutputWindow> Window;
};

} // namespace mcxapp

#endif
