/**
 * @class   vtkMCXFirstErrorObserver
 * @brief   Keeps the first error an algorithm reports, as one line.
 *
 * Observe vtkCommand::ErrorEvent with it: VTK's report
 * "ERROR: In file, line N\nvtkClass (0x...): message" comes down to its
 * message's first line, and a report that nests another (vtk-dicom's
 * reader repeats its parser's) to the innermost one. Later errors are
 * ignored until Clear(). The report is then not printed: a program can say
 * it once, in its own words. ObserveAlgorithm() watches an algorithm and its
 * executive (whose "returned failure" report would otherwise be printed);
 * StopObserving() lets them go (the observed hold the observer).
 */
#ifndef vtkMCXFirstErrorObserver_h
#define vtkMCXFirstErrorObserver_h

#include "MonteCarloXRayIOModule.h" // for export macro
#include "vtkCommand.h"

class vtkAlgorithm;

#include <string> // for std::string

class MONTECARLOXRAYIO_EXPORT vtkMCXFirstErrorObserver : public vtkCommand
{
public:
  static vtkMCXFirstErrorObserver* New();
  vtkTypeMacro(vtkMCXFirstErrorObserver, vtkCommand);

  void Execute(vtkObject* caller, unsigned long event, void* callData) override;

  /** The first error's message since construction or Clear(); empty if none. */
  const std::string& GetErrorText() const { return this->Message; }

  /** Observes the errors of the algorithm and of its executive. */
  void ObserveAlgorithm(vtkAlgorithm* algorithm);

  /** Removes this observer from what ObserveAlgorithm() watched. */
  void StopObserving();

  /** Forgets the error kept so far. */
  void Clear() { this->Message.clear(); }

  /** The message of a VTK error report: the text after its innermost "(0x...): ", first line only. */
  static std::string MessageOf(const std::string& report);

protected:
  vtkMCXFirstErrorObserver() = default;
  ~vtkMCXFirstErrorObserver() override = default;

private:
  vtkMCXFirstErrorObserver(const vtkMCXFirstErrorObserver&) = delete;
  void operator=(const vtkMCXFirstErrorObserver&) = delete;

  std::string Message;
  vtkAlgorithm* Algorithm = nullptr;
  vtkObject* Executive = nullptr;
  unsigned long AlgorithmTag = 0;
  unsigned long ExecutiveTag = 0;
};

#endif
