#include "vtkMCXAgreeingExecutivePrivate.h"

#include "vtkMCXDensityIndex.h"
#include "vtkMCXDistributedPrivate.h"

#include "vtkInformation.h"
#include "vtkInformationIntegerKey.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkMCXAgreeingExecutive);
vtkInformationKeyMacro(vtkMCXAgreeingExecutive, UPSTREAM_FAILED, Integer);

bool vtkMCXAgreeingExecutive::UpstreamFailed(vtkInformation* request)
{
  return request && request->Has(UPSTREAM_FAILED()) && request->Get(UPSTREAM_FAILED()) != 0;
}

int vtkMCXAgreeingExecutive::UpstreamFailures::Forwarded(
  vtkInformation* request, int result, bool distributed)
{
  if (request->Has(REQUEST_INFORMATION()))
  {
    this->Information = !result;
    this->Data = false;
  }
  else if (request->Has(REQUEST_DATA()))
  {
    this->Data = !result;
  }
  else
  {
    return result;
  }
  if (!distributed)
  {
    return result;
  }
  // The data pass works on the information pass's outcome too.
  const bool failed = this->Information || (request->Has(REQUEST_DATA()) && this->Data);
  request->Set(UPSTREAM_FAILED(), failed ? 1 : 0);
  return 1;
}

void vtkMCXAgreeingExecutive::UpstreamFailures::Consumed(vtkInformation* request)
{
  // Not after REQUEST_DATA_NOT_GENERATED, which comes before the data pass's
  // RequestData in the same request.
  if (request->Has(REQUEST_INFORMATION()) || request->Has(REQUEST_DATA()))
  {
    request->Remove(UPSTREAM_FAILED());
  }
}

int vtkMCXAgreeingExecutive::ForwardUpstream(vtkInformation* request)
{
  const int result = this->Superclass::ForwardUpstream(request);
  auto* index = vtkMCXDensityIndex::SafeDownCast(this->GetAlgorithm());
  return this->Failures.Forwarded(
    request, result, index && mcx::IsDistributed(index->GetController()));
}

int vtkMCXAgreeingExecutive::CallAlgorithm(vtkInformation* request, int direction,
  vtkInformationVector** inInfo, vtkInformationVector* outInfo)
{
  const int result = this->Superclass::CallAlgorithm(request, direction, inInfo, outInfo);
  UpstreamFailures::Consumed(request);
  return result;
}

void vtkMCXAgreeingExecutive::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Failures.Information: " << this->Failures.Information << "\n";
  os << indent << "Failures.Data: " << this->Failures.Data << "\n";
}
