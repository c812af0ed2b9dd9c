/**
 * @class   vtkMCXParaViewIndexExecutive
 * @brief   ParaView's executive for the X-Ray Density Index filter, which
 * lets a failed reader on one process through to the index.
 *
 * ParaView gives every filter proxy an executive (the proxy's "executive"
 * attribute, vtkPVCompositeDataPipeline by default). This one is that
 * executive plus what the index's own executive (vtkMCXAgreeingExecutive)
 * adds: on a parallel server, when the reader upstream fails on one process
 * (a missing or truncated file there), the index still runs there, meets the
 * other processes and fails on every one of them with that process's
 * message, instead of leaving them waiting for it.
 */
#ifndef vtkMCXParaViewIndexExecutive_h
#define vtkMCXParaViewIndexExecutive_h

#include "MonteCarloXRayParaViewModule.h"   // for export macro
#include "vtkMCXAgreeingExecutive.h"        // for vtkMCXAgreeingExecutive::UpstreamFailures
#include "vtkPVCompositeDataPipeline.h"

class MONTECARLOXRAYPARAVIEW_EXPORT vtkMCXParaViewIndexExecutive : public vtkPVCompositeDataPipeline
{
public:
  static vtkMCXParaViewIndexExecutive* New();
  vtkTypeMacro(vtkMCXParaViewIndexExecutive, vtkPVCompositeDataPipeline);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkMCXParaViewIndexExecutive() = default;
  ~vtkMCXParaViewIndexExecutive() override = default;

  using Superclass::ForwardUpstream;
  int ForwardUpstream(vtkInformation* request) override;
  int CallAlgorithm(vtkInformation* request, int direction, vtkInformationVector** inInfo,
    vtkInformationVector* outInfo) override;
  int InputTypeIsValid(int port, int index, vtkInformationVector** inInfo) override;

  vtkMCXAgreeingExecutive::UpstreamFailures Failures;

private:
  vtkMCXParaViewIndexExecutive(const vtkMCXParaViewIndexExecutive&) = delete;
  void operator=(const vtkMCXParaViewIndexExecutive&) = delete;
};

#endif
