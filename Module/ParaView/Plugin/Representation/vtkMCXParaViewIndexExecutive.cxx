#include "vtkMCXParaViewIndexExecutive.h"

#include "vtkMCXDensityIndex.h"
#include "vtkMCXDistributed.h"

#include "vtkInformation.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkMCXParaViewIndexExecutive);

int vtkMCXParaViewIndexExecutive::ForwardUpstream(vtkInformation* request)
{
  const int result = this->Superclass::ForwardUpstream(request);
  auto* index = vtkMCXDensityIndex::SafeDownCast(this->GetAlgorithm());
  return this->Failures.Forwarded(
    request, result, index && mcx::IsDistributed(index->GetController()));
}

int vtkMCXParaViewIndexExecutive::CallAlgorithm(vtkInformation* request, int direction,
  vtkInformationVector** inInfo, vtkInformationVector* outInfo)
{
  const int result = this->Superclass::CallAlgorithm(request, direction, inInfo, outInfo);
  vtkMCXAgreeingExecutive::UpstreamFailures::Consumed(request);
  return result;
}

int vtkMCXParaViewIndexExecutive::InputTypeIsValid(
  int port, int index, vtkInformationVector** inInfo)
{
  return this->Failures.InputMayBeMissing()
    ? 1
    : this->Superclass::InputTypeIsValid(port, index, inInfo);
}

void vtkMCXParaViewIndexExecutive::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  this->Failures.PrintSelf(os, indent);
}
