#include "vtkMCXAgreeingExecutive.h"

#include "vtkMCXDensityIndex.h"
#include "vtkMCXDistributed.h"

#include "vtkInformation.h"
#include "vtkInformationIntegerKey.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

vtkStandardNewMacro(vtkMCXAgreeingExecutive);
vtkInformationKeyMacro(vtkMCXAgreeingExecutive, UPSTREAM_FAILED, Integer);

bool vtkMCXAgreeingExecutive::UpstreamFailed(vtkInformation* request)
{
  return request && request->Has(UPSTREAM_FAILED()) && request->Get(UPSTREAM_FAILED()) != 0;
}

int vtkMCXAgreeingExecutive::UpstreamFailures::Forwarded(
  vtkInformation* request, int result, bool distributed)
{
  this->Distributed = distributed;
  if (request->Has(REQUEST_DATA_OBJECT()))
  {
    // A reader that cannot make its output (a legacy VTK file missing) fails
    // here, before any information: the information pass must still meet
    // the others, and fail.
    this->DataObject = !result;
    return distributed ? 1 : result;
  }
  if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()))
  {
    // An input that failed before cannot take an extent either; the data
    // pass must still run the algorithm.
    return distributed ? 1 : result;
  }
  if (request->Has(REQUEST_INFORMATION()))
  {
    this->Information = this->DataObject || !result;
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

void vtkMCXAgreeingExecutive::UpstreamFailures::PrintSelf(ostream& os, vtkIndent indent) const
{
  os << indent << "Failures.Distributed: " << this->Distributed << "\n";
  os << indent << "Failures.DataObject: " << this->DataObject << "\n";
  os << indent << "Failures.Information: " << this->Information << "\n";
  os << indent << "Failures.Data: " << this->Data << "\n";
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

int vtkMCXAgreeingExecutive::InputTypeIsValid(int port, int index, vtkInformationVector** inInfo)
{
  return this->Failures.InputMayBeMissing()
    ? 1
    : this->Superclass::InputTypeIsValid(port, index, inInfo);
}

void vtkMCXAgreeingExecutive::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  this->Failures.PrintSelf(os, indent);
}
