/**
 * @class   vtkMCXAttenuationFunction
 * @brief   The transfer function from Hounsfield units to linear attenuation:
 *          mu = mu_water (1 + HU / 1000), 0 at and below air (-1000 HU).
 *
 * A helper, not a function itself: FillTransferFunction() writes the map
 * into a vtkPiecewiseFunction (replacing its points), which then serves as
 * the TF of a sampler or projector; each pixel holds the line integral of
 * mu, which vtkMCXRadiograph turns into a radiograph. Fill again after a
 * change of the parameters. mu_water sets the beam energy (default 0.02 per
 * mm, water at about 70 keV); the unit of mu is the inverse of the volume's
 * world unit (mm for DICOM and NIfTI). The function is exact (linear) over
 * HounsfieldRange and holds its end values beyond it.
 */
#ifndef vtkMCXAttenuationFunction_h
#define vtkMCXAttenuationFunction_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkObject.h"

class vtkPiecewiseFunction;

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXAttenuationFunction : public vtkObject
{
public:
  static vtkMCXAttenuationFunction* New();
  vtkTypeMacro(vtkMCXAttenuationFunction, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** mu of water per world unit (default 0.02, per mm at about 70 keV). */
  vtkSetClampMacro(WaterAttenuation, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(WaterAttenuation, double);
  ///@}

  ///@{
  /** The Hounsfield range the function is linear over (default -1024 to 3071). */
  void SetHounsfieldRange(double lowest, double highest);
  vtkGetVector2Macro(HounsfieldRange, double);
  ///@}

  /**
   * Replaces the points of `tf` by the map (and turns its clamping on);
   * an error and no change when `tf` is null.
   */
  void FillTransferFunction(vtkPiecewiseFunction* tf);

protected:
  vtkMCXAttenuationFunction() = default;
  ~vtkMCXAttenuationFunction() override = default;

  double WaterAttenuation = 0.02;
  double HounsfieldRange[2] = { -1024.0, 3071.0 };

private:
  vtkMCXAttenuationFunction(const vtkMCXAttenuationFunction&) = delete;
  void operator=(const vtkMCXAttenuationFunction&) = delete;
};

#endif
