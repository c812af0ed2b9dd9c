#include "mcxXRayViewer.h"

#include "mcxTransferFunctionSpec.h"

#include "vtkActor2D.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkCoordinate.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkMCXXRayMapper.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper2D.h"
#include "vtkProperty2D.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSliderRepresentation2D.h"
#include "vtkSliderWidget.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace mcxapp
{

namespace
{
// Frames per second the renderer aims at while interacting and while
// refining: each render adds the points that fit 1/30 s.
constexpr double InteractiveRate = 30.0;
constexpr int MaximumViewerExponent = 28;

const char* const KeyHelp =
  "keys: 1 raw (all), 2 bone, 3 soft tissue, +/- points, i invert, "
  "b radiograph (Beer-Lambert of mu(HU) x TF), p projection, r reset camera, q quit";
const char* const PolychromaticKeyHelp =
  "keys: +/- points, i invert, b intensity I0 T / -ln T, p projection, r reset camera, q quit";

// The controls' ink on dark film; on light film each colour is inverted, as
// the film is, and drawn on a light backing instead of a dark one.
const double OverlayInk[3] = { 1.0, 0.85, 0.2 };
const double SliderInk[3] = { 1.0, 1.0, 1.0 };
const double SelectedInk[3] = { 1.0, 0.2, 0.2 };
// Behind the controls the film keeps 30 % of its contrast: the ink reads at
// a WCAG contrast of 4.5 or more whatever film lies behind it.
constexpr double BackingOpacity = 0.7;
// The backing behind the sliders, their labels and titles (normalized viewport).
const double SliderBackingBox[4] = { 0.2, 0.98, 0.01, 0.25 };

void SetColour(const double ink[3], bool inverted, double colour[3])
{
  for (int c = 0; c < 3; ++c)
  {
    colour[c] = inverted ? 1.0 - ink[c] : ink[c];
  }
}

void SetTextInk(vtkTextProperty* text, const double ink[3], bool inverted)
{
  double colour[3];
  SetColour(ink, inverted, colour);
  text->SetColor(colour);
}

void SetPropertyInk(vtkProperty2D* property, const double ink[3], bool inverted)
{
  double colour[3];
  SetColour(ink, inverted, colour);
  property->SetColor(colour);
}

// What the window's values are.
const char* DisplayedQuantity(vtkMCXXRayMapper* mapper)
{
  if (mapper->GetNegativeLog())
  {
    return "-ln I/I0";
  }
  if (mapper->GetBeerLambert() || mapper->GetPhotonsPerPixel() > 0)
  {
    return "intensity I";
  }
  return mapper->GetSpectrum() && *mapper->GetSpectrum() ? "-ln T" : "TF x length";
}

bool IsIntegerType(int type)
{
  return type != VTK_FLOAT && type != VTK_DOUBLE;
}

std::string Thousands(long long n)
{
  std::string digits = std::to_string(n);
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3)
  {
    digits.insert(static_cast<std::size_t>(i), ",");
  }
  return digits;
}
}

XRayViewer::XRayViewer(vtkImageData* volume, const ViewerOptions& options)
{
  vtkDataArray* scalars = volume ? volume->GetPointData()->GetScalars() : nullptr;
  if (!scalars)
  {
    this->ErrorMessage = "the volume has no scalars";
    return;
  }
  scalars->GetRange(this->DataRange);
  if (IsIntegerType(scalars->GetDataType()))
  {
    this->LabelFormat = "%.0f";
  }
  this->AirValue = AirValueOf(this->DataRange);
  if (!this->ReadTransferFunctionOption(options.TransferFunction))
  {
    return;
  }

  // The mapper indexes and samples the volume under the property's TF.
  this->Mapper->SetInputData(volume);
  this->Mapper->SetSampleExponent(options.SampleExponent);
  this->Mapper->SetStrategy(options.Strategy);
  this->Mapper->SetKernel(options.Kernel);
  this->Mapper->SetDeposit(options.Deposit);
  this->Mapper->SetSeed(static_cast<vtkTypeInt64>(options.Seed));
  if (options.ReorderAngle >= 0)
  {
    this->Mapper->SetReorderAngle(options.ReorderAngle);
  }
  this->Volume->GetProperty()->SetScalarOpacity(this->TransferFunction);
  this->Volume->SetMapper(this->Mapper);
  this->Renderer->AddVolume(this->Volume);
  this->Renderer->SetBackground(0, 0, 0);
  this->SetUpOverlay();

  this->Window->SetSize(options.Size[0], options.Size[1]);
  this->Window->SetOffScreenRendering(options.OffScreen ? 1 : 0);
  this->Window->SetMultiSamples(0);
  this->Window->SetWindowName("mcxray view");
  this->Window->AddRenderer(this->Renderer);
  this->Interactor->SetRenderWindow(this->Window);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  this->Interactor->SetInteractorStyle(style);
  this->Interactor->SetDesiredUpdateRate(InteractiveRate);
  this->Interactor->SetStillUpdateRate(InteractiveRate);

  // A radiograph-like start: looking along +y at the volume, z up.
  vtkCamera* camera = this->Renderer->GetActiveCamera();
  double bounds[6];
  volume->GetBounds(bounds);
  const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0], centre[1] - 1.0, centre[2]);
  camera->SetViewUp(0, 0, 1);
  this->Renderer->ResetCamera(bounds);

  // Density-axis sliders span the data range; the width may reach all of it.
  const double span =
    this->DataRange[1] > this->DataRange[0] ? this->DataRange[1] - this->DataRange[0] : 1.0;
  // Each slider's value sits above its track and its title below: 0.13 of
  // the window apart, the upper title stays clear of the lower value. The
  // backing goes first: it is drawn under them.
  this->AddSliderBacking();
  this->AddSlider(this->CentreSlider, "TF centre", this->DataRange[0], this->DataRange[1], 0.19);
  this->AddSlider(this->WidthSlider, "TF width", span / 1000.0, 2.0 * span, 0.06);
  this->UpdateSlidersFromTransferFunction();
  this->MatchControlsToFilm();

  // Our key handler runs before the style's and swallows the keys it uses
  // (the style would toggle stereo on '3' and pick on 'p').
  this->CharCommand->SetClientData(this);
  this->CharCommand->SetCallback(&XRayViewer::OnChar);
  this->Interactor->AddObserver(vtkCommand::CharEvent, this->CharCommand, 1.0);
  this->TimerCommand->SetClientData(this);
  this->TimerCommand->SetCallback(&XRayViewer::OnTimer);
  this->Interactor->AddObserver(vtkCommand::TimerEvent, this->TimerCommand);
  this->RenderEndCommand->SetClientData(this);
  this->RenderEndCommand->SetCallback(&XRayViewer::OnRenderEnd);
  this->Renderer->AddObserver(vtkCommand::EndEvent, this->RenderEndCommand);
  this->Overlay->SetInput(KeyHelp);
}

// --tf: a weight (a preset or points), or mu: all tissue, as attenuation.
bool XRayViewer::ReadTransferFunctionOption(const std::string& spec)
{
  std::string error;
  vtkSmartPointer<vtkPiecewiseFunction> tf = MakeTransferFunction(spec, this->DataRange, error);
  if (!tf)
  {
    this->ErrorMessage = error;
    return false;
  }
  this->AttenuationAsked = IsAttenuationSpec(spec);
  if (this->AttenuationAsked)
  {
    this->WaterAttenuation = tf->GetValue(0.0); // mu at 0 HU
    tf = MakeTransferFunction("raw", this->DataRange, error);
  }
  this->WeightSelectsAll = spec == "raw" || this->AttenuationAsked;
  this->Weight->DeepCopy(tf);
  this->UpdateTransferFunction();
  return true;
}

// Text on a backing box that follows the film (MatchControlsToFilm).
void XRayViewer::SetUpOverlay()
{
  vtkTextProperty* text = this->Overlay->GetTextProperty();
  text->SetFontSize(14);
  text->SetVerticalJustificationToTop();
  text->SetBackgroundOpacity(BackingOpacity);
  this->Overlay->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  this->Overlay->SetPosition(0.01, 0.99);
  this->Renderer->AddActor2D(this->Overlay);
}

void XRayViewer::AddSliderBacking()
{
  const double* box = SliderBackingBox;
  vtkNew<vtkPoints> corners;
  corners->InsertNextPoint(box[0], box[2], 0);
  corners->InsertNextPoint(box[1], box[2], 0);
  corners->InsertNextPoint(box[1], box[3], 0);
  corners->InsertNextPoint(box[0], box[3], 0);
  vtkNew<vtkCellArray> quad;
  const vtkIdType ids[4] = { 0, 1, 2, 3 };
  quad->InsertNextCell(4, ids);
  vtkNew<vtkPolyData> rectangle;
  rectangle->SetPoints(corners);
  rectangle->SetPolys(quad);
  vtkNew<vtkCoordinate> viewport;
  viewport->SetCoordinateSystemToNormalizedViewport();
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(rectangle);
  mapper->SetTransformCoordinate(viewport);
  this->SliderBacking->SetMapper(mapper);
  this->SliderBacking->GetProperty()->SetOpacity(BackingOpacity);
  this->Renderer->AddActor2D(this->SliderBacking);
}

XRayViewer::~XRayViewer() = default;

void XRayViewer::AddSlider(
  vtkSliderWidget* slider, const char* title, double lowest, double highest, double y)
{
  vtkNew<vtkSliderRepresentation2D> representation;
  representation->SetMinimumValue(lowest);
  representation->SetMaximumValue(highest);
  representation->SetTitleText(title);
  representation->GetPoint1Coordinate()->SetCoordinateSystemToNormalizedDisplay();
  representation->GetPoint1Coordinate()->SetValue(0.25, y);
  representation->GetPoint2Coordinate()->SetCoordinateSystemToNormalizedDisplay();
  representation->GetPoint2Coordinate()->SetValue(0.95, y);
  representation->SetSliderLength(0.02);
  representation->SetSliderWidth(0.02);
  representation->SetTubeWidth(0.005);
  representation->SetTitleHeight(0.02);
  representation->SetLabelHeight(0.02);
  representation->SetLabelFormat(this->LabelFormat.c_str());
  slider->SetInteractor(this->Interactor);
  slider->SetRepresentation(representation);
  slider->SetAnimationModeToJump();
  this->SliderCommand->SetClientData(this);
  this->SliderCommand->SetCallback(&XRayViewer::OnSlider);
  slider->AddObserver(vtkCommand::InteractionEvent, this->SliderCommand);
  this->DragStartCommand->SetClientData(this);
  this->DragStartCommand->SetCallback(&XRayViewer::OnDragStart);
  slider->AddObserver(vtkCommand::StartInteractionEvent, this->DragStartCommand);
  this->DragEndCommand->SetClientData(this);
  this->DragEndCommand->SetCallback(&XRayViewer::OnDragEnd);
  slider->AddObserver(vtkCommand::EndInteractionEvent, this->DragEndCommand);
  slider->EnabledOn();
}

void XRayViewer::UpdateSlidersFromTransferFunction()
{
  double range[2];
  this->Weight->GetRange(range);
  auto* centre = vtkSliderRepresentation2D::SafeDownCast(this->CentreSlider->GetRepresentation());
  auto* width = vtkSliderRepresentation2D::SafeDownCast(this->WidthSlider->GetRepresentation());
  centre->SetValue(0.5 * (range[0] + range[1]));
  width->SetValue(range[1] - range[0]);
}

void XRayViewer::SetTransferFunctionWindow(double centre, double width)
{
  width = std::max(width, 1e-12 * std::max(1.0, std::fabs(centre)));
  // One Modified() for the whole edit: the sampler runs once.
  const double points[4] = { centre - 0.5 * width, 0.0, centre + 0.5 * width, 1.0 };
  vtkNew<vtkPiecewiseFunction> window;
  window->ClampingOn();
  window->AddPoint(points[0], points[1]);
  window->AddPoint(points[2], points[3]);
  this->Weight->DeepCopy(window);
  this->WeightSelectsAll = false;
  this->UpdateTransferFunction();
}

bool XRayViewer::ApplyPreset(const std::string& name)
{
  std::string error;
  vtkSmartPointer<vtkPiecewiseFunction> tf = MakeTransferFunction(name, this->DataRange, error);
  if (!tf || (name != "raw" && name != "bone" && name != "soft-tissue"))
  {
    return false;
  }
  this->Weight->DeepCopy(tf);
  this->WeightSelectsAll = name == "raw";
  this->UpdateTransferFunction();
  this->UpdateSlidersFromTransferFunction();
  return true;
}

void XRayViewer::SetRadiograph(bool on)
{
  this->Mapper->SetBeerLambert(on);
  this->FollowRadiographPhysics();
}

void XRayViewer::FollowRadiographPhysics()
{
  this->UpdateTransferFunction();
  this->MatchControlsToFilm();
}

bool XRayViewer::HasRadiographPhysics() const
{
  vtkMCXXRayMapper* mapper = this->Mapper;
  return mapper->GetBeerLambert() || mapper->GetPhotonsPerPixel() > 0 || mapper->GetNegativeLog();
}

// Air shows the intensity I0 (light) in a Beer-Lambert image, 0 (dark) in
// a line-integral or -ln image; inverting swaps them.
bool XRayViewer::AirIsLight() const
{
  vtkMCXXRayMapper* mapper = this->Mapper;
  const bool intensity =
    (mapper->GetBeerLambert() || mapper->GetPhotonsPerPixel() > 0) && !mapper->GetNegativeLog();
  return intensity != mapper->GetInvertDisplay();
}

// The controls invert with the film: light ink on a dark backing over dark
// air, dark ink on a light backing over light air.
void XRayViewer::MatchControlsToFilm()
{
  const bool light = this->AirIsLight();
  const double paper = light ? 1.0 : 0.0;
  this->Renderer->SetBackground(paper, paper, paper);
  vtkTextProperty* text = this->Overlay->GetTextProperty();
  SetTextInk(text, OverlayInk, light);
  text->SetBackgroundColor(paper, paper, paper);
  this->SliderBacking->GetProperty()->SetColor(paper, paper, paper);
  for (vtkSliderWidget* slider : { this->CentreSlider.Get(), this->WidthSlider.Get() })
  {
    auto* representation = vtkSliderRepresentation2D::SafeDownCast(slider->GetRepresentation());
    SetPropertyInk(representation->GetSliderProperty(), SliderInk, light);
    SetPropertyInk(representation->GetTubeProperty(), SliderInk, light);
    SetPropertyInk(representation->GetCapProperty(), SliderInk, light);
    SetPropertyInk(representation->GetSelectedProperty(), SelectedInk, light);
    SetTextInk(representation->GetLabelProperty(), SliderInk, light);
    SetTextInk(representation->GetTitleProperty(), SliderInk, light);
  }
}

// The mapper samples the weight, or with radiograph physics the attenuation
// of the tissue the weight selects; one Modified() per change.
void XRayViewer::UpdateTransferFunction()
{
  if (!(this->AttenuationAsked || this->HasRadiographPhysics()))
  {
    this->TransferFunction->DeepCopy(this->Weight);
    return;
  }
  this->WarnIfNotHounsfield();
  this->TransferFunction->DeepCopy(
    MakeWeightedAttenuation(this->WeightSelectsAll ? nullptr : this->Weight.Get(),
      this->WaterAttenuation, this->AirValue, this->DataRange));
}

void XRayViewer::WarnIfNotHounsfield()
{
  if (this->AirValue == -1000.0 || this->NotHounsfieldWarned)
  {
    return;
  }
  this->NotHounsfieldWarned = true;
  std::cerr << "mcxray: warning: the radiograph's mu takes CT in HU, but "
            << NoAirNote(this->DataRange) << ": the lowest counts as air (-1000 HU)" << std::endl;
}

std::string XRayViewer::OverlayText(bool withFrameTime) const
{
  vtkMCXXRayMapper* mapper = this->Mapper;
  std::ostringstream text;
  text.precision(3);
  const bool everyVoxel = mapper->GetStrategy() == vtkMCXTypes::EVERY_VOXEL;
  const long long total = static_cast<long long>(mapper->GetNumberOfInputPoints());
  text << Thousands(mapper->GetNumberOfAccumulatedSamples()) << " of " << Thousands(total)
       << (everyVoxel ? " voxels   " : " samples   ");
  if (withFrameTime)
  {
    text << this->LastFrameSeconds * 1000.0 << " ms/frame   ";
  }
  const double error = mapper->GetEstimatedRelativeError();
  if (everyVoxel)
  {
    text << "each voxel once";
  }
  else if (std::isfinite(error))
  {
    text << "est. error " << 100.0 * error << " %";
  }
  else
  {
    text << "est. error -";
  }
  if (this->Polychromatic)
  {
    text << "\nspectrum " << mapper->GetSpectrum() << ", materials " << mapper->GetMaterials()
         << ", detector " << mapper->GetDetector() << "   window ";
  }
  else
  {
    double range[2];
    this->Weight->GetRange(range);
    char lowest[32], highest[32];
    std::snprintf(lowest, sizeof(lowest), this->LabelFormat.c_str(), range[0]);
    std::snprintf(highest, sizeof(highest), this->LabelFormat.c_str(), range[1]);
    const bool attenuation = this->AttenuationAsked || this->HasRadiographPhysics();
    text << "\nTF " << (attenuation ? "mu(HU) x " : "") << lowest << " .. " << highest
         << " (data units)   window ";
  }
  text << mapper->GetDisplayedLevel() - 0.5 * mapper->GetDisplayedWindow() << " .. "
       << mapper->GetDisplayedLevel() + 0.5 * mapper->GetDisplayedWindow() << " ("
       << DisplayedQuantity(mapper) << ")   "
       << (this->Renderer->GetActiveCamera()->GetParallelProjection() ? "parallel" : "perspective")
       << (mapper->GetInvertDisplay() ? ", inverted" : "")
       << (mapper->GetBeerLambert() || mapper->GetPhotonsPerPixel() > 0 ? ", Beer-Lambert" : "")
       << (mapper->GetPhotonsPerPixel() > 0 ? ", Poisson noise" : "")
       << (mapper->GetNegativeLog() ? ", -ln" : "") << "\n"
       << (this->Polychromatic ? PolychromaticKeyHelp : KeyHelp);
  return text.str();
}

void XRayViewer::OnRenderEnd(vtkObject*, unsigned long, void* self, void*)
{
  auto* viewer = static_cast<XRayViewer*>(self);
  ++viewer->Frames;
  viewer->LastFrameSeconds = viewer->Renderer->GetLastRenderTimeInSeconds();
  // The overlay describes the frame just drawn; the next render shows it.
  const std::string state = viewer->OverlayText(false);
  viewer->OverlayCurrent = state == viewer->OverlayState;
  if (!viewer->OverlayCurrent)
  {
    viewer->OverlayState = state;
    viewer->Overlay->SetInput(viewer->OverlayText().c_str());
  }
}

void XRayViewer::OnTimer(vtkObject*, unsigned long, void* self, void*)
{
  auto* viewer = static_cast<XRayViewer*>(self);
  // Refine while the view is still; one more render brings the overlay up to date.
  if (!viewer->Mapper->IsRefinementComplete() || !viewer->OverlayCurrent)
  {
    viewer->Interactor->Render();
  }
}

void XRayViewer::OnSlider(vtkObject*, unsigned long, void* self, void*)
{
  auto* viewer = static_cast<XRayViewer*>(self);
  auto value = [](vtkSliderWidget* slider)
  { return vtkSliderRepresentation2D::SafeDownCast(slider->GetRepresentation())->GetValue(); };
  viewer->SetTransferFunctionWindow(value(viewer->CentreSlider), value(viewer->WidthSlider));
}

// While a slider is dragged each frame projects what fits the drag budget,
// under the window of before the drag (the automatic window would project
// 4 points a pixel of every edit); the release renders still and
// re-windows.
void XRayViewer::OnDragStart(vtkObject*, unsigned long, void* self, void*)
{
  auto* viewer = static_cast<XRayViewer*>(self);
  vtkMCXXRayMapper* mapper = viewer->Mapper;
  viewer->WindowWasAutomatic = mapper->GetAutomaticWindowLevel();
  if (viewer->WindowWasAutomatic)
  {
    mapper->SetColorWindow(mapper->GetDisplayedWindow());
    mapper->SetColorLevel(mapper->GetDisplayedLevel());
    mapper->AutomaticWindowLevelOff();
  }
  mapper->SetMaximumRenderTime(viewer->DragRenderTime);
}

void XRayViewer::OnDragEnd(vtkObject*, unsigned long, void* self, void*)
{
  auto* viewer = static_cast<XRayViewer*>(self);
  viewer->Mapper->SetAutomaticWindowLevel(viewer->WindowWasAutomatic);
  viewer->Mapper->SetMaximumRenderTime(0.0);
}

void XRayViewer::OnChar(vtkObject*, unsigned long, void* self, void*)
{
  auto* viewer = static_cast<XRayViewer*>(self);
  const char key = viewer->Interactor->GetKeyCode();
  bool handled = true;
  // Polychromatic: no TF to choose, and b is the intensity alone.
  const bool presets = !viewer->Polychromatic;
  switch (key)
  {
    case '1':
    case '2':
    case '3':
      handled = presets;
      if (handled)
      {
        viewer->ApplyPreset(key == '1' ? "raw" : key == '2' ? "bone" : "soft-tissue");
      }
      break;
    case 'b':
      if (presets)
      {
        viewer->SetRadiograph(!viewer->Mapper->GetBeerLambert());
      }
      else
      {
        viewer->Mapper->SetBeerLambert(!viewer->Mapper->GetBeerLambert());
        viewer->MatchControlsToFilm();
      }
      break;
    case 'i':
      viewer->Mapper->SetInvertDisplay(!viewer->Mapper->GetInvertDisplay());
      viewer->MatchControlsToFilm();
      break;
    case 'p':
    {
      vtkCamera* camera = viewer->Renderer->GetActiveCamera();
      camera->SetParallelProjection(!camera->GetParallelProjection());
      break;
    }
    case '+':
    case '=':
    case '-':
      // An every-voxel cloud has no sample count to change.
      handled = viewer->Mapper->GetStrategy() != vtkMCXTypes::EVERY_VOXEL;
      if (handled)
      {
        const int step = key == '-' ? -1 : 1;
        viewer->Mapper->SetSampleExponent(std::max(
          10, std::min(MaximumViewerExponent, viewer->Mapper->GetSampleExponent() + step)));
      }
      break;
    default:
      handled = false;
  }
  if (handled)
  {
    viewer->CharCommand->SetAbortFlag(1);
    viewer->Interactor->Render();
  }
}

void XRayViewer::Start()
{
  this->Interactor->Initialize();
  this->Interactor->CreateRepeatingTimer(15);
  this->Window->Render();
  this->Interactor->Start();
}

void XRayViewer::ShowControls(bool show)
{
  this->Overlay->SetVisibility(show);
  const bool sliders = show && !this->Polychromatic;
  this->SliderBacking->SetVisibility(sliders);
  this->CentreSlider->SetEnabled(sliders);
  this->WidthSlider->SetEnabled(sliders);
}

void XRayViewer::SetPolychromatic(
  const std::string& spectrum, const std::string& materials, const std::string& detector)
{
  this->Polychromatic = !spectrum.empty();
  this->Mapper->SetSpectrum(spectrum.c_str());
  this->Mapper->SetMaterials(materials.c_str());
  this->Mapper->SetDetector(detector.c_str());
  this->ShowControls(this->Overlay->GetVisibility() != 0);
}

int XRayViewer::RefineUntilComplete()
{
  int renders = 0;
  do
  {
    this->Window->Render();
    ++renders;
  } while ((!this->Mapper->IsRefinementComplete() || !this->OverlayCurrent) && renders < 1000);
  return renders;
}

} // namespace mcxapp
