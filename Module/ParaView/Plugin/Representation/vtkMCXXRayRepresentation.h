/**
 * @class   vtkMCXXRayRepresentation
 * @brief   ParaView's "Monte Carlo X-Ray" representation of image data.
 *
 * The data server builds the density index of the selected point array
 * (vtkMCXDensityIndex) and delivers it, without the voxel values, to the
 * rendering processes; there a vtkMCXXRayMapper takes it as its input,
 * samples it under the scalar opacity function of the colour-map editor (set
 * on its volume's property) and renders it in the view, refining
 * progressively. An opacity edit re-samples only; it neither re-indexes nor
 * re-delivers the data.
 *
 * On a parallel server (pvserver or pvbatch under mpirun) each process reads
 * and indexes only its z-slab of the volume, and the slabs' indices are
 * gathered onto the first process (vtkMCXAggregateIndex): the index of the
 * whole volume, the same as one process's. X-ray images add rather than
 * depth-composite, so the first process draws the whole image and the others
 * draw nothing of it; the server renders (IceT keeps the first process's
 * pixels) and the picture is the serial one. The first process holds the
 * whole index (4 bytes a voxel); an image of a volume whose index outgrows
 * one machine is the X-Ray Projector's (vtkMCXProjector), which keeps the
 * index distributed.
 */
#ifndef vtkMCXXRayRepresentation_h
#define vtkMCXXRayRepresentation_h

#include "MonteCarloXRayParaViewModule.h" // for export macro
#include "vtkNew.h"                       // for members
#include "vtkPVDataRepresentation.h"
#include "vtkSmartPointer.h" // for members

class vtkImageData;
class vtkPolyData;
class vtkPVRenderView;
class vtkMCXAggregateIndex;
class vtkMCXDensityIndex;
class vtkMCXXRayMapper;
class vtkPiecewiseFunction;
class vtkTrivialProducer;
class vtkVolume;

class MONTECARLOXRAYPARAVIEW_EXPORT vtkMCXXRayRepresentation : public vtkPVDataRepresentation
{
public:
  static vtkMCXXRayRepresentation* New();
  vtkTypeMacro(vtkMCXXRayRepresentation, vtkPVDataRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(
    vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo) override;
  void SetVisibility(bool visible) override;

  /**
   * The TF from data values to g: the colour map's scalar opacity function.
   * Without one (not coloured by an array yet), a ramp from 0 at
   * DefaultRampStart (the lowest density; -200 for CT in HU) to 1 at the
   * highest.
   */
  void SetScalarOpacityFunction(vtkPiecewiseFunction* function);

  ///@{
  /** Forwarded to the mapper (see vtkMCXXRayMapper's sampling settings). */
  void SetSampleExponent(int exponent);
  void SetStrategy(int strategy);
  void SetKernel(int kernel);
  void SetDeposit(int deposit);
  void SetSeed(vtkTypeInt64 seed);
  void SetReorderAngle(double degrees);
  ///@}

  ///@{
  /** Forwarded to the mapper (see vtkMCXXRayMapper). */
  void SetInvertDisplay(bool invert);
  void SetCompositing(int compositing);
  void SetColorWindow(double window);
  void SetColorLevel(double level);
  void SetProgressiveRefinement(bool progressive);
  ///@}

  ///@{
  /**
   * The automatic window (default on), forwarded to the mapper; turning it
   * off starts the manual window and level where the displayed ones are, so
   * that the picture does not jump (a window or level set afterwards, or in
   * the same update as ParaView pushes them, replaces them).
   */
  void SetAutomaticWindowLevel(bool automatic);
  ///@}

  ///@{
  /** The window and level the last render used (the panel's X-Ray Window/Level information). */
  double GetDisplayedWindow();
  double GetDisplayedLevel();
  ///@}

  /** What the mapper samples: the TF itself, or the attenuation of the tissue it weighs. */
  enum AttenuationModes
  {
    WEIGHT_ONLY = 0, ///< g = TF(value): the TF is the sampled quantity (any units)
    HU_TO_MU = 1     ///< g = mu(HU) x TF(value), the TF a 0-1 weight
  };

  ///@{
  /**
   * The attenuation mode (default WEIGHT_ONLY). With HU_TO_MU the mapper
   * samples mu(HU) x TF, mcxray's `--tf mu` map (vtkMCXAttenuationFunction:
   * mu = WaterAttenuation (1 + HU / 1000) per world unit, 0 at and below
   * air) times the opacity editor's TF clamped to [0, 1]; the same
   * composition as `mcxray view`'s key `b` (mcxapp::MakeWeightedAttenuation).
   * Pixels then hold line integrals of mu (per mm x mm: dimensionless), so
   * Beer-Lambert, noise and the negative log read in physical units. Values
   * are taken as HU when the lowest density is at or below -500, else the
   * lowest density is air (-1000 HU).
   */
  void SetAttenuation(int mode); // clamped to WEIGHT_ONLY-HU_TO_MU
  vtkGetMacro(Attenuation, int);
  ///@}

  ///@{
  /**
   * mu of water per world unit in the HU_TO_MU mode (default 0.02 per mm,
   * about 70 keV; 0.0227 at 50 keV, 0.0184 at 80 keV, 0.0171 at 100 keV;
   * clamped to 0.001-1).
   */
  vtkSetClampMacro(WaterAttenuation, double, 0.001, 1.0);
  vtkGetMacro(WaterAttenuation, double);
  ///@}

  ///@{
  /**
   * Radiograph physics, forwarded to the mapper (vtkMCXXRayMapper's
   * BeerLambert, PhotonsPerPixel, NegativeLog). They need pixels in line
   * integrals of an attenuation coefficient: Beer-Lambert or noise with
   * Attenuation WEIGHT_ONLY and a TF above 0.1 (not an attenuation per mm)
   * warns once, in one line, at the first render; again only after the
   * combination is entered anew (Beer-Lambert or noise turned on,
   * Attenuation turned off, another TF object), not at TF edits.
   */
  void SetBeerLambert(bool on);
  void SetPhotonsPerPixel(double photons);
  void SetNegativeLog(bool on);
  ///@}

  ///@{
  /**
   * The polychromatic X-ray, forwarded to the mapper (vtkMCXXRayMapper's
   * Spectrum, Materials and Detector): an empty spectrum (the default) is
   * monochromatic; set, the mapper samples the materials' density of the
   * delivered index (the TF and Attenuation do not apply) and shows -ln T.
   */
  void SetSpectrum(const char* spectrum);
  void SetMaterials(const char* materials);
  void SetDetector(const char* detector);
  ///@}

  ///@{
  /**
   * Seconds a frame may spend projecting points while the camera moves
   * (default 0.05: 20 frames a second, 0.001 to 10); the still render draws
   * them all. Camera motion counts as interactive when ParaView uses its
   * LOD path: the representation reports the drawn cloud's size (12 bytes a
   * point) as its data size, so with many points ParaView also uses the
   * other representations' LOD geometry and, in client-server sessions,
   * remote rendering (both decided by ParaView's size thresholds). The first
   * render after a TF edit projects the automatic window's prefix (4 points
   * a pixel) whatever the budget.
   */
  void SetInteractiveRenderTime(double seconds);
  double GetInteractiveRenderTime() const { return this->InteractiveRenderTime; }
  ///@}

  ///@{
  /**
   * With ParaView's streaming on (its general setting EnableStreaming), the seconds
   * a still render may spend projecting points (default 0.5); the streaming
   * passes that follow add the rest, render by render, without user action.
   * Without streaming a still render draws every point.
   */
  void SetStillRenderTime(double seconds);
  double GetStillRenderTime() const { return this->StillRenderTime; }
  void SetFootprintReach(double reach);
  ///@}

  /**
   * Where the default TF's ramp starts for densities from low to high: for
   * CT in Hounsfield units (low below -500, high above 1000) at -200 HU, so
   * that air and padding weigh nothing and fat little, and bone and soft
   * tissue read on the first picture; else at the lowest density.
   */
  static double DefaultRampStart(double low, double high)
  {
    return low < -500.0 && high > 1000.0 ? -200.0 : low;
  }

  /** The mapper, for tests and scripts. */
  vtkMCXXRayMapper* GetMapper();

protected:
  vtkMCXXRayRepresentation();
  ~vtkMCXXRayRepresentation() override;

  /// A vtkMCXXRayRepresentationExecutive: on a parallel server a reader that
  /// fails on one process still runs RequestData there, which tells the others.
  vtkExecutive* CreateDefaultExecutive() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;

  vtkNew<vtkTrivialProducer> Slab; // this process's part of the input, with the whole extent
  vtkNew<vtkMCXDensityIndex> Index;
  vtkNew<vtkMCXAggregateIndex> Aggregate; // the whole index, on the first process
  vtkNew<vtkMCXXRayMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkSmartPointer<vtkImageData> DeliveredIndex;
  // Delivered where there is no index (a client of a remote server, a failed
  // update): ParaView's delivery of streamed pieces needs a data object on
  // every process that gets them.
  vtkNew<vtkImageData> NoIndex;
  vtkSmartPointer<vtkPiecewiseFunction> OpacityFunction; // the colour map's, if any
  vtkNew<vtkPiecewiseFunction> DefaultRamp;              // else this, over the densities
  double DataBounds[6];
  double InteractiveRenderTime = 0.05;
  double StillRenderTime = 0.5;
  vtkNew<vtkPolyData> MorePointsToken; // the streamed "piece": more points to show
  vtkTypeInt64 StreamedProgress = -1;  // the mapper's projecting renders at the last streaming pass
  bool ToldServerCannotRender = false; // the warning is given once
  int Attenuation = WEIGHT_ONLY;
  double WaterAttenuation = 0.02;
  vtkNew<vtkPiecewiseFunction> WeightedAttenuation; // mu(HU) x TF, in the HU_TO_MU mode
  // What it was made of: the weight (compared, not held), its time, mu of water, the densities.
  vtkPiecewiseFunction* WeightedAttenuationOf = nullptr;
  vtkMTimeType WeightedAttenuationTime = 0;
  double WeightedAttenuationWater = 0.0;
  double WeightedAttenuationRange[2] = { 0.0, 0.0 }; // the densities it was made for
  bool ToldNotAttenuation = false;                   // the warning is given once

private:
  vtkMCXXRayRepresentation(const vtkMCXXRayRepresentation&) = delete;
  void UseDefaultRampUnlessColoured(vtkImageData* index);
  void UseSampledFunction(vtkImageData* index); // the TF, or mu(HU) x the TF
  bool ServerRenders(); // the view's server processes can render
  void operator=(const vtkMCXXRayRepresentation&) = delete;
};

#endif
