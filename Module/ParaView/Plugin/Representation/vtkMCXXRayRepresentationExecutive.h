/**
 * @class   vtkMCXXRayRepresentationExecutive
 * @brief   The executive of the "Monte Carlo X-Ray" representation, which
 * lets a failed reader on one process through to the representation.
 *
 * ParaView's representation executive (vtkPVDataRepresentationPipeline)
 * plus what the index's own executive (vtkMCXAgreeingExecutive) adds: on a
 * parallel server (several processes in the global controller, which the
 * representation's agreement uses too), when the reader upstream fails on
 * one process, the representation still runs there and tells the others
 * (each process indexes its slab together with the others), so that every
 * process reports the failure and none waits for it.
 */
#ifndef vtkMCXXRayRepresentationExecutive_h
#define vtkMCXXRayRepresentationExecutive_h

#include "MonteCarloXRayParaViewModule.h"   // for export macro
#include "vtkMCXAgreeingExecutive.h"        // for vtkMCXAgreeingExecutive::UpstreamFailures
#include "vtkPVDataRepresentationPipeline.h"

class MONTECARLOXRAYPARAVIEW_EXPORT vtkMCXXRayRepresentationExecutive
  : public vtkPVDataRepresentationPipeline
{
public:
  static vtkMCXXRayRepresentationExecutive* New();
  vtkTypeMacro(vtkMCXXRayRepresentationExecutive, vtkPVDataRepresentationPipeline);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkMCXXRayRepresentationExecutive() = default;
  ~vtkMCXXRayRepresentationExecutive() override = default;

  using Superclass::ForwardUpstream;
  int ForwardUpstream(vtkInformation* request) override;
  int CallAlgorithm(vtkInformation* request, int direction, vtkInformationVector** inInfo,
    vtkInformationVector* outInfo) override;
  int InputTypeIsValid(int port, int index, vtkInformationVector** inInfo) override;

  vtkMCXAgreeingExecutive::UpstreamFailures Failures;

private:
  vtkMCXXRayRepresentationExecutive(const vtkMCXXRayRepresentationExecutive&) = delete;
  void operator=(const vtkMCXXRayRepresentationExecutive&) = delete;
};

#endif
