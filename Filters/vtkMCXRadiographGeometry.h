/**
 * @class   vtkMCXRadiographGeometry
 * @brief   A cone-beam view as radiographers give it, in plastimatch drr's
 *          terms: source-to-axis and source-to-image distances, detector
 *          pixels and pitch, gantry angle (or detector normal), view-up,
 *          image centre and isocentre.
 *
 * The same angle gives the same view as `plastimatch drr` (1.9.4, checked
 * against the matrices it writes): at gantry angle a (degrees) the source
 * sits at isocentre + SAD (cos a, -sin a, 0) -- on +x at 0, on -y
 * (anterior, in LPS) at 90 -- and looks at the isocentre; with
 * UseDetectorNormal, at isocentre + SAD DetectorNormal instead. The flat
 * detector lies SID from the source, beyond the isocentre; its top row
 * towards ViewUp (default +z), its columns along ViewUp x normal (+y at
 * angle 0). GetProjectionMatrix() gives the view as a 3x4 matrix for the
 * projectors (vtkMCXProjectorBase::SetProjectionMatrix, with
 * GetDetectorPixels() as ImageSize); ConfigureCamera() gives the vtkCamera
 * of the view where a camera can hold it (square pixels, the image centre
 * at the detector's centre), for a renderer with the mapper. Pixel values
 * stay line integrals along the rays.
 */
#ifndef vtkMCXRadiographGeometry_h
#define vtkMCXRadiographGeometry_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkObject.h"

class vtkCamera;

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXRadiographGeometry : public vtkObject
{
public:
  static vtkMCXRadiographGeometry* New();
  vtkTypeMacro(vtkMCXRadiographGeometry, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Source-to-axis (isocentre) distance, world units (default 1000). */
  vtkSetClampMacro(SourceToAxisDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SourceToAxisDistance, double);
  ///@}

  ///@{
  /** Source-to-image (detector) distance, world units (default 1500). */
  vtkSetClampMacro(SourceToImageDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SourceToImageDistance, double);
  ///@}

  ///@{
  /** Detector size in pixels, columns x rows, each 1 to 65536 (default 512 x 512). */
  virtual void SetDetectorPixels(int columns, int rows);
  void SetDetectorPixels(const int pixels[2]) { this->SetDetectorPixels(pixels[0], pixels[1]); }
  vtkGetVector2Macro(DetectorPixels, int);
  ///@}

  ///@{
  /**
   * Detector pixel pitch along the columns and the rows, world units
   * (default 0.8, 0.8); one value sets both.
   */
  vtkSetVector2Macro(PixelPitch, double);
  void SetPixelPitch(double pitch) { this->SetPixelPitch(pitch, pitch); }
  vtkGetVector2Macro(PixelPitch, double);
  ///@}

  ///@{
  /** Gantry angle in degrees (default 0: source on +x; 90: on -y). */
  vtkSetMacro(GantryAngle, double);
  vtkGetMacro(GantryAngle, double);
  ///@}

  ///@{
  /**
   * The direction from the isocentre to the source, used instead of the
   * gantry angle when UseDetectorNormal is on (default off; plastimatch's
   * --nrm).
   */
  vtkSetVector3Macro(DetectorNormal, double);
  vtkGetVector3Macro(DetectorNormal, double);
  vtkSetMacro(UseDetectorNormal, bool);
  vtkGetMacro(UseDetectorNormal, bool);
  vtkBooleanMacro(UseDetectorNormal, bool);
  ///@}

  ///@{
  /** Towards the detector's top row (default 0, 0, 1; plastimatch's --vup). */
  vtkSetVector3Macro(ViewUp, double);
  vtkGetVector3Macro(ViewUp, double);
  ///@}

  ///@{
  /**
   * The pixel (column, row from the top, 0 at the first pixel's centre)
   * where the ray through the isocentre lands, used when UseImageCenter is
   * on (default off: the detector's centre; plastimatch's -c).
   */
  vtkSetVector2Macro(ImageCenter, double);
  vtkGetVector2Macro(ImageCenter, double);
  vtkSetMacro(UseImageCenter, bool);
  vtkGetMacro(UseImageCenter, bool);
  vtkBooleanMacro(UseImageCenter, bool);
  ///@}

  ///@{
  /** Isocentre, world coordinates (default 0, 0, 0). */
  vtkSetVector3Macro(Isocenter, double);
  vtkGetVector3Macro(Isocenter, double);
  ///@}

  /** Largest detector side in pixels. */
  static constexpr int MaximumDetectorPixels = 65536;

  /**
   * True when the geometry is usable: positive, finite distances and pitch,
   * a finite gantry angle, isocentre and image centre, a view-up that is
   * not along the normal; otherwise an error says why.
   */
  bool IsValid();

  /**
   * The view's 3x4 projection matrix (world to the column and the row
   * counted from the top, the layout of vtkMCXProjectorBase's
   * ProjectionMatrix); false, with an error, when the geometry is not valid.
   */
  bool GetProjectionMatrix(double matrix[12]);

  /**
   * Sets position, focal point, view-up, view angle and clipping range of
   * `camera`; false, with an error, when there is no camera, the geometry is
   * not valid, or a camera cannot hold it (pixels that are not square, an
   * image centre elsewhere than the detector's centre).
   */
  bool ConfigureCamera(vtkCamera* camera);

  /** Pixel pitch along the columns scaled to the isocentre plane: PixelPitch[0] SAD / SID. */
  double GetPixelSpacingAtIsocenter() const;

protected:
  vtkMCXRadiographGeometry() = default;
  ~vtkMCXRadiographGeometry() override = default;

  double SourceToAxisDistance = 1000.0;
  double SourceToImageDistance = 1500.0;
  int DetectorPixels[2] = { 512, 512 };
  double PixelPitch[2] = { 0.8, 0.8 };
  double GantryAngle = 0.0;
  double DetectorNormal[3] = { 1, 0, 0 };
  bool UseDetectorNormal = false;
  double ViewUp[3] = { 0, 0, 1 };
  double ImageCenter[2] = { 0, 0 };
  bool UseImageCenter = false;
  double Isocenter[3] = { 0.0, 0.0, 0.0 };

private:
  vtkMCXRadiographGeometry(const vtkMCXRadiographGeometry&) = delete;
  void operator=(const vtkMCXRadiographGeometry&) = delete;
};

#endif
