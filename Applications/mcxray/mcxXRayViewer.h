// The interactive X-ray viewer behind `mcxray view`: a volume rendered with
// vtkMCXXRayMapper, mouse camera control, TF window sliders and preset keys,
// an overlay with the sample count, frame time and error estimate, and
// progressive refinement while the view is still. Kept apart from main() so
// that a test can drive it with events.
#ifndef mcxXRayViewer_h
#define mcxXRayViewer_h

#include "vtkMCXTypes.h"
#include "vtkMCXXRayMapper.h" // for the index and sampler getters
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <string>

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
  vtkPiecewiseFunction* GetTransferFunction() { return this->TransferFunction; }
  vtkSliderWidget* GetCentreSlider() { return this->CentreSlider; }
  vtkSliderWidget* GetWidthSlider() { return this->WidthSlider; }
  int GetNumberOfFrames() const { return this->Frames; }

private:
  static void OnChar(vtkObject*, unsigned long, void* self, void*);
  static void OnTimer(vtkObject*, unsigned long, void* self, void*);
  static void OnSlider(vtkObject*, unsigned long, void* self, void*);
  static void OnRenderEnd(vtkObject*, unsigned long, void* self, void*);
  void AddSlider(
    vtkSliderWidget* slider, const char* title, double lowest, double highest, double y);
  void UpdateSlidersFromTransferFunction();

  std::string ErrorMessage;
  double DataRange[2] = { 0, 1 };
  double LastFrameSeconds = 0.0;
  int Frames = 0;
  bool OverlayCurrent = false;
  std::string OverlayState;
  vtkNew<vtkPiecewiseFunction> TransferFunction;
  vtkNew<vtkMCXXRayMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderWindowInteractor> Interactor;
  vtkNew<vtkTextActor> Overlay;
  vtkNew<vtkSliderWidget> CentreSlider;
  vtkNew<vtkSliderWidget> WidthSlider;
  vtkNew<vtkCallbackCommand> CharCommand;
  vtkNew<vtkCallbackCommand> TimerCommand;
  vtkNew<vtkCallbackCommand> SliderCommand;
  vtkNew<vtkCallbackCommand> RenderEndCommand;
};

} // namespace mcxapp

#endif
