/**
 * @class   vtkMCXViewProjector
 * @brief   ParaView's "X-Ray Projector": vtkMCXProjector that says a long
 *          run before it starts.
 *
 * A projection from a density index whose sample count will take more than
 * about 10 s (2^SampleExponent - 1 samples at about 15 M a second) warns in
 * one line with the count and the time before it starts, so that a GUI that
 * is busy for minutes has said why.
 */
#ifndef vtkMCXViewProjector_h
#define vtkMCXViewProjector_h

#include "MonteCarloXRayParaViewModule.h" // for export macro
#include "vtkMCXProjector.h"

class MONTECARLOXRAYPARAVIEW_EXPORT vtkMCXViewProjector : public vtkMCXProjector
{
public:
  static vtkMCXViewProjector* New();
  vtkTypeMacro(vtkMCXViewProjector, vtkMCXProjector);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkMCXViewProjector() = default;
  ~vtkMCXViewProjector() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMCXViewProjector(const vtkMCXViewProjector&) = delete;
  void operator=(const vtkMCXViewProjector&) = delete;
};

#endif
