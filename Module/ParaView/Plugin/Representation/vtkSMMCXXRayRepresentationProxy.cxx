#include "vtkSMMCXXRayRepresentationProxy.h"

#include "vtkCommand.h"
#include "vtkObjectFactory.h"
#include "vtkSMPropertyHelper.h"

vtkStandardNewMacro(vtkSMMCXXRayRepresentationProxy);

vtkSMMCXXRayRepresentationProxy::~vtkSMMCXXRayRepresentationProxy()
{
  if (this->ObservedView && this->RenderObserver)
  {
    this->ObservedView->RemoveObserver(this->RenderObserver);
  }
}

void vtkSMMCXXRayRepresentationProxy::ViewUpdated(vtkSMProxy* view)
{
  this->Superclass::ViewUpdated(view);
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
}
