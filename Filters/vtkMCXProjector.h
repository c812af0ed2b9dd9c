/**
 * @class   vtkMCXProjector
 * @brief   Monte Carlo X-ray projection: counts samples per pixel.
 *
 * With a density index (vtkMCXDensityIndex) as input it generates the
 * samples and projects them at once, without storing them (the paper's
 * off-line rendering); with a point cloud from vtkMCXPointSampler it projects
 * the stored points. Accumulation is exact (integer counts, or fixed point
 * for perspective weights, in 128 bits), so the image is bit-identical for any
 * number of threads. See vtkMCXProjectorBase for the view and the output.
 *
 * The output's field data carries "SampleCount", "SampleWeight" and
 * "Integral" of the samples that made the image.
 */
#ifndef vtkMCXProjector_h
#define vtkMCXProjector_h

#include "MonteCarloXRayModule.h" // for export macro
#include "vtkMCXProjectorBase.h"

class MONTECARLOXRAY_EXPORT vtkMCXProjector : public vtkMCXProjectorBase
{
public:
  static vtkMCXProjector* New();
  vtkTypeMacro(vtkMCXProjector, vtkMCXProjectorBase);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * With an index input: M = 2^SampleExponent - 1 samples (default m = 24),
   * the sampling strategy (vtkMCXPointSampler::HYBRID, MONTE_CARLO,
   * QUASI_MONTE_CARLO) and the seed. Ignored for a point-cloud input.
   */
  vtkSetClampMacro(SampleExponent, int, 0, 63);
  vtkGetMacro(SampleExponent, int);
  void SetNumberOfSamples(vtkTypeInt64 n);
  vtkTypeInt64 GetNumberOfSamples();
  vtkSetClampMacro(Strategy, int, 0, 2);
  vtkGetMacro(Strategy, int);
  vtkSetMacro(Seed, vtkTypeUInt64);
  vtkGetMacro(Seed, vtkTypeUInt64);
  ///@}

protected:
  vtkMCXProjector();
  ~vtkMCXProjector() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int SampleExponent = 24;
  int Strategy = 0;
  vtkTypeUInt64 Seed = 0;

private:
  vtkMCXProjector(const vtkMCXProjector&) = delete;
  void operator=(const vtkMCXProjector&) = delete;
};

#endif
