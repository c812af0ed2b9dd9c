// A progress bar on stderr for the stages of a run, shown only on a
// terminal and only once a stage runs long, so that logs and pipes stay clean.
#ifndef mcxProgressBar_h
#define mcxProgressBar_h

#include "vtkNew.h"
#include <string>

#include <chrono>
#include <cstddef>

class vtkAlgorithm;
class vtkCallbackCommand;
class vtkObject;

namespace mcxapp
{

class ProgressBar
{
public:
  ProgressBar();
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Shows the progress events of algorithm.
  void Watch(vtkAlgorithm* algorithm);

  /// A stage starts: the bar is labelled stage until End(). A stage in
  /// parts (the poses of a sweep) is begun once per part: the bar shows the
  /// whole stage, part of parts, and its half-second of silence counts
  /// from part 0.
  void Begin(const std::string& stage, std::size_t part = 0, std::size_t parts = 1);

  /// The stage is over: clears the bar if it was shown.
  void End();

private:
  static void OnProgress(vtkObject*, unsigned long, void* self, void* fraction);
  void Update(double fraction);

  bool Enabled = false;
  std::string Stage;
  std::size_t Part = 0;
  std::size_t Parts = 1;
  std::chrono::steady_clock::time_point Start;
  bool Shown = false;
  vtkNew<vtkCallbackCommand> Command;
};

} // namespace mcxapp

#endif
