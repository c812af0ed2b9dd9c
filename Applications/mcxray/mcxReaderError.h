// The first error a reader reports, kept instead of printed, as one line:
// VTK's report "ERROR: In file, line N\nvtkClass (0x...): message" (vtk-dicom
// nests its parser's report in the reader's) comes down to its innermost
// message.
#ifndef mcxReaderError_h
#define mcxReaderError_h

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"

#include <string>

namespace mcxapp
{

struct ReaderError
{
  std::string Message; // empty until the reader reports an error

  explicit ReaderError(vtkAlgorithm* reader)
  {
    this->Command->SetClientData(&this->Message);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long, void* data, void* text)
      {
        auto* message = static_cast<std::string*>(data);
        if (message->empty() && text)
        {
          std::string report = static_cast<const char*>(text);
          const std::size_t colon = report.rfind("): ");
          report = colon == std::string::npos ? report : report.substr(colon + 3);
          *message = report.substr(0, report.find('\n'));
        }
      });
    reader->AddObserver(vtkCommand::ErrorEvent, this->Command);
  }

private:
  vtkNew<vtkCallbackCommand> Command;
};

} // namespace mcxapp

#endif
