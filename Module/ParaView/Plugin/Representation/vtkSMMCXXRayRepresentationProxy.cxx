#include "vtkSMMCXXRayRepresentationProxy.h"

#include "vtkCommand.h"
#include "vtkMCXCostPrivate.h"
#include "vtkMCXXRayMapper.h"
#include "vtkMCXXRayRepresentation.h"
#include "vtkObjectFactory.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMPropertyHelper.h"

#include <string>
#include <vector>

vtkStandardNewMacro(vtkSMMCXXRayRepresentationProxy);

vtkSMMCXXRayRepresentationProxy::~vtkSMMCXXRayRepresentationProxy()
{
  if (this->ObservedView && this->RenderObserver)
  {
    this->ObservedView->RemoveObserver(this->RenderObserver);
  }
}

void vtkSMMCXXRayRepresentationProxy::UpdateVTKObjects()
{
  this->Superclass::UpdateVTKObjects();
  mcx::ClampToRangeDomains(this, "XRay");
}

void vtkSMMCXXRayRepresentationProxy::ViewUpdated(vtkSMProxy* view)
{
  this->Superclass::ViewUpdated(view);
  this->PrepareFirstPicture(view);
  this->InkOrientationAxes(view);
  if (view && view != this->ObservedView)
  {
    if (this->ObservedView && this->RenderObserver)
    {
      this->ObservedView->RemoveObserver(this->RenderObserver);
    }
    this->ObservedView = view;
    this->RenderObserver =
      view->AddObserver(vtkCommand::EndEvent, this, &vtkSMMCXXRayRepresentationProxy::OnRendered);
  }
}

void vtkSMMCXXRayRepresentationProxy::OnRendered(vtkObject*, unsigned long, void* callData)
{
  // EndEvent's call data: 0 after a still render, 1 after an interactive one.
  if (!(callData && *static_cast<int*>(callData) != 0))
  {
    this->ShowDisplayedWindow();
  }
}

void vtkSMMCXXRayRepresentationProxy::PrepareFirstPicture(vtkSMProxy* view)
{
  // Only while the X-ray is the representation shown.
  vtkSMProxy* parent = this->GetParentProxy();
  if (!view || !parent || !parent->GetProperty("Representation") ||
    std::string(vtkSMPropertyHelper(parent, "Representation").GetAsString()) !=
      "Monte Carlo X-Ray" ||
    !vtkSMPVRepresentationProxy::GetUsingScalarColoring(parent))
  {
    return;
  }
  vtkSMProxy* opacity = vtkSMPropertyHelper(this, "ScalarOpacityFunction", true).GetAsProxy();
  if (opacity && opacity != this->PreparedOpacity)
  {
    this->PreparedOpacity = opacity;
    vtkSMPropertyHelper points(opacity, "Points");
    std::vector<double> ramp = points.GetDoubleArray();
    // ParaView's default: (x, y, midpoint, sharpness) = (low, 0, 0.5, 0), (high, 1, 0.5, 0).
    if (ramp.size() == 8 && ramp[1] == 0.0 && ramp[5] == 1.0 && ramp[2] == 0.5 && ramp[3] == 0.0 &&
      ramp[6] == 0.5 && ramp[7] == 0.0)
    {
      const double start = vtkMCXXRayRepresentation::DefaultRampStart(ramp[0], ramp[4]);
      if (start != ramp[0])
      {
        ramp[0] = start;
        points.Set(ramp.data(), 8);
        opacity->UpdateVTKObjects();
      }
    }
  }
  vtkSMProxy* colorMap = vtkSMPropertyHelper(parent, "LookupTable", true).GetAsProxy();
  if (colorMap && colorMap != this->HiddenBarColorMap)
  {
    this->HiddenBarColorMap = colorMap;
    vtkSMPVRepresentationProxy::SetScalarBarVisibility(parent, view, false);
  }
}

bool vtkSMMCXXRayRepresentationProxy::InkOrientationAxes(vtkSMProxy* view)
{
  vtkSMProxy* parent = this->GetParentProxy();
  if (!view || !view->GetProperty("OrientationAxesLabelColor") || !parent ||
    !parent->GetProperty("Representation"))
  {
    return false;
  }
  // The empty film's grey: 0 for line integrals and their negative log, 1
  // for Beer-Lambert's intensity (also with noise), inverted by X-Ray Invert.
  const bool shown = std::string(vtkSMPropertyHelper(parent, "Representation").GetAsString()) ==
      "Monte Carlo X-Ray" &&
    vtkSMPropertyHelper(parent, "Visibility").GetAsInt() != 0 &&
    vtkSMPropertyHelper(this, "XRayCompositing").GetAsInt() == vtkMCXXRayMapper::FILM;
  const bool intensity = (vtkSMPropertyHelper(this, "XRayBeerLambert").GetAsInt() != 0 ||
                           vtkSMPropertyHelper(this, "XRayPhotonsPerPixel").GetAsDouble() > 0) &&
    vtkSMPropertyHelper(this, "XRayNegativeLog").GetAsInt() == 0;
  const bool light =
    shown && (intensity != (vtkSMPropertyHelper(this, "XRayInvert").GetAsInt() != 0));
  vtkSMPropertyHelper labels(view, "OrientationAxesLabelColor");
  double ink[3];
  labels.Get(ink, 3);
  const bool white = ink[0] == 1.0 && ink[1] == 1.0 && ink[2] == 1.0;
  const bool black = ink[0] == 0.0 && ink[1] == 0.0 && ink[2] == 0.0;
  double wanted[3] = { 1.0, 1.0, 1.0 };
  if (light && white)
  {
    wanted[0] = wanted[1] = wanted[2] = 0.0;
  }
  else if (light || !(this->InkedAxesLabels && black))
  {
    return false; // already black, or not ours to change
  }
  labels.Set(wanted, 3);
  view->UpdateVTKObjects();
  this->InkedAxesLabels = light;
  return true;
}

bool vtkSMMCXXRayRepresentationProxy::ShowDisplayedWindow()
{
  vtkSMProperty* windowInfo = this->GetProperty("XRayWindowInfo");
  vtkSMProperty* levelInfo = this->GetProperty("XRayLevelInfo");
  if (!this->ObjectsCreated || !windowInfo || !levelInfo ||
    vtkSMPropertyHelper(this, "Visibility").GetAsInt() == 0 ||
    vtkSMPropertyHelper(this, "XRayAutomaticWindow").GetAsInt() == 0)
  {
    return false;
  }
  this->UpdatePropertyInformation(windowInfo);
  this->UpdatePropertyInformation(levelInfo);
  const double window = vtkSMPropertyHelper(windowInfo).GetAsDouble();
  const double level = vtkSMPropertyHelper(levelInfo).GetAsDouble();
  bool changed = false;
  if (vtkSMPropertyHelper(this, "XRayWindow").GetAsDouble() != window)
  {
    vtkSMPropertyHelper(this, "XRayWindow").Set(window);
    changed = true;
  }
  if (vtkSMPropertyHelper(this, "XRayLevel").GetAsDouble() != level)
  {
    vtkSMPropertyHelper(this, "XRayLevel").Set(level);
    changed = true;
  }
  return changed;
}

void vtkSMMCXXRayRepresentationProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ObservedView: " << this->ObservedView.GetPointer() << "\n";
  os << indent << "RenderObserver: " << this->RenderObserver << "\n";
  os << indent << "InkedAxesLabels: " << this->InkedAxesLabels << "\n";
  os << indent << "PreparedOpacity: " << this->PreparedOpacity.GetPointer() << "\n";
  os << indent << "HiddenBarColorMap: " << this->HiddenBarColorMap.GetPointer() << "\n";
}
