// The interactive X-ray viewer behind `mcxray view`: a volume rendered with
// vtkMCXXRayMapper, mouse camera control, TF window sliders and preset keys,
// an overlay with the sample count, frame time and error estimate, and
// progressive refinement while the view is still. Kept apart from main() so
// that a test can drive it with events.
//
// The TF the keys and sliders set is a weight per data value. With radiograph
// physics on (key b, or Beer-Lambert, photons or -ln from the command line)
// the mapper samples an attenuation instead: mu of the HU (water 0.02 per mm,
// or --tf mu=MU_WATER) times the weight clamped to [0, 1], the raw preset
// selecting all tissue; --tf mu selects all tissue with physics off too.
//
// Polychromatic (SetPolychromatic, mcxray view --spectrum): the mapper samples
// the materials' density instead of any TF, so the TF sliders and presets are
// off; the image is the effective line integral -ln T, and key b shows the
// intensity I0 T instead.
#ifndef mcxXRayViewer_h
#define mcxXRayViewer_h

#include "vtkMCXTypes.h"
#include "vtkMCXXRayMapper.h" // for the index and sampler getters
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <string>

class vtkActor2D;
class vtkCallbackCommand;
class vtkImageData;
class vtkMCXDensityIndex;
class vtkMCXPointSampler;
class vtkMCXXRayMapper;
class vtkObject;
class vtkPiecewiseFunction;
class vtkRenderWindow;
class vtkRenderWindowInteractor;
class vtkRenderer;
class vtkSliderWidget;
class vtkTextActor;
class vtkVolume;

namespace mcxapp
{

struct ViewerOptions
{
  std::string TransferFunction = "raw";
  int SampleExponent = vtkMCXTypes::DefaultSampleExponent;
  int Strategy = vtkMCXTypes::HYBRID;
  int Kernel = vtkMCXTypes::TENT;
  int Deposit = vtkMCXTypes::FOOTPRINT;
  unsigned long long Seed = 0;
  double ReorderAngle = -1.0; // below 0: the mapper's default
  int Size[2] = { 768, 768 };
  bool OffScreen = false;
};

class XRayViewer
{
public:
  /// Builds the scene for `volume`; check Error() before use.
  XRayViewer(vtkImageData* volume, const ViewerOptions& options);
  ~XRayViewer();
  XRayViewer(const XRayViewer&) = delete;
  XRayViewer& operator=(const XRayViewer&) = delete;

  /// Why the viewer cannot run (empty when it can).
  const std::string& Error() const { return this->ErrorMessage; }

  /// Runs the interactive event loop until the window closes.
  void Start();

  /// Renders until every point counts (batch use); returns the number of renders.
  int RefineUntilComplete();

  /// Shows or hides the controls drawn over the X-ray (the overlay text and
  /// the TF sliders); a screenshot is the X-ray alone.
  void ShowControls(bool show);

  /// TF window on the density axis: 0 below centre - width / 2, rising
  /// linearly to 1 at centre + width / 2 and above (what the sliders set).
  void SetTransferFunctionWindow(double centre, double width);

  /// A preset by name (raw, bone, soft-tissue); false if unknown.
  bool ApplyPreset(const std::string& name);

  /// Switches the radiograph (key b): Beer-Lambert of the attenuation.
  void SetRadiograph(bool on);

  /// The polychromatic mode: the mapper's Spectrum, Materials and Detector
  /// (vtkMCXXRayMapper's texts); the TF controls are hidden.
  void SetPolychromatic(
    const std::string& spectrum, const std::string& materials, const std::string& detector);
  bool IsPolychromatic() const { return this->Polychromatic; }

  /// Brings the TF and the controls in line with the mapper's radiograph
  /// physics, after a change made on the mapper itself.
  void FollowRadiographPhysics();

  /// Seconds a frame may spend projecting while a slider is dragged
  /// (default 1/30); the render at the release has no such limit.
  void SetDragRenderTime(double seconds) { this->DragRenderTime = seconds; }

  /// What the overlay shows for the image on screen (with the last frame
  /// time, or without it: the part that says whether the overlay is stale).
  std::string OverlayText(bool withFrameTime = true) const;

  vtkRenderWindow* GetRenderWindow() { return this->Window; }
  vtkRenderWindowInteractor* GetInteractor() { return this->Interactor; }
  vtkRenderer* GetRenderer() { return this->Renderer; }
  vtkMCXXRayMapper* GetMapper() { return this->Mapper; }
  /// The mapper's own index and sampler (it indexes and samples the volume).
  vtkMCXDensityIndex* GetIndex() { return this->Mapper->GetDensityIndex(); }
  vtkMCXPointSampler* GetSampler() { return this->Mapper->GetPointSampler(); }
  /// The TF the mapper samples (the weight, or the radiograph's attenuation).
  vtkPiecewiseFunction* GetTransferFunction() { return this->TransferFunction; }
  /// The weight the keys and the sliders set.
  vtkPiecewiseFunction* GetWeight() { return this->Weight; }
  vtkSliderWidget* GetCentreSlider() { return this->CentreSlider; }
  vtkSliderWidget* GetWidthSlider() { return this->WidthSlider; }
  int GetNumberOfFrames() const { return this->Frames; }
  vtkTextActor* GetOverlay() { return this->Overlay; }

private:
  static void OnChar(vtkObject*, unsigned long, void* self, void*);
  static void OnTimer(vtkObject*, unsigned long, void* self, void*);
  static void OnSlider(vtkObject*, unsigned long, void* self, void*);
  static void OnRenderEnd(vtkObject*, unsigned long, void* self, void*);
  static void OnDragStart(vtkObject*, unsigned long, void* self, void*);
  static void OnDragEnd(vtkObject*, unsigned long, void* self, void*);
  bool ReadTransferFunctionOption(const std::string& spec);
  void SetUpOverlay();
  void AddSliderBacking();
  void AddSlider(
    vtkSliderWidget* slider, const char* title, double lowest, double highest, double y);
  void UpdateSlidersFromTransferFunction();
  bool HasRadiographPhysics() const;
  bool AirIsLight() const;
  void MatchControlsToFilm();
  void UpdateTransferFunction();
  void WarnIfNotHounsfield();

  std::string ErrorMessage;
  double DataRange[2] = { 0, 1 };
  std::string LabelFormat = "%.4g"; // "%.0f" for integer data
  double LastFrameSeconds = 0.0;
  double DragRenderTime = 1.0 / 30.0;
  bool WindowWasAutomatic = true;
  // The radiograph's attenuation: mu of water per world unit, the data
  // value of air, whether --tf mu asked for it, whether the weight selects
  // all tissue (the raw preset).
  double WaterAttenuation = 0.02;
  double AirValue = -1000.0;
  bool AttenuationAsked = false;
  bool WeightSelectsAll = false;
  bool NotHounsfieldWarned = false;
  bool Polychromatic = false;
  int Frames = 0;
  bool OverlayCurrent = false;
  std::string OverlayState;
  vtkNew<vtkPiecewiseFunction> Weight;
  vtkNew<vtkPiecewiseFunction> TransferFunction;
  vtkNew<vtkMCXXRayMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderWindowInteractor> Interactor;
  vtkNew<vtkTextActor> Overlay;
  vtkNew<vtkActor2D> SliderBacking;
  vtkNew<vtkSliderWidget> CentreSlider;
  vtkNew<vtkSliderWidget> WidthSlider;
  vtkNew<vtkCallbackCommand> CharCommand;
  vtkNew<vtkCallbackCommand> TimerCommand;
  vtkNew<vtkCallbackCommand> SliderCommand;
  vtkNew<vtkCallbackCommand> RenderEndCommand;
  vtkNew<vtkCallbackCommand> DragStartCommand;
  vtkNew<vtkCallbackCommand> DragEndCommand;
};

} // namespace mcxapp

#endif
