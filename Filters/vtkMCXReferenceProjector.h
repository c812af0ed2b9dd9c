/**
 * @class   vtkMCXReferenceProjector
 * @brief   Exact X-ray projection of the reconstructed field: the ground
 *          truth for the Monte Carlo projectors.
 *
 * Computes the same estimand as vtkMCXProjector, deterministically: each
 * line integral of g is exact (per-cell Simpson integration of the trilinear
 * field for the tent kernel, exact segment lengths for the box kernel), and
 * the mean over a pixel's area uses S x S rays at the centres of a regular
 * subdivision of the pixel, with S = 1, 3, 9, 27, ... (nested, so each step
 * refines the last) until the relative RMS change of the image between two
 * steps is at most RelativeTolerance, or S reaches MaximumSubdivision
 * (then with a warning). An empty image is refined on: a volume thinner
 * than a pixel may lie between the rays.
 * The output's field data holds "EstimatedRelativeError" (that last change)
 * and "RaysPerPixelAxis" (S).
 *
 * Input: a vtkMCXDensityIndex output. The cost grows with the number of rays
 * times the number of cells a ray crosses.
 */
#ifndef vtkMCXReferenceProjector_h
#define vtkMCXReferenceProjector_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkMCXProjectorBase.h"

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXReferenceProjector : public vtkMCXProjectorBase
{
public:
  static vtkMCXReferenceProjector* New();
  vtkTypeMacro(vtkMCXReferenceProjector, vtkMCXProjectorBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Target relative RMS change between subdivision steps (default 1e-3). */
  vtkSetClampMacro(RelativeTolerance, double, 0.0, 1.0);
  vtkGetMacro(RelativeTolerance, double);
  ///@}

  ///@{
  /** Largest number of rays per pixel axis (default 27). */
  vtkSetClampMacro(MaximumSubdivision, int, 1, 729);
  vtkGetMacro(MaximumSubdivision, int);
  ///@}

protected:
  vtkMCXReferenceProjector();
  ~vtkMCXReferenceProjector() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double RelativeTolerance = 1e-3;
  int MaximumSubdivision = 27;

private:
  vtkMCXReferenceProjector(const vtkMCXReferenceProjector&) = delete;
  void operator=(const vtkMCXReferenceProjector&) = delete;
};

#endif
