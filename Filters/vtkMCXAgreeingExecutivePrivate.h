// The executive of the density index: under several processes a failure
// upstream (a reader that cannot read this process's piece, or its
// information) does not stop the index here, because the index must meet the
// other processes to tell them so -- else they would wait for it forever. The
// index asks InputFailed() and then fails on every process with this
// process's message. With one process, failures stop the pipeline as usual.
#ifndef vtkMCXAgreeingExecutivePrivate_h
#define vtkMCXAgreeingExecutivePrivate_h

#include "vtkCompositeDataPipeline.h"

class vtkMCXAgreeingExecutive : public vtkCompositeDataPipeline
{
public:
  static vtkMCXAgreeingExecutive* New();
  vtkTypeMacro(vtkMCXAgreeingExecutive, vtkCompositeDataPipeline);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// True when the last information pass upstream failed.
  bool InformationFailed() const { return this->FailedInformation; }
  /// True when the last information or data pass upstream failed.
  bool InputFailed() const { return this->FailedInformation || this->FailedData; }

protected:
  vtkMCXAgreeingExecutive() = default;
  ~vtkMCXAgreeingExecutive() override = default;

  int ForwardUpstream(vtkInformation* request) override;

  bool FailedInformation = false;
  bool FailedData = false;

private:
  vtkMCXAgreeingExecutive(const vtkMCXAgreeingExecutive&) = delete;
  void operator=(const vtkMCXAgreeingExecutive&) = delete;
};

#endif
