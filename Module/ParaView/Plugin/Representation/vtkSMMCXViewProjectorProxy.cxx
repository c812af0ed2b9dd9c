#include "vtkSMMCXViewProjectorProxy.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkMCXCostPrivate.h"
#include "vtkMCXTypes.h"
#include "vtkMCXViewProjector.h"
#include "vtkObjectFactory.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkRenderWindow.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxySelectionModel.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSettings.h"
#include "vtkSMTransferFunctionProxy.h"

#include <algorithm>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSMMCXViewProjectorProxy);

namespace
{
// The projector's image in grey: ParaView gives a new colour map of an
// array its ".standard_presets.<array>" preset. Added once, below the user's
// and the site's settings (which may choose another).
void InstallGreyLineIntegralColorMap()
{
  static bool installed = false;
  if (!installed)
  {
    installed = vtkSMSettings::GetInstance()->AddCollectionFromString(
      std::string("{ \"standard_presets\": { \"") + vtkMCXTypes::LineIntegralName() +
        "\": \"Grayscale\" } }",
      0.5);
  }
}
}

vtkSMMCXViewProjectorProxy::vtkSMMCXViewProjectorProxy() = default;

vtkSMMCXViewProjectorProxy::~vtkSMMCXViewProjectorProxy()
{
  this->FollowView(nullptr);
  if (this->Selection && this->SelectionObserver)
  {
    this->Selection->RemoveObserver(this->SelectionObserver);
  }
}

void vtkSMMCXViewProjectorProxy::CreateVTKObjects()
{
  if (this->ObjectsCreated)
  {
    return;
  }
  this->Superclass::CreateVTKObjects();
  if (!this->ObjectsCreated) // a prototype (Location 0) follows no view
  {
    return;
  }
  InstallGreyLineIntegralColorMap();
  vtkSMSessionProxyManager* pxm = this->GetSessionProxyManager();
  vtkSMProxySelectionModel* selection = pxm ? pxm->GetSelectionModel("ActiveView") : nullptr;
  if (selection)
  {
    this->Selection = selection;
    this->SelectionObserver = selection->AddObserver(
      vtkCommand::CurrentChangedEvent, this, &vtkSMMCXViewProjectorProxy::OnActiveViewChanged);
  }
  this->FollowView(this->ActiveView());
}

vtkSMProxy* vtkSMMCXViewProjectorProxy::ActiveView()
{
  auto* selection = vtkSMProxySelectionModel::SafeDownCast(this->Selection);
  return vtkSMRenderViewProxy::SafeDownCast(selection ? selection->GetCurrentProxy() : nullptr);
}

void vtkSMMCXViewProjectorProxy::FollowView(vtkSMProxy* view)
{
  if (view == this->FollowedView)
  {
    return;
  }
  if (this->FollowedView && this->RenderObserver)
  {
    this->FollowedView->RemoveObserver(this->RenderObserver);
  }
  this->RenderObserver = 0;
  this->FollowedView = view;
  if (view)
  {
    this->RenderObserver =
      view->AddObserver(vtkCommand::StartEvent, this, &vtkSMMCXViewProjectorProxy::OnRender);
  }
}

void vtkSMMCXViewProjectorProxy::OnActiveViewChanged()
{
  this->FollowView(this->ActiveView());
}

void vtkSMMCXViewProjectorProxy::OnRender(vtkObject*, unsigned long, void* callData)
{
  // StartEvent's call data: 0 for a still render, 1 for an interactive one.
  // A still render updates the view's representations after this event, so
  // the projector re-projects for the camera the render shows.
  const bool interactive = callData && *static_cast<int*>(callData) != 0;
  // A screenshot larger than the view renders it in tiles, each with a
  // narrowed camera (the GUI) while the window's tile scale is above 1: the
  // image keeps the view's camera.
  auto* view = vtkSMViewProxy::SafeDownCast(this->FollowedView);
  vtkRenderWindow* window = view ? view->GetRenderWindow() : nullptr;
  if (window && (window->GetTileScale()[0] != 1 || window->GetTileScale()[1] != 1))
  {
    return;
  }
  if (!interactive && this->CopyActiveViewCamera())
  {
    this->UpdateVTKObjects();
  }
  if (!interactive)
  {
    this->WindowShownImage();
  }
}

void vtkSMMCXViewProjectorProxy::WindowShownImage()
{
  if (!this->FollowedView || !this->FollowedView->GetProperty("Representations"))
  {
    return;
  }
  vtkSMPropertyHelper representations(this->FollowedView, "Representations");
  for (unsigned int i = 0; i < representations.GetNumberOfElements(); ++i)
  {
    vtkSMProxy* representation = representations.GetAsProxy(i);
    if (!representation || !representation->GetProperty("Input") ||
      !representation->GetProperty("LookupTable") ||
      vtkSMPropertyHelper(representation, "Input").GetAsProxy() != this)
    {
      continue;
    }
    vtkSMProxy* colorMap = vtkSMPropertyHelper(representation, "LookupTable").GetAsProxy();
    const char* colored =
      vtkSMPropertyHelper(representation, "ColorArrayName").GetInputArrayNameToProcess();
    if (!colorMap || colorMap == this->WindowedColorMap || !colored ||
      std::string(colored) != vtkMCXTypes::LineIntegralName())
    {
      continue;
    }
    vtkPVArrayInformation* window = this->GetDataInformation(0)->GetArrayInformation(
      vtkMCXViewProjector::AutomaticWindowName(), vtkDataObject::FIELD_ASSOCIATION_NONE);
    if (!window || !(window->GetComponentRange(0)[1] > 0.0))
    {
      return;
    }
    const double top = window->GetComponentRange(0)[1];
    vtkSMTransferFunctionProxy::RescaleTransferFunction(colorMap, 0.0, top);
    if (vtkSMProxy* opacity =
          vtkSMPropertyHelper(colorMap, "ScalarOpacityFunction", true).GetAsProxy())
    {
      vtkSMTransferFunctionProxy::RescaleTransferFunction(opacity, 0.0, top);
    }
    this->WindowedColorMap = colorMap;
  }
}

bool vtkSMMCXViewProjectorProxy::CopyActiveViewCamera()
{
  if (!this->GetProperty("UseActiveViewCamera") || !this->GetProperty("ViewCameraInUse"))
  {
    return false;
  }
  vtkSMProxy* view = this->ActiveView();
  this->FollowView(view);
  const bool use = vtkSMPropertyHelper(this, "UseActiveViewCamera").GetAsInt() != 0 && view;
  std::vector<double> values; // position, focal point, view up, angle, scale, parallel
  vtkCamera* camera = use ? vtkSMRenderViewProxy::SafeDownCast(view)->GetActiveCamera() : nullptr;
  bool changed = false;
  auto set = [this, &changed](const char* name, const double* v, unsigned int n)
  {
    vtkSMPropertyHelper helper(this, name);
    std::vector<double> now = helper.GetDoubleArray();
    if (now.size() != n || !std::equal(now.begin(), now.end(), v))
    {
      helper.Set(v, n);
      changed = true;
    }
  };
  const double inUse = camera ? 1.0 : 0.0;
  if (vtkSMPropertyHelper(this, "ViewCameraInUse").GetAsInt() != static_cast<int>(inUse))
  {
    vtkSMPropertyHelper(this, "ViewCameraInUse").Set(static_cast<int>(inUse));
    changed = true;
  }
  if (!camera)
  {
    return changed;
  }
  set("ViewCameraPosition", camera->GetPosition(), 3);
  set("ViewCameraFocalPoint", camera->GetFocalPoint(), 3);
  set("ViewCameraViewUp", camera->GetViewUp(), 3);
  const double angle = camera->GetViewAngle();
  const double scale = camera->GetParallelScale();
  set("ViewCameraViewAngle", &angle, 1);
  set("ViewCameraParallelScale", &scale, 1);
  if (vtkSMPropertyHelper(this, "ViewCameraParallelProjection").GetAsInt() !=
    camera->GetParallelProjection())
  {
    vtkSMPropertyHelper(this, "ViewCameraParallelProjection").Set(camera->GetParallelProjection());
    changed = true;
  }
  // The view's aspect, for an automatic image size: a resize that keeps it
  // (a screenshot at a multiple of the view's size) projects nothing again.
  int viewSize[2] = { 0, 0 };
  vtkSMPropertyHelper(view, "ViewSize").Get(viewSize, 2);
  if (this->GetProperty("ViewAspect") && viewSize[0] > 0 && viewSize[1] > 0)
  {
    const double aspect = static_cast<double>(viewSize[0]) / viewSize[1];
    set("ViewAspect", &aspect, 1);
  }
  return changed;
}

void vtkSMMCXViewProjectorProxy::UpdateVTKObjects()
{
  this->CopyActiveViewCamera();
  this->Superclass::UpdateVTKObjects();
  // The panel shows what the projector uses (its setters clamp silently).
  mcx::ClampToRangeDomains(this, "");
}

void vtkSMMCXViewProjectorProxy::UpdatePipeline()
{
  if (this->CopyActiveViewCamera())
  {
    this->UpdateVTKObjects();
  }
  this->Superclass::UpdatePipeline();
}

void vtkSMMCXViewProjectorProxy::UpdatePipeline(double time)
{
  if (this->CopyActiveViewCamera())
  {
    this->UpdateVTKObjects();
  }
  this->Superclass::UpdatePipeline(time);
}

void vtkSMMCXViewProjectorProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FollowedView: " << this->FollowedView.GetPointer() << "\n";
  os << indent << "RenderObserver: " << this->RenderObserver << "\n";
  os << indent << "WindowedColorMap: " << this->WindowedColorMap.GetPointer() << "\n";
  os << indent << "Selection: " << this->Selection.GetPointer() << "\n";
  os << indent << "SelectionObserver: " << this->SelectionObserver << "\n";
}
