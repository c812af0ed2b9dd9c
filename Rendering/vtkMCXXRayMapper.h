/**
 * @class   vtkMCXXRayMapper
 * @brief   Draws a volume, or a vtkMCXPointSampler point cloud, as an X-ray
 *          image of the renderer's active camera, refining progressively.
 *
 * A drop-in volume mapper: an application that shows a vtkImageData with
 * vtkSmartVolumeMapper switches to an X-ray by changing the mapper:
 * @code
 * vtkNew<vtkMCXXRayMapper> mapper;             // was vtkSmartVolumeMapper
 * mapper->SetInputConnection(reader->GetOutputPort());
 * volume->SetMapper(mapper);
 * volume->GetProperty()->SetScalarOpacity(tf); // X-ray weight per data value
 * renderWindow->Render();
 * @endcode
 * With image data as input the mapper owns the pipeline of the method: it
 * indexes the volume's density array (vtkMCXDensityIndex; the point scalars,
 * or the array chosen with SelectScalarArray and a field-data ScalarMode),
 * once, and samples it (vtkMCXPointSampler, with this mapper's
 * SampleExponent, Strategy, Kernel, Deposit and Seed) under the TF of the
 * vtkVolume's property: its scalar opacity function of component 0, read as
 * an X-ray weight g per data value (for radiograph physics an attenuation
 * coefficient per world unit, vtkMCXAttenuationFunction); colour,
 * shading and the opacity unit distance do not apply. A TF edit re-samples
 * in O(M) without re-indexing; a view-ordered strategy is sorted for the view
 * on the first render and again after a TF or setting change (not on camera
 * moves alone). A density index (vtkMCXDensityIndex's output) is taken as it
 * is, without indexing again.
 *
 * A point cloud input (vtkMCXPointSampler's output: points in Halton order,
 * carrying "Integral" in field data) is drawn as it is, and the property is
 * unused. Each render projects a prefix of 2^k - 1 points
 * for the active camera (parallel or perspective, the same geometry and
 * weights as vtkMCXProjector) at the viewport's resolution into an exact
 * integer accumulation buffer; pixel values are line integrals of g in TF
 * units times world length, so they do not change with zoom or viewport size.
 *
 * It is a volume mapper (for a vtkVolume) because volumes render after the
 * opaque and translucent geometry: the depth buffer is complete when the
 * mapper reads it, and ParaView and VTK treat the prop as the volume it
 * stands for. The vtkVolume's matrix moves the volume.
 *
 * Work follows what changed:
 * - a different camera, viewport, prop matrix, occluding depth or input
 *   restarts the projection (a TF edit re-samples the cloud, which is a new
 *   input; re-sampling does not re-index); the most refined image of
 *   another view of the same input is kept aside, and a render of that view
 *   again (a viewport resized and back, as ParaView's screenshot dialog
 *   does, or a camera set back) takes it back instead of restarting (the
 *   cost: a second accumulation buffer);
 * - a display change (window, level, inversion) only redraws the accumulated
 *   buffer;
 * - otherwise, with ProgressiveRefinement on, each render adds the largest
 *   prefix that fits the prop's allocated render time (1 / the render
 *   window's desired update rate) to the buffer, until all points count;
 *   IsRefinementComplete() tells an application when to stop asking for
 *   renders.
 *
 * When the renderer also holds visible opaque geometry, samples behind it in
 * the depth buffer do not count; without any, no depth work is done. A
 * cloud of voxel centres (vtkMCXTypes::FOOTPRINT) is deposited as
 * footprints, as vtkMCXProjector deposits it (the same image for the same
 * camera); behind opaque geometry a footprint is tested pixel by pixel at
 * its voxel centre's depth.
 *
 * Display: the image is mapped by a window and level (in line-integral units;
 * automatic by default: 0 to the 99.5th percentile of the 4 x 4 block means
 * of the image of the first 2^k - 1 points with at least 4 per pixel, once
 * per input) to a grey value g in [0, 1]. By default (FILM compositing) g is
 * drawn opaquely, as film, wherever no opaque geometry is in front, so the
 * picture is the same on any background; with InvertDisplay on, 1 - g (dark
 * bone on light film). ADDITIVE compositing adds g to what is behind it
 * (the X-ray as emitted light), or with InvertDisplay multiplies it by
 * 1 - g, for compositing with other props. Film is laid once per render of
 * a renderer, by its first X-ray: further X-rays (several volumes shown as
 * X-rays), and every X-ray over opaque geometry or in a renderer that holds
 * translucent props (which film would cover), blend additively.
 *
 * Polychromatic mode (Spectrum set, an image input in HU;
 * Documentation/polychromatic.md): the volume is sampled under the
 * materials' total density curve (Materials; vtkMCXMaterialWeights's
 * FillDensityFunction) instead of the property's TF, each point's deposit
 * is split into a channel per material by the mass fractions at its voxel
 * (Core/mcxChannelSplit.h, as vtkMCXProjector's channels: the channels add
 * up to the image of the points exactly, in the same pass), and the image
 * shown is the effective line
 * integral -ln T of the channels through the spectrum and the detector
 * (mcx::PolychromaticModel, as vtkMCXPolychromaticRadiograph; world units
 * taken as mm). The radiograph physics above then applies to -ln T. A
 * Spectrum or Detector change maps the accumulated channels again without
 * projecting or sampling again; a Materials change samples again. It needs
 * the footprint deposit and a strategy other than EVERY_VOXEL; another
 * view's image is kept aside with its channels.
 *
 * The accumulation runs on the CPU with vtkSMPTools; images are the same for
 * any number of threads.
 */
#ifndef vtkMCXXRayMapper_h
#define vtkMCXXRayMapper_h

#include "MonteCarloXRayRenderingModule.h" // for export macro
#include "vtkAbstractVolumeMapper.h"
#include "vtkMCXRadiograph.h" // for the radiograph limits
#include "vtkMCXTypes.h"      // for the sampling settings and limits

#include <string> // for SelectDensityArray

class vtkDataArray;
class vtkMCXDensityIndex;
class vtkMCXPointSampler;
class vtkImageData;
class vtkPolyData;
class vtkInformationIntegerKey;

class MONTECARLOXRAYRENDERING_EXPORT vtkMCXXRayMapper : public vtkAbstractVolumeMapper
{
public:
  static vtkMCXXRayMapper* New();
  vtkTypeMacro(vtkMCXXRayMapper, vtkAbstractVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The input: a volume (its density array is indexed and sampled here), a
   * density index, or a vtkMCXPointSampler's cloud. SetInputConnection
   * takes the same from a pipeline.
   */
  void SetInputData(vtkImageData* volume);
  void SetInputData(vtkPolyData* cloud);
  ///@}

  ///@{
  /**
   * How an image input is sampled (vtkMCXPointSampler's settings, defaults
   * and ranges): 2^SampleExponent - 1 points (default
   * vtkMCXTypes::DefaultSampleExponent), the strategy (HYBRID), the kernel
   * (TENT), the deposit (FOOTPRINT) and the seed (0). A point-cloud input
   * carries its own.
   */
  vtkSetClampMacro(SampleExponent, int, 0, vtkMCXTypes::MaximumPointCloudExponent);
  vtkGetMacro(SampleExponent, int);
  vtkSetClampMacro(Strategy, int, vtkMCXTypes::HYBRID, vtkMCXTypes::VIEW_ORDERED);
  vtkGetMacro(Strategy, int);
  vtkSetClampMacro(Kernel, int, vtkMCXTypes::TENT, vtkMCXTypes::BOX);
  vtkGetMacro(Kernel, int);
  vtkSetClampMacro(Deposit, int, vtkMCXTypes::POINT, vtkMCXTypes::FOOTPRINT);
  vtkGetMacro(Deposit, int);
  vtkSetClampMacro(Seed, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(Seed, vtkTypeInt64);
  ///@}

  ///@{
  /**
   * The VIEW_ORDERED strategy's vtkMCXPointSampler::ReorderAngle, in
   * degrees (0 to 180; default 30, where the sampler's is 0): a TF edit
   * after the camera turned about the volume by at most this much from the
   * view the voxels were last sorted for keeps that order and projects
   * only the control image of the view as it is, which on a 400 M-voxel CT
   * takes about an eighth of the sort's time, at more error for the same
   * points (the estimate shows it). A pan, a zoom or a resize sorts again;
   * so does every new view with 0.
   */
  vtkSetClampMacro(ReorderAngle, double, 0.0, 180.0);
  vtkGetMacro(ReorderAngle, double);
  ///@}

  ///@{
  /**
   * Window and level of the display, in line-integral units (TF units times
   * world length); used when AutomaticWindowLevel is off.
   */
  vtkSetClampMacro(ColorWindow, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ColorWindow, double);
  vtkSetMacro(ColorLevel, double);
  vtkGetMacro(ColorLevel, double);
  ///@}

  ///@{
  /**
   * Choose window and level for each input (default on): 0 to the 99.5th
   * percentile of the non-zero 4 x 4 block means of the image of its first
   * 2^k - 1 points, the smallest such prefix with at least 4 points per pixel
   * (or all points). The window does not depend on the sample count beyond
   * that prefix, on the time budget or on how far refinement has gone; a
   * camera change keeps it.
   */
  vtkSetMacro(AutomaticWindowLevel, bool);
  vtkGetMacro(AutomaticWindowLevel, bool);
  vtkBooleanMacro(AutomaticWindowLevel, bool);
  ///@}

  /** The window and level the last render used. */
  vtkGetMacro(DisplayedWindow, double);
  vtkGetMacro(DisplayedLevel, double);

  ///@{
  /** Show 1 - g: dark where the line integral is large (default off). */
  vtkSetMacro(InvertDisplay, bool);
  vtkGetMacro(InvertDisplay, bool);
  vtkBooleanMacro(InvertDisplay, bool);
  ///@}

  /** How the grey value meets what the renderer drew before. */
  enum
  {
    FILM = 0,    ///< opaque film where nothing opaque is in front (the default)
    ADDITIVE = 1 ///< added to the background (inverted: multiplied onto it)
  };

  ///@{
  /** FILM (default) or ADDITIVE; see the class description. */
  vtkSetClampMacro(Compositing, int, FILM, ADDITIVE);
  vtkGetMacro(Compositing, int);
  void SetCompositingToFilm() { this->SetCompositing(FILM); }
  void SetCompositingToAdditive() { this->SetCompositing(ADDITIVE); }
  ///@}

  ///@{
  /**
   * Set when a depth compositor merges this render with other processes'
   * (ParaView's IceT on a server of several processes, where one process
   * draws the X-ray and the others draw nothing of it): the image then
   * writes a depth just in front of the far plane where nothing opaque was
   * drawn, so that the compositor keeps it against the others' empty pixels
   * (which it takes for background); geometry in front still covers it.
   * Default off: the image writes no depth.
   */
  vtkSetMacro(CompositedByDepth, bool);
  vtkGetMacro(CompositedByDepth, bool);
  vtkBooleanMacro(CompositedByDepth, bool);
  ///@}

  ///@{
  /**
   * Radiograph physics on the accumulated image, as vtkMCXRadiograph applies
   * it off line (use vtkMCXAttenuationFunction as the TF): BeerLambert shows
   * I0 exp(-line integral); PhotonsPerPixel > 0 adds seeded Poisson noise;
   * NegativeLog shows -ln(I / I0). All off by default; a change re-maps the
   * buffer, it does not re-project. Names, defaults and ranges are
   * vtkMCXRadiograph's.
   */
  vtkSetMacro(BeerLambert, bool);
  vtkGetMacro(BeerLambert, bool);
  vtkBooleanMacro(BeerLambert, bool);
  vtkSetClampMacro(IncidentIntensity, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(IncidentIntensity, double);
  vtkSetClampMacro(PhotonsPerPixel, double, 0.0, vtkMCXRadiograph::MaximumPhotonsPerPixel);
  vtkGetMacro(PhotonsPerPixel, double);
  vtkSetClampMacro(NoiseSeed, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(NoiseSeed, vtkTypeInt64);
  vtkSetMacro(NegativeLog, bool);
  vtkGetMacro(NegativeLog, bool);
  vtkBooleanMacro(NegativeLog, bool);
  ///@}

  ///@{
  /**
   * The polychromatic mode (see the class description). Spectrum: the tube,
   * "<kV>kVp[,<mm>mm<element>...][,<deg>deg][,<keV>keV]" or a spectrum file
   * (vtkMCXPolychromaticRadiograph's syntax); null or empty (the default):
   * monochromatic, the property's TF. Materials: "default",
   * "default,iodine=<HU>,titanium=<HU>" or a materials file (default
   * "default"). Detector: "integrating" (default) or "counting", optionally
   * ",<material>:<mm>[:<g/cm3>]". A text that does not parse is an error
   * once, and nothing is drawn until it is fixed.
   */
  vtkSetStringMacro(Spectrum);
  vtkGetStringMacro(Spectrum);
  vtkSetStringMacro(Materials);
  vtkGetStringMacro(Materials);
  vtkSetStringMacro(Detector);
  vtkGetStringMacro(Detector);
  ///@}

  /** The channels of the image on screen: its materials, 0 when monochromatic. */
  int GetNumberOfChannels();

  /**
   * Channel m of the image on screen, laid out as GetLineIntegralImage's:
   * "LineIntegral" of material m's density x fraction (g/cm^3 x world
   * length), what vtkMCXProjector makes of vtkMCXMaterialWeights's cloud of
   * channel m but for the rounding of the split; field data SampleCount and the channel's
   * EstimatedRelativeError. Empty outside 0 .. GetNumberOfChannels() - 1.
   */
  void GetChannelImage(int m, vtkImageData* output);

  ///@{
  /**
   * Refine over several renders (default on). Off: every render that needs a
   * new image projects all points at once.
   */
  vtkSetMacro(ProgressiveRefinement, bool);
  vtkGetMacro(ProgressiveRefinement, bool);
  vtkBooleanMacro(ProgressiveRefinement, bool);
  ///@}

  ///@{
  /**
   * The most time one render may spend projecting points, in seconds (0,
   * the default: no limit beyond the prop's allocated render time). An
   * application sets it for interactive renders (ParaView's representation
   * does while the camera moves) so that a frame draws only the prefix that
   * fits, and clears it for the still render.
   */
  vtkSetClampMacro(MaximumRenderTime, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumRenderTime, double);
  ///@}

  ///@{
  /**
   * The first image after a change has at least 2^InitialSampleExponent - 1
   * points (default 14), however little time is allocated.
   */
  vtkSetClampMacro(InitialSampleExponent, int, 1, vtkMCXTypes::MaximumPointCloudExponent);
  vtkGetMacro(InitialSampleExponent, int);
  ///@}

  ///@{
  /**
   * For a footprint cloud (the FOOTPRINT deposit): a
   * kernel reaching more than this many pixels along a projected voxel axis
   * is split into a random coarse part and a deposited fine part (default 16,
   * 0.5 to 32; see vtkMCXProjector::SetFootprintReach).
   */
  vtkSetClampMacro(FootprintReach, double, 0.5, 32.0);
  vtkGetMacro(FootprintReach, double);
  ///@}

  /** Number of points in the image on screen. */
  vtkTypeInt64 GetNumberOfAccumulatedSamples();

  /**
   * For an image input: brings the input up to date and indexes it now
   * (otherwise the first render does), so that an application can show the
   * indexing's progress (observe GetDensityIndex()) before the first frame.
   */
  void UpdateDensityIndex();

  ///@{
  /**
   * The index and the sampler this mapper uses for an image input, for
   * progress observers and tests; set them up through the mapper's own
   * settings (they are overwritten at each render).
   */
  vtkMCXDensityIndex* GetDensityIndex();
  vtkMCXPointSampler* GetPointSampler();
  ///@}

  /**
   * Number of points of the cloud drawn (the input's, or the one sampled
   * from an image input); 0 before the first render.
   */
  vtkTypeInt64 GetNumberOfInputPoints();

  /** True when the image on screen holds every point of the input. */
  bool IsRefinementComplete();

  /**
   * Estimated relative RMS error of the image on screen, from its two
   * Halton halves (as vtkMCXProjector's EstimatedRelativeError); NaN before
   * the first render and for a non-empty cloud of every voxel (not
   * estimated).
   */
  double GetEstimatedRelativeError();

  /**
   * The image on screen in physical units: a 2D image laid out like
   * vtkMCXProjector's output (point data "LineIntegral", float64; pixel (0, 0)
   * at the viewport's lower left), with field data SampleCount and
   * EstimatedRelativeError; radiograph physics, when on, is not applied to
   * it (pass it through vtkMCXRadiograph). In the polychromatic mode the
   * values are the effective line integral -ln T, and the error is the one
   * propagated from the channels' (as vtkMCXPolychromaticRadiograph's).
   * Empty before the first render.
   */
  void GetLineIntegralImage(vtkImageData* output);

  ///@{
  /**
   * Work counters for tests and profiling: projections started from zero,
   * renders that added points, texture uploads, and draws.
   */
  vtkGetMacro(NumberOfRestarts, vtkTypeInt64);
  vtkGetMacro(NumberOfRefinements, vtkTypeInt64);
  vtkGetMacro(NumberOfUploads, vtkTypeInt64);
  vtkGetMacro(NumberOfDraws, vtkTypeInt64);
  ///@}

  /** True when the last render culled samples against opaque geometry. */
  vtkGetMacro(LastRenderUsedDepth, bool);

  /**
   * True when the image is the controlled estimate of a view-ordered cloud
   * (vtkMCXPointSampler::SetControlVariate): the camera and the size are
   * the cloud's ordering view, the prop's matrix is the identity and
   * nothing opaque hides the volume.
   */
  bool GetLastRenderUsedControlImage();

  /**
   * The volume's support (the sampler's SupportCorners), so that a camera
   * reset frames the volume even when the TF leaves the cloud empty; else
   * the points' bounds; uninitialised without points or support.
   */
  double* GetBounds() VTK_SIZEHINT(6) override;
  using vtkAbstractVolumeMapper::GetBounds;

  void Render(vtkRenderer* renderer, vtkVolume* volume) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkMCXXRayMapper();
  ~vtkMCXXRayMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  /** Seconds this render may spend projecting: allocated, capped by MaximumRenderTime. */
  double RenderTimeBudget(vtkVolume* volume) const;

  int SampleExponent = vtkMCXTypes::DefaultSampleExponent;
  int Strategy = vtkMCXTypes::HYBRID;
  int Kernel = vtkMCXTypes::TENT;
  int Deposit = vtkMCXTypes::FOOTPRINT;
  vtkTypeInt64 Seed = 0;
  double ReorderAngle = 30.0;
  double ColorWindow = 1.0;
  double ColorLevel = 0.5;
  bool AutomaticWindowLevel = true;
  double DisplayedWindow = 1.0;
  double DisplayedLevel = 0.5;
  bool InvertDisplay = false;
  int Compositing = FILM;
  bool CompositedByDepth = false;
  bool BeerLambert = false;
  double IncidentIntensity = 1.0;
  double PhotonsPerPixel = 0.0;
  vtkTypeInt64 NoiseSeed = 0;
  bool NegativeLog = false;
  bool ProgressiveRefinement = true;
  int InitialSampleExponent = 14;
  double MaximumRenderTime = 0.0;
  double FootprintReach = 16.0;
  char* Spectrum = nullptr;
  char* Materials = nullptr;
  char* Detector = nullptr;
  vtkTypeInt64 NumberOfRestarts = 0;
  vtkTypeInt64 NumberOfRefinements = 0;
  vtkTypeInt64 NumberOfUploads = 0;
  vtkTypeInt64 NumberOfDraws = 0;
  bool LastRenderUsedDepth = false;

private:
  vtkMCXXRayMapper(const vtkMCXXRayMapper&) = delete;

  // Render's work, which may throw std::bad_alloc (caught by Render: no
  // exception may reach ParaView or Python).
  void RenderImage(vtkRenderer* renderer, vtkVolume* volume);

  // In a renderer's information: whether an X-ray has laid its film in the
  // render in progress (reset by the renderer's StartEvent), and whether
  // that reset is installed.
  static vtkInformationIntegerKey* FILM_LAID();
  static vtkInformationIntegerKey* FILM_RESET_INSTALLED();
  bool TakeFilm(vtkRenderer* renderer, vtkVolume* volume);
  /// The one-component point array of image to index (the scalars, or the
  /// one SelectScalarArray chose); null with problem set when there is none.
  vtkDataArray* SelectDensityArray(vtkImageData* image, std::string& problem);
  /// The world corners of the input's support; false when it has none.
  bool SupportCorners(vtkDataObject* input, double corners[24]);
  /// Connects the index (a volume) and the sampler to an image input and
  /// applies the sampling settings; false, reported if asked, when the
  /// volume has no density array.
  bool ConnectImageInput(vtkImageData* image, bool report);
  void operator=(const vtkMCXXRayMapper&) = delete;

  struct vtkInternals;
  vtkInternals* Internals;
};

#endif
