/**
 * @class   vtkMCXRadiograph
 * @brief   X-ray physics applied after accumulation: Beer-Lambert
 *          attenuation, quantum (Poisson) noise and the negative-log image.
 *
 * The input is a projector's image whose "LineIntegral" is the integral of
 * the linear attenuation coefficient mu along each ray (use
 * vtkMCXAttenuationFunction as the transfer function, mu per world unit).
 * Each effect is off unless asked for, and costs only its own work:
 * - nothing on: the input passes through unchanged (shallow copy);
 * - BeerLambert: point data "Intensity" = I0 exp(-LineIntegral);
 * - PhotonsPerPixel N > 0 (implies Beer-Lambert): the detector counts
 *   k ~ Poisson(N exp(-LineIntegral)) photons and Intensity = I0 k / N;
 *   the noise is seeded (NoiseSeed), the same for any number of threads;
 * - NegativeLog: point data "Attenuation" = -ln(Intensity / I0), the display
 *   radiologists read (dense is bright); without noise it equals the line
 *   integral. A pixel that counted no photons is given half a photon.
 * The line integrals must be of an attenuation per world unit (a few
 * through a body): Beer-Lambert or noise of an image whose positive line
 * integrals average above NotAttenuationMean (a 0-1 TF, not mu: a black
 * image) warns once, in one line; again only after an image that is an
 * attenuation's.
 * The input's arrays and field data are kept; the new array is the active
 * scalars. vtkMCXXRayMapper has the same five properties, with the same
 * names, defaults and ranges, for the image on screen.
 */
#ifndef vtkMCXRadiograph_h
#define vtkMCXRadiograph_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkMCXTypes.h" // for the array names and constants
#include "vtkImageAlgorithm.h"

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXRadiograph : public vtkImageAlgorithm
{
public:
  static vtkMCXRadiograph* New();
  vtkTypeMacro(vtkMCXRadiograph, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Attenuate: Intensity = I0 exp(-line integral) (default off). */
  vtkSetMacro(BeerLambert, bool);
  vtkGetMacro(BeerLambert, bool);
  vtkBooleanMacro(BeerLambert, bool);
  ///@}

  ///@{
  /** I0, the unattenuated intensity (default 1). */
  vtkSetClampMacro(IncidentIntensity, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(IncidentIntensity, double);
  ///@}

  /** Largest PhotonsPerPixel: Poisson counts stay exact in a double. */
  static constexpr double MaximumPhotonsPerPixel = 1e15;

  ///@{
  /** Photons reaching an unattenuated pixel; 0 (default) means no noise. */
  vtkSetClampMacro(PhotonsPerPixel, double, 0.0, MaximumPhotonsPerPixel);
  vtkGetMacro(PhotonsPerPixel, double);
  ///@}

  ///@{
  /** Seed of the noise, 0 to 2^63 - 1 (default 0). */
  vtkSetClampMacro(NoiseSeed, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(NoiseSeed, vtkTypeInt64);
  ///@}

  ///@{
  /** Output -ln(I / I0) as "Attenuation" (default off). */
  vtkSetMacro(NegativeLog, bool);
  vtkGetMacro(NegativeLog, bool);
  vtkBooleanMacro(NegativeLog, bool);
  ///@}

  /**
   * Above this mean positive line integral an image is not an attenuation's:
   * 400 mm of water (an adult's abdomen, side to side) at 50 keV (0.0227 per
   * mm) is 9.1, so a body's mean stays below 10 (bone is a small part of the
   * path), while exp(-20) ~ 2e-9 leaves an average pixel without a photon
   * even at 10^6 a pixel, about the most an unattenuated CT detector element
   * gets in one view (ln 10^6 ~ 14). A 0-1 weight through a body averages
   * about 100.
   */
  static constexpr double NotAttenuationMean = 20.0;

  /** True when some effect is on (else the filter passes its input through). */
  bool HasEffects();

protected:
  vtkMCXRadiograph();
  ~vtkMCXRadiograph() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool BeerLambert = false;
  double IncidentIntensity = 1.0;
  double PhotonsPerPixel = 0.0;
  vtkTypeInt64 NoiseSeed = 0;
  bool NegativeLog = false;
  bool ToldNotAttenuation = false; // the warning is given once

private:
  vtkMCXRadiograph(const vtkMCXRadiograph&) = delete;
  void operator=(const vtkMCXRadiograph&) = delete;
};

#endif
