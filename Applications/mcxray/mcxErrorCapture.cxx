#include "mcxErrorCapture.h"

#include "mcxFail.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"

namespace mcxapp
{

// Keeps the first message it is given instead of printing it.
class SilentOutputWindow : public vtkOutputWindow
{
public:
  static SilentOutputWindow* New();
  vtkTypeMacro(SilentOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override
  {
    if (this->First.empty() && text)
    {
      this->First = text;
    }
  }
  std::string First;
};
vtkStandardNewMacro(SilentOutputWindow);

namespace
{
vtkSmartPointer<vtkCallbackCommand> MakeCommand(
  void (*callback)(vtkObject*, unsigned long, void*, void*), ErrorCapture* capture)
{
  auto command = vtkSmartPointer<vtkCallbackCommand>::New();
  command->SetClientData(capture);
  command->SetCallback(callback);
  return command;
}
}

namespace
{
const char* const LogCallbackId = "mcxray-error-capture";
}

ErrorCapture::ErrorCapture()
{
  this->Window = vtkSmartPointer<SilentOutputWindow>::New();
  vtkOutputWindow::SetInstance(this->Window);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  vtkLogger::AddCallback(LogCallbackId, &ErrorCapture::OnLog, this, vtkLogger::VERBOSITY_ERROR);
}

ErrorCapture::~ErrorCapture()
{
  vtkLogger::RemoveCallback(LogCallbackId);
}

// The commands are made with the first watch, not before: each VTK object
// made advances the global modification clock, whose values VTK's failure
// reports print; making them only when needed keeps those reports as they are.
void ErrorCapture::Watch(vtkAlgorithm* algorithm)
{
  if (!this->ErrorCommand)
  {
    this->ErrorCommand = MakeCommand(&ErrorCapture::OnError, this);
    this->WarningCommand = MakeCommand(&ErrorCapture::OnWarning, this);
  }
  algorithm->AddObserver(vtkCommand::ErrorEvent, this->ErrorCommand);
  algorithm->AddObserver(vtkCommand::WarningEvent, this->WarningCommand);
}

void ErrorCapture::FailOnWatchedError() const
{
  if (!this->Error.empty())
  {
    Fail(this->Error);
  }
}

void ErrorCapture::FailOnAnyError() const
{
  this->FailOnWatchedError();
  if (!this->Window->First.empty())
  {
    Fail(Clean(this->Window->First.c_str()));
  }
  if (!this->LoggedError.empty())
  {
    Fail(this->LoggedError);
  }
}

std::string ErrorCapture::Clean(const char* text)
{
  std::string message = text ? text : "";
  const std::size_t colon = message.find("): ");
  if (colon != std::string::npos)
  {
    message = message.substr(colon + 3);
  }
  while (!message.empty() && (message.back() == '\n' || message.back() == '\r'))
  {
    message.pop_back();
  }
  return message.substr(0, message.find('\n'));
}

void ErrorCapture::OnError(vtkObject*, unsigned long, void* self, void* text)
{
  auto* capture = static_cast<ErrorCapture*>(self);
  if (capture->Error.empty())
  {
    capture->Error = Clean(static_cast<const char*>(text));
  }
}

void ErrorCapture::OnLog(void* self, const vtkLogger::Message& message)
{
  auto* capture = static_cast<ErrorCapture*>(self);
  if (capture->LoggedError.empty() && message.verbosity <= vtkLogger::VERBOSITY_ERROR)
  {
    capture->LoggedError = Clean(message.message);
  }
}

void ErrorCapture::OnWarning(vtkObject*, unsigned long, void* self, void* text)
{
  static_cast<ErrorCapture*>(self)->WarningLines.push_back(Clean(static_cast<const char*>(text)));
}

} // namespace mcxapp
