/**
 * @class   vtkSMMCXXRayRepresentationProxy
 * @brief   The client-side proxy of the "Monte Carlo X-Ray" representation:
 *          shows the automatic window in the panel.
 *
 * After each still render of a view that shows it, the proxy reads the
 * window and level the X-ray used (information properties XRayWindowInfo
 * and XRayLevelInfo, vtkMCXXRayRepresentation::GetDisplayedWindow and
 * GetDisplayedLevel) and, while XRayAutomaticWindow is on, sets X-Ray Window
 * and X-Ray Level to them (not pushed: the mapper ignores them while the
 * window is automatic). The panel thus shows the automatic values, and
 * unticking X-Ray Automatic Window starts the manual window from them.
 *
 * First pictures that read: when the X-ray is shown coloured by an array
 * whose opacity function is still ParaView's default (a ramp from 0 at the
 * data's minimum to 1 at its maximum) and the data are CT in Hounsfield
 * units, the ramp starts at -200 HU instead
 * (vtkMCXXRayRepresentation::DefaultRampStart), once per opacity function;
 * and the colour map's scalar bar, which means nothing for a grey X-ray, is
 * hidden once per colour map (the legend button shows it again).
 *
 * Orientation axes that read on the film: ParaView draws the axes' labels
 * white, which vanish on a light film (X-Ray Invert, or Beer-Lambert's
 * intensity). While the X-ray is shown on a light film (Film compositing),
 * the view's OrientationAxesLabelColor is black, and white again on a dark
 * one; a colour the user chose (neither white nor the black set here) is
 * left alone.
 */
#ifndef vtkSMMCXXRayRepresentationProxy_h
#define vtkSMMCXXRayRepresentationProxy_h

#include "MonteCarloXRayParaViewModule.h" // for export macro
#include "vtkSMRepresentationProxy.h"
#include "vtkWeakPointer.h" // for members

class MONTECARLOXRAYPARAVIEW_EXPORT vtkSMMCXXRayRepresentationProxy
  : public vtkSMRepresentationProxy
{
public:
  static vtkSMMCXXRayRepresentationProxy* New();
  vtkTypeMacro(vtkSMMCXXRayRepresentationProxy, vtkSMRepresentationProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Pushes the properties, then clamps the X-Ray ones to their ranges (the
   * classes'), so that the panel shows what the X-ray uses: 31 typed into
   * X-Ray Sample Exponent reads 30 once the class has clamped and warned.
   */
  void UpdateVTKObjects() override;

  /** Observes the view's still renders (the first time a view updates it). */
  void ViewUpdated(vtkSMProxy* view) override;

  /**
   * Reads the displayed window and, while it is automatic, puts it in X-Ray
   * Window and X-Ray Level; true when they changed.
   */
  bool ShowDisplayedWindow();

  /**
   * Starts ParaView's default opacity ramp at -200 HU for CT in HU and hides
   * the scalar bar, each once per function (see the class comment).
   */
  void PrepareFirstPicture(vtkSMProxy* view);

  /**
   * Black orientation-axes labels on a light film, white on a dark one
   * (see the class comment); true when it changed them.
   */
  bool InkOrientationAxes(vtkSMProxy* view);

protected:
  vtkSMMCXXRayRepresentationProxy() = default;
  ~vtkSMMCXXRayRepresentationProxy() override;

private:
  vtkSMMCXXRayRepresentationProxy(const vtkSMMCXXRayRepresentationProxy&) = delete;
  void operator=(const vtkSMMCXXRayRepresentationProxy&) = delete;

  void OnRendered(vtkObject*, unsigned long, void* callData);

  vtkWeakPointer<vtkSMProxy> ObservedView;
  bool InkedAxesLabels = false;                 // the labels are black because of the film
  vtkWeakPointer<vtkSMProxy> PreparedOpacity;   // the opacity function last looked at
  vtkWeakPointer<vtkSMProxy> HiddenBarColorMap; // the colour map whose bar was hidden
  unsigned long RenderObserver = 0;
};

#endif
