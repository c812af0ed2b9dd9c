#include "vtkMCXFirstErrorObserver.h"

#include "mcxPrintableText.h"

#include "vtkAlgorithm.h"
#include "vtkExecutive.h"
#include "vtkObjectFactory.h"

#include <cctype>

vtkStandardNewMacro(vtkMCXFirstErrorObserver);

void vtkMCXFirstErrorObserver::Execute(vtkObject*, unsigned long event, void* callData)
{
  if (event == vtkCommand::ErrorEvent && this->Message.empty() && callData)
  {
    this->Message = MessageOf(static_cast<const char*>(callData));
  }
}

void vtkMCXFirstErrorObserver::ObserveAlgorithm(vtkAlgorithm* algorithm)
{
  this->StopObserving();
  this->Algorithm = algorithm;
  this->Executive = algorithm->GetExecutive();
  this->AlgorithmTag = algorithm->AddObserver(vtkCommand::ErrorEvent, this);
  this->ExecutiveTag = this->Executive->AddObserver(vtkCommand::ErrorEvent, this);
}

void vtkMCXFirstErrorObserver::StopObserving()
{
  if (this->Algorithm)
  {
    this->Algorithm->RemoveObserver(this->AlgorithmTag);
    this->Executive->RemoveObserver(this->ExecutiveTag);
  }
  this->Algorithm = nullptr;
  this->Executive = nullptr;
}

std::string vtkMCXFirstErrorObserver::MessageOf(const std::string& report)
{
  // The last "(0x<hex>): ", so that a "): " inside the message itself (a
  // list in parentheses) does not cut it.
  std::size_t start = 0;
  for (std::size_t at = report.find("(0x"); at != std::string::npos; at = report.find("(0x", at + 1))
  {
    std::size_t end = at + 3;
    while (end < report.size() && std::isxdigit(static_cast<unsigned char>(report[end])))
    {
      ++end;
    }
    if (end > at + 3 && report.compare(end, 3, "): ") == 0)
    {
      start = end + 3;
    }
  }
  const std::string message = report.substr(start);
  return mcx::PrintableText(message.substr(0, message.find('\n')));
}
