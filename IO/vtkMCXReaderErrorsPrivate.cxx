#include "vtkMCXReaderErrorsPrivate.h"

#include "vtkAlgorithm.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMCXFirstErrorObserver.h"
#include "vtkNew.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <new>

namespace mcxio
{

std::string RunReaderStage(vtkAlgorithm* reader, const std::function<int()>& stage,
  const std::function<std::string()>& problem)
{
  vtkNew<vtkMCXFirstErrorObserver> error;
  error->ObserveAlgorithm(reader);
  int result = 0;
  std::string thrown;
  try
  {
    result = stage();
  }
  catch (const std::bad_alloc&)
  {
    thrown = "out of memory";
  }
  error->StopObserving();
  if (!error->GetErrorText().empty())
  {
    return error->GetErrorText();
  }
  const std::string found = problem();
  if (!found.empty())
  {
    return found;
  }
  if (!thrown.empty())
  {
    return thrown;
  }
  return result ? std::string() : std::string("the reader failed");
}

void ReportReaderFailure(vtkAlgorithm* reader, vtkInformationVector* outputVector, const char* path,
  const std::string& problem)
{
  vtkErrorWithObjectMacro(reader, << "cannot read '" << (path ? path : "") << "': " << problem);
  if (outputVector)
  {
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outputVector->GetInformationObject(0)->Set(
      vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
  }
}

} // namespace mcxio
