// The executive of the density index: under several processes a failure
// upstream (a reader that cannot make, describe or read this process's
// piece) does not stop the index here, because the index must meet the
// other processes to tell them so -- else they would wait for it forever. The
// executive marks the request (UPSTREAM_FAILED) and the index then fails on
// every process with this process's message. With one process, failures stop
// the pipeline as usual.
//
// ParaView gives its filter proxies and representations executives of its
// own; the plugin's executives for the index and the X-ray representation
// (Module/ParaView/Plugin/Representation) do the same through
// UpstreamFailures.
#ifndef vtkMCXAgreeingExecutive_h
#define vtkMCXAgreeingExecutive_h

#include "MonteCarloXRayFiltersModule.h" // for the export macro
#include "vtkCompositeDataPipeline.h"

class vtkInformationIntegerKey;

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXAgreeingExecutive : public vtkCompositeDataPipeline
{
public:
  static vtkMCXAgreeingExecutive* New();
  vtkTypeMacro(vtkMCXAgreeingExecutive, vtkCompositeDataPipeline);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Set by an agreeing executive under several processes, in the
  /// information and data requests its algorithm gets: 1 when this process's
  /// input could not be produced (in this pass or in the information pass
  /// before it), else 0. Absent otherwise.
  static vtkInformationIntegerKey* UPSTREAM_FAILED();

  /// True when the request says that the input of this pass failed upstream
  /// (only an agreeing executive under several processes says so).
  static bool UpstreamFailed(vtkInformation* request);

  /// What an agreeing executive remembers between passes.
  struct MONTECARLOXRAYFILTERS_EXPORT UpstreamFailures
  {
    bool Distributed = false;
    bool DataObject = false;
    bool Information = false;
    bool Data = false;
    /// Records the result of forwarding a data-object, information, update
    /// extent or data request upstream and marks the information and data
    /// requests. Returns what ForwardUpstream returns: success under several
    /// processes (the algorithm must run to tell the others), else the result.
    int Forwarded(vtkInformation* request, int result, bool distributed);
    /// True when the input's data object could not be made (distributed):
    /// the executive then takes the missing input as valid, so that the
    /// information pass still runs the algorithm, which fails with the others.
    bool InputMayBeMissing() const { return this->Distributed && this->DataObject; }
    /// Clears the mark once the algorithm has run the pass (the request
    /// travels on through other executives, whose algorithms must not read
    /// it). Call after CallAlgorithm.
    static void Consumed(vtkInformation* request);
    /// Prints the members, for the executives' PrintSelf.
    void PrintSelf(ostream& os, vtkIndent indent) const;
  };

protected:
  vtkMCXAgreeingExecutive() = default;
  ~vtkMCXAgreeingExecutive() override = default;

  using Superclass::ForwardUpstream;
  int ForwardUpstream(vtkInformation* request) override;
  int CallAlgorithm(vtkInformation* request, int direction, vtkInformationVector** inInfo,
    vtkInformationVector* outInfo) override;
  int InputTypeIsValid(int port, int index, vtkInformationVector** inInfo) override;

  UpstreamFailures Failures;

private:
  vtkMCXAgreeingExecutive(const vtkMCXAgreeingExecutive&) = delete;
  void operator=(const vtkMCXAgreeingExecutive&) = delete;
};

#endif
