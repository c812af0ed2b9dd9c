#include "mcxXRayViewer.h"

#include "mcxTransferFunctionSpec.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkMCXXRayMapper.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSliderRepresentation2D.h"
#include "vtkSliderWidget.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <cstdio>
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
  "keys: 1 raw, 2 bone, 3 soft tissue, +/- points, i invert, b Beer-Lambert, "
  "p projection, r reset camera, q quit";

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
  std::string error;
  vtkSmartPointer<vtkPiecewiseFunction> tf =
    MakeTransferFunction(options.TransferFunction, this->DataRange, error);
  if (!tf)
  {
    this->ErrorMessage = error;
    return;
  }
  this->TransferFunction->DeepCopy(tf);

  // The mapper indexes and samples the volume under the property's TF.
  this->Mapper->SetInputData(volume);
  this->Mapper->SetSampleExponent(options.SampleExponent);
  this->Mapper->SetStrategy(options.Strategy);
  this->Mapper->SetKernel(options.Kernel);
  this->Mapper->SetDeposit(options.Deposit);
  this->Mapper->SetSeed(static_cast<vtkTypeInt64>(options.Seed));
  this->Volume->GetProperty()->SetScalarOpacity(this->TransferFunction);
  this->Volume->SetMapper(this->Mapper);
  this->Renderer->AddVolume(this->Volume);
  this->Renderer->SetBackground(0, 0, 0);

  this->Overlay->GetTextProperty()->SetFontSize(14);
  this->Overlay->GetTextProperty()->SetColor(1.0, 0.85, 0.2);
  this->Overlay->GetTextProperty()->SetVerticalJustificationToTop();
  this->Overlay->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  this->Overlay->SetPosition(0.01, 0.99);
  this->Renderer->AddActor2D(this->Overlay);

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
  // the window apart, the upper title stays clear of the lower value.
  this->AddSlider(this->CentreSlider, "TF centre", this->DataRange[0], this->DataRange[1], 0.19);
  this->AddSlider(this->WidthSlider, "TF width", span / 1000.0, 2.0 * span, 0.06);
  this->UpdateSlidersFromTransferFunction();

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
  representation->SetLabelFormat("%.4g");
  slider->SetInteractor(this->Interactor);
  slider->SetRepresentation(representation);
  slider->SetAnimationModeToJump();
  this->SliderCommand->SetClientData(this);
  this->SliderCommand->SetCallback(&XRayViewer::OnSlider);
  slider->AddObserver(vtkCommand::InteractionEvent, this->SliderCommand);
  slider->EnabledOn();
}

void XRayViewer::UpdateSlidersFromTransferFunction()
{
  double range[2];
  this->TransferFunction->GetRange(range);
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
  this->TransferFunction->DeepCopy(window);
}

bool XRayViewer::ApplyPreset(const std::string& name)
{
  std::string error;
  vtkSmartPointer<vtkPiecewiseFunction> tf = MakeTransferFunction(name, this->DataRange, error);
  if (!tf || (name != "raw" && name != "bone" && name != "soft-tissue"))
  {
    return false;
  }
  this->TransferFunction->DeepCopy(tf);
  this->UpdateSlidersFromTransferFunction();
  return true;
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
  double range[2];
  this->TransferFunction->GetRange(range);
  text << "\nTF " << range[0] << " .. " << range[1] << " (data units)   window "
       << mapper->GetDisplayedLevel() - 0.5 * mapper->GetDisplayedWindow() << " .. "
       << mapper->GetDisplayedLevel() + 0.5 * mapper->GetDisplayedWindow() << " (TF x length)   "
       << (this->Renderer->GetActiveCamera()->GetParallelProjection() ? "parallel" : "perspective")
       << (mapper->GetInvertDisplay() ? ", inverted" : "")
       << (mapper->GetBeerLambert() || mapper->GetPhotonsPerPixel() > 0 ? ", Beer-Lambert" : "")
       << (mapper->GetPhotonsPerPixel() > 0 ? ", Poisson noise" : "")
       << (mapper->GetNegativeLog() ? ", -ln" : "") << "\n"
       << KeyHelp;
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

void XRayViewer::OnChar(vtkObject*, unsigned long, void* self, void*)
{
  auto* viewer = static_cast<XRayViewer*>(self);
  const char key = viewer->Interactor->GetKeyCode();
  bool handled = true;
  switch (key)
  {
    case '1':
      viewer->ApplyPreset("raw");
      break;
    case '2':
      viewer->ApplyPreset("bone");
      break;
    case '3':
      viewer->ApplyPreset("soft-tissue");
      break;
    case 'i':
      viewer->Mapper->SetInvertDisplay(!viewer->Mapper->GetInvertDisplay());
      viewer->Renderer->SetBackground(viewer->Mapper->GetInvertDisplay() ? 1.0 : 0.0,
        viewer->Mapper->GetInvertDisplay() ? 1.0 : 0.0,
        viewer->Mapper->GetInvertDisplay() ? 1.0 : 0.0);
      break;
    case 'b':
      viewer->Mapper->SetBeerLambert(!viewer->Mapper->GetBeerLambert());
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
  this->CentreSlider->SetEnabled(show);
  this->WidthSlider->SetEnabled(show);
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
