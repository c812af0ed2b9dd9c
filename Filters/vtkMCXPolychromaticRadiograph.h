/**
 * @class   vtkMCXPolychromaticRadiograph
 * @brief   A polychromatic radiograph from one line-integral image per
 *          material: a tube spectrum, xraylib's attenuation and a detector.
 *
 * Input (port 0): one projection split into a channel per material, in the
 * order of Materials (vtkMCXProjector::SetNumberOfChannels with
 * vtkMCXMaterialWeights::FillFractionFunction's fractions under its
 * FillDensityFunction TF: its "ChannelLineIntegral" of density x fraction,
 * g/cm^3 x mm, from one sampling pass), or, repeated, one image per
 * material, each a LineIntegral (vtkMCXMaterialWeights weighs a stored
 * cloud's points for them). Per pixel the detected
 * signal relative to the open beam is T = sum_E w(E) exp(-sum_m (mu/rho)_m(E)
 * L_m), w = spectrum x detector response normalised (mcxPolychromaticModel.h),
 * and the output is what vtkMCXRadiograph makes of the effective line
 * integral -ln T: "Intensity" = I0 T, with Poisson noise of PhotonsPerPixel
 * photons (the spectrum's photons reaching an open pixel), or with
 * NegativeLog "Attenuation" = -ln(I / I0). "EffectiveLineIntegral" (-ln T)
 * is kept, and "ChannelLineIntegral", the channels (one component each,
 * named by its material). A Spectrum, Detector or effect change re-executes this filter
 * alone: the channels are not sampled again.
 */
#ifndef vtkMCXPolychromaticRadiograph_h
#define vtkMCXPolychromaticRadiograph_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkMCXRadiograph.h" // for MaximumPhotonsPerPixel

#include "vtkSmartPointer.h" // for the channel array

#include <memory> // for the model
#include <string> // for the model's key
#include <vector> // for the channels

class vtkDoubleArray;
namespace mcx
{
class PolychromaticModel;
}

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXPolychromaticRadiograph : public vtkImageAlgorithm
{
public:
  static vtkMCXPolychromaticRadiograph* New();
  vtkTypeMacro(vtkMCXPolychromaticRadiograph, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The tube: "<kV>kVp[,<mm>mm<material>...][,<deg>deg][,<keV>keV]" (default
   * "70kVp,2.5mmAl": IEC 60601-1-3's minimum total filtration of a
   * diagnostic tube) or a spectrum file of "energy_keV photons" lines.
   */
  vtkSetStringMacro(Spectrum);
  vtkGetStringMacro(Spectrum);
  ///@}

  ///@{
  /** "integrating" (default) or "counting", optionally ",<material>:<mm>[:<g/cm3>]". */
  vtkSetStringMacro(Detector);
  vtkGetStringMacro(Detector);
  ///@}

  ///@{
  /** The decomposition the channels were made with (default "default"). */
  vtkSetStringMacro(Materials);
  vtkGetStringMacro(Materials);
  ///@}

  ///@{
  /** I0, the open beam's intensity (default 1). */
  vtkSetClampMacro(IncidentIntensity, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(IncidentIntensity, double);
  ///@}

  ///@{
  /** Photons reaching an open pixel; 0 (default): no noise. */
  vtkSetClampMacro(PhotonsPerPixel, double, 0.0, vtkMCXRadiograph::MaximumPhotonsPerPixel);
  vtkGetMacro(PhotonsPerPixel, double);
  ///@}

  ///@{
  /** The noise's seed (default 0). */
  vtkSetClampMacro(NoiseSeed, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(NoiseSeed, vtkTypeInt64);
  ///@}

  ///@{
  /** "Attenuation" = -ln(I / I0) instead of "Intensity" (default off). */
  vtkSetMacro(NegativeLog, bool);
  vtkGetMacro(NegativeLog, bool);
  vtkBooleanMacro(NegativeLog, bool);
  ///@}

  /** The mean energy in keV of the spectrum (0 with an error when unusable). */
  double GetMeanEnergy();

protected:
  vtkMCXPolychromaticRadiograph();
  ~vtkMCXPolychromaticRadiograph() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMCXPolychromaticRadiograph(const vtkMCXPolychromaticRadiograph&) = delete;
  void operator=(const vtkMCXPolychromaticRadiograph&) = delete;

  // The channels' line integrals and estimated errors from the inputs
  // (false, reported, when they do not fit `materials`), and the output's
  // geometry and field data from the first.
  bool ReadChannels(vtkInformationVector* inputs, int materials, vtkImageData* output,
    std::vector<std::vector<double>>& values, std::vector<double>& channelErrors);

  // The channels' line integrals as one array, each component named by its
  // material (the output's "ChannelLineIntegral").
  vtkSmartPointer<vtkDoubleArray> ChannelArray(
    const std::vector<std::vector<double>>& values) const;

  // The model of Spectrum, Detector and Materials, rebuilt when they change.
  const mcx::PolychromaticModel* Model();

  char* Spectrum = nullptr;
  char* Detector = nullptr;
  char* Materials = nullptr;
  double IncidentIntensity = 1.0;
  double PhotonsPerPixel = 0.0;
  vtkTypeInt64 NoiseSeed = 0;
  bool NegativeLog = false;
  std::unique_ptr<mcx::PolychromaticModel> Cached;
  std::string CachedKey;
  std::vector<std::string> CachedNames; // the materials' xraylib names
  double CachedMeanEnergy = 0.0;
};

#endif
