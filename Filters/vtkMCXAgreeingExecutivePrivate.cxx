#include "vtkMCXAgreeingExecutivePrivate.h"

#include "vtkMCXDensityIndex.h"
#include "vtkMCXDistributedPrivate.h"

#include "vtkInformation.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkMCXAgreeingExecutive);

int vtkMCXAgreeingExecutive::ForwardUpstream(vtkInformation* request)
{
  const int result = this->Superclass::ForwardUpstream(request);
  auto* index = vtkMCXDensityIndex::SafeDownCast(this->GetAlgorithm());
  const bool distributed = index && mcx::IsDistributed(index->GetController());
  if (request->Has(REQUEST_INFORMATION()))
  {
    this->FailedInformation = !result;
    this->FailedData = false;
  }
  else if (request->Has(REQUEST_DATA()))
  {
    this->FailedData = !result;
  }
  else
  {
    return result;
  }
  return distributed ? 1 : result;
}

void vtkMCXAgreeingExecutive::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FailedInformation: " << this->FailedInformation << "\n";
  os << indent << "FailedData: " << this->FailedData << "\n";
}
