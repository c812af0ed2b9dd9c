#include "vtkMCXXRayRepresentationExecutive.h"

#include "vtkMCXDistributed.h"

#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkMCXXRayRepresentationExecutive);

int vtkMCXXRayRepresentationExecutive::ForwardUpstream(vtkInformation* request)
{
  if (!this->GetNeedsUpdate())
  {
    // ParaView shunts the pass (the representation uses what it has): there
    // is nothing new to record.
    return this->Superclass::ForwardUpstream(request);
  }
  const int result = this->Superclass::ForwardUpstream(request);
  return this->Failures.Forwarded(
    request, result, mcx::IsDistributed(vtkMultiProcessController::GetGlobalController()));
}

int vtkMCXXRayRepresentationExecutive::CallAlgorithm(vtkInformation* request, int direction,
  vtkInformationVector** inInfo, vtkInformationVector* outInfo)
{
  const int result = this->Superclass::CallAlgorithm(request, direction, inInfo, outInfo);
  vtkMCXAgreeingExecutive::UpstreamFailures::Consumed(request);
  return result;
}

int vtkMCXXRayRepresentationExecutive::InputTypeIsValid(
  int port, int index, vtkInformationVector** inInfo)
{
  return this->Failures.InputMayBeMissing()
    ? 1
    : this->Superclass::InputTypeIsValid(port, index, inInfo);
}

void vtkMCXXRayRepresentationExecutive::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  this->Failures.PrintSelf(os, indent);
}
