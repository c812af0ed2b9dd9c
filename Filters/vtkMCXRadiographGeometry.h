/**
 * @class   vtkMCXRadiographGeometry
 * @brief   A cone-beam view as radiographers give it: source-to-axis and
 *          source-to-image distances, detector pixels and pitch, gantry
 *          angle and isocentre (the parameters of plastimatch drr).
 *
 * The source turns about the z axis through the isocentre: at gantry angle
 * a (degrees) it sits at isocentre + SAD (cos a, sin a, 0) and looks at the
 * isocentre; the flat detector lies SID from the source, beyond it, with
 * rows along +z (image row 0 at the bottom) and columns along
 * direction-of-projection x z (+y at angle 0), as plastimatch lays out its
 * images. ConfigureCamera() gives the vtkCamera of that view (for
 * vtkMCXProjector, vtkMCXReferenceProjector, or a renderer with the mapper);
 * the projectors then take GetDetectorPixels() as ImageSize and
 * GetPixelSpacingAtIsocenter() as PixelSpacing, so that their pixels are the
 * detector's. Pixel values stay line integrals along the rays.
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
  /** Detector pixel pitch, world units (default 0.8). */
  vtkSetClampMacro(PixelPitch, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(PixelPitch, double);
  ///@}

  ///@{
  /** Gantry angle in degrees (default 0: source on +x). */
  vtkSetMacro(GantryAngle, double);
  vtkGetMacro(GantryAngle, double);
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
   * a finite gantry angle and isocentre; otherwise an error says why.
   */
  bool IsValid();

  /**
   * Sets position, focal point, view-up, view angle and clipping range of
   * `camera`; false, with an error, when the geometry is not valid or there
   * is no camera.
   */
  bool ConfigureCamera(vtkCamera* camera);

  /** Pixel pitch scaled to the isocentre plane: PixelPitch SAD / SID. */
  double GetPixelSpacingAtIsocenter() const;

protected:
  vtkMCXRadiographGeometry() = default;
  ~vtkMCXRadiographGeometry() override = default;

  double SourceToAxisDistance = 1000.0;
  double SourceToImageDistance = 1500.0;
  int DetectorPixels[2] = { 512, 512 };
  double PixelPitch = 0.8;
  double GantryAngle = 0.0;
  double Isocenter[3] = { 0.0, 0.0, 0.0 };

private:
  vtkMCXRadiographGeometry(const vtkMCXRadiographGeometry&) = delete;
  void operator=(const vtkMCXRadiographGeometry&) = delete;
};

#endif
