/**
 * @class   vtkSMMCXViewProjectorProxy
 * @brief   The client-side proxy of "X-Ray Projector": makes the DRR for
 *          the active render view's camera.
 *
 * With its property UseActiveViewCamera on (the XML's default), the proxy
 * copies the camera of the active render view (the one the GUI shows
 * active, or paraview.simple's GetActiveView()) into the projector's
 * ViewCamera* properties and pushes them: on Apply (UpdateVTKObjects), on
 * UpdatePipeline, and at the start of each still render of that view, so
 * that the image follows the view once a camera motion ends (interactive
 * renders leave it be), and gives the image's grey colour map the
 * automatic window when the image is first shown. Without an active render view, or with the
 * property off, the projector keeps its explicit detector (DetectorAxisU and DetectorAxisV). Works
 * in built-in and client-server sessions alike: the copy happens on the client, and only the
 * camera's numbers travel.
 */
#ifndef vtkSMMCXViewProjectorProxy_h
#define vtkSMMCXViewProjectorProxy_h

#include "MonteCarloXRayParaViewModule.h" // for export macro
#include "vtkSMSourceProxy.h"
#include "vtkWeakPointer.h" // for members

class MONTECARLOXRAYPARAVIEW_EXPORT vtkSMMCXViewProjectorProxy : public vtkSMSourceProxy
{
public:
  static vtkSMMCXViewProjectorProxy* New();
  vtkTypeMacro(vtkSMMCXViewProjectorProxy, vtkSMSourceProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Copies the active view's camera first; clamps the properties to their
   * ranges after pushing (the panel shows what the projector uses).
   */
  void UpdateVTKObjects() override;
  void UpdatePipeline() override;
  void UpdatePipeline(double time) override;

  /**
   * Copies the active render view's camera into the ViewCamera* properties
   * (ViewCameraInUse 1), or sets ViewCameraInUse 0 when UseActiveViewCamera
   * is off or no render view is active; true when a property changed. Does
   * not push them.
   */
  bool CopyActiveViewCamera();

  /**
   * Gives the colour map of this proxy's image (LineIntegral) in the followed
   * view the automatic window (0 to the output's AutomaticWindow), once per
   * colour map: when the image is first shown. Called at each still render.
   */
  void WindowShownImage();

protected:
  vtkSMMCXViewProjectorProxy();
  ~vtkSMMCXViewProjectorProxy() override;

  void CreateVTKObjects() override;

private:
  vtkSMMCXViewProjectorProxy(const vtkSMMCXViewProjectorProxy&) = delete;
  void operator=(const vtkSMMCXViewProjectorProxy&) = delete;

  vtkSMProxy* ActiveView();                                 // the active render view, if any
  void FollowView(vtkSMProxy* view);                        // observes that view's still renders
  void OnActiveViewChanged();                               // the selection changed
  void OnRender(vtkObject*, unsigned long, void* callData); // a render starts

  vtkWeakPointer<vtkSMProxy> FollowedView;
  unsigned long RenderObserver = 0;
  vtkWeakPointer<vtkSMProxy> WindowedColorMap; // the colour map given the automatic window
  vtkWeakPointer<vtkObject> Selection;         // the session's "ActiveView" selection model
  unsigned long SelectionObserver = 0;
};

#endif
