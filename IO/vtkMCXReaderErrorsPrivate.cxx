#include "vtkMCXReaderErrorsPrivate.h"

#include "mcxPrintableText.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMCXFirstErrorObserver.h"
#include "vtkNew.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtksys/SystemTools.hxx"

#include <exception>
#include <new>

namespace mcxio
{

std::string RunReaderStage(vtkAlgorithm* reader, const std::function<int()>& stage,
  const std::function<std::string()>& problem, bool warningsAreErrors)
{
  vtkNew<vtkMCXFirstErrorObserver> error;
  error->ObserveAlgorithm(reader);
  // A short read is only a warning of vtkImageReader2's: a volume's data.
  std::string warning;
  vtkNew<vtkCallbackCommand> warnings;
  warnings->SetClientData(&warning);
  warnings->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      auto* first = static_cast<std::string*>(clientData);
      if (first->empty() && callData)
      {
        *first = vtkMCXFirstErrorObserver::MessageOf(static_cast<const char*>(callData));
      }
    });
  const unsigned long tag =
    warningsAreErrors ? reader->AddObserver(vtkCommand::WarningEvent, warnings) : 0;
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
  catch (const std::exception& e)
  {
    thrown = std::string("the reader failed (") + e.what() + ")";
  }
  if (warningsAreErrors)
  {
    reader->RemoveObserver(tag);
  }
  error->StopObserving();
  if (!error->GetErrorText().empty())
  {
    return error->GetErrorText();
  }
  if (!warning.empty())
  {
    return warning;
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
  vtkErrorWithObjectMacro(reader, << mcx::PrintableText("cannot read '" +
                                    std::string(path ? path : "") + "': " + problem));
  if (outputVector)
  {
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outputVector->GetInformationObject(0)->Set(
      vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
  }
}

bool FinishInformation(vtkAlgorithm* reader, vtkInformationVector* outputVector, const char* path,
  const std::string& problem, const Placement& placement)
{
  if (!problem.empty())
  {
    ReportReaderFailure(reader, outputVector, path, problem);
    return false;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkDataObject::ORIGIN(), placement.Origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), placement.Spacing, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), placement.Direction, 9);
  return true;
}

bool ReadPlaced(vtkAlgorithm* reader, vtkInformationVector* outputVector, const char* path,
  bool informationFailed, const std::function<int()>& read, const Placement& placement)
{
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (informationFailed)
  {
    output->Initialize();
    return true; // said by the information request
  }
  const std::string problem = RunReaderStage(reader, read, [] { return std::string(); }, true);
  if (!problem.empty())
  {
    output->Initialize();
    ReportReaderFailure(reader, nullptr, path, problem);
    return false;
  }
  output->SetOrigin(placement.Origin);
  output->SetSpacing(placement.Spacing);
  output->SetDirectionMatrix(placement.Direction);
  return true;
}

std::string DescribeHeaderProblem(const char* path, HeaderCheck check)
{
  if (!path || !*path || !vtksys::SystemTools::PathExists(path))
  {
    return std::string();
  }
  unsigned long long claimed = 0;
  std::string problem;
  return check(path, claimed, problem) ? std::string() : problem;
}

std::string DescribeShortRawData(
  const std::vector<std::string>& files, unsigned long long offset, unsigned long long total)
{
  const unsigned long long each = files.empty() ? 0 : total / files.size();
  for (const std::string& file : files)
  {
    const unsigned long long size = vtksys::SystemTools::FileLength(file);
    if (size < offset || size - offset < each)
    {
      return "truncated: the header claims " + std::to_string(each) + " bytes of voxels in '" +
        file + "', which holds " + std::to_string(size > offset ? size - offset : 0);
    }
  }
  return std::string();
}

} // namespace mcxio
