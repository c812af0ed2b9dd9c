/**
 * @class   vtkMCXViewProjector
 * @brief   ParaView's "X-Ray Projector": vtkMCXProjector for a view's
 *          camera, that says a long run before it starts.
 *
 * With ViewCameraInUse on, the projector projects for the camera given by
 * the ViewCamera* values (a render view's, copied on the client by
 * vtkSMMCXViewProjectorProxy): vtkMCXProjectorBase::SetCamera with a
 * camera of this class's own; off (the default), the explicit detector.
 *
 * The output's field data AutomaticWindow (one value) is the window the
 * X-ray representation would choose for the image (vtkMCXXRayMapper's
 * rule: the 99.5th percentile of the positive 4 x 4 block means of
 * LineIntegral), which vtkSMMCXViewProjectorProxy gives the image's colour
 * map when it is first shown.
 *
 * With the view's camera in use and ImageSize automatic (0 x 0), the
 * image has the view's aspect (ViewAspect, width / height of the view in
 * pixels, copied with the camera): DefaultImageSize pixels along its longer
 * side, as vtkMCXProjector makes it for that camera and size. Without a
 * view aspect (0) it is DefaultImageSize square.
 *
 * Attenuation HU_TO_MU (default WEIGHT_ONLY) projects an index input under
 * mu(HU) x TF instead of the TF, as vtkMCXXRayRepresentation's X-Ray
 * Attenuation does (mcxray's `--tf mu` map at WaterAttenuation per world
 * unit times the TF clamped to [0, 1], mcxapp::MakeWeightedAttenuation; no
 * TF: mu alone): LineIntegral then holds line integrals of mu, which X-Ray
 * Radiograph turns into a radiograph. The TF itself is left as it is.
 *
 * A projection from a density index whose sample count will take more than
 * about 10 s (2^SampleExponent - 1 samples at about 15 M a second) warns in
 * one line with the count and the time before it starts, so that a GUI that
 * is busy for minutes has said why.
 */
#ifndef vtkMCXViewProjector_h
#define vtkMCXViewProjector_h

#include "MonteCarloXRayParaViewModule.h" // for export macro
#include "vtkMCXProjector.h"
#include "vtkNew.h" // for members

class vtkCamera;

class MONTECARLOXRAYPARAVIEW_EXPORT vtkMCXViewProjector : public vtkMCXProjector
{
public:
  static vtkMCXViewProjector* New();
  vtkTypeMacro(vtkMCXViewProjector, vtkMCXProjector);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Project for the ViewCamera* camera (default off: the explicit detector). */
  void SetViewCameraInUse(bool use);
  vtkGetMacro(ViewCameraInUse, bool);
  ///@}

  ///@{
  /** The view's camera (vtkCamera's values; the defaults are vtkCamera's). */
  void SetViewCameraPosition(double x, double y, double z);
  void SetViewCameraFocalPoint(double x, double y, double z);
  void SetViewCameraViewUp(double x, double y, double z);
  void SetViewCameraViewAngle(double degrees);
  void SetViewCameraParallelScale(double scale);
  void SetViewCameraParallelProjection(bool parallel);
  vtkCamera* GetViewCamera() { return this->ViewCamera; }
  ///@}

  ///@{
  /**
   * The view's width / height in pixels (default 0: none, a square image),
   * for an automatic ImageSize with the view's camera (see the class comment).
   */
  vtkSetClampMacro(ViewAspect, double, 0.0, 65536.0);
  vtkGetMacro(ViewAspect, double);
  ///@}

  /** What an index input is projected under: the TF, or mu(HU) x the TF. */
  enum AttenuationModes
  {
    WEIGHT_ONLY = 0,
    HU_TO_MU = 1
  };

  ///@{
  /** The attenuation mode (default WEIGHT_ONLY, see the class comment). */
  vtkSetClampMacro(Attenuation, int, WEIGHT_ONLY, HU_TO_MU);
  vtkGetMacro(Attenuation, int);
  ///@}

  ///@{
  /** mu of water per world unit for HU_TO_MU (default 0.02 per mm, about 70 keV; 0.001-1). */
  vtkSetClampMacro(WaterAttenuation, double, 0.001, 1.0);
  vtkGetMacro(WaterAttenuation, double);
  ///@}

  /** The name of the output's field data with the automatic window. */
  static const char* AutomaticWindowName() { return "AutomaticWindow"; }

protected:
  vtkMCXViewProjector();
  ~vtkMCXViewProjector() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkNew<vtkCamera> ViewCamera;
  bool ViewCameraInUse = false;
  double ViewAspect = 0.0;
  int Attenuation = WEIGHT_ONLY;
  double WaterAttenuation = 0.02;

private:
  vtkMCXViewProjector(const vtkMCXViewProjector&) = delete;
  /// The size of an automatic image of the view's aspect; false when ImageSize
  /// or the aspect leaves it to the superclass.
  bool ViewImageSize(int size[2]) const;
  void operator=(const vtkMCXViewProjector&) = delete;
};

#endif
