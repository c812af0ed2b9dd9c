/**
 * @class   vtkMCXProjectorBase
 * @brief   Detector geometry, transfer function and kernel shared by the
 *          Monte Carlo and the exact X-ray projectors.
 *
 * The view is a 3x4 projection matrix with ImageSize (UseProjectionMatrix),
 * or a vtkCamera (parallel or perspective), or, without either, an explicit
 * parallel detector with axes DetectorAxisU and
 * DetectorAxisV (rays run along their cross product). ImageSize and
 * PixelSpacing set the image; what is left at 0 is chosen so that the image
 * covers the projected support of g (the volume grown by the kernel) -- with a
 * camera, the camera sets the field of view instead and the size defaults to
 * 512 x 512.
 *
 * The output is a 2D vtkImageData (extent [0, W-1] x [0, H-1] x [0, 0]) whose
 * point data "LineIntegral" (float64) holds, per pixel, the mean over the
 * pixel's area of the line integral of g along the ray: TF units times world
 * length. Its origin and spacing are detector-plane coordinates of the pixel
 * centres: (x . U, x . V) in a parallel view; for a perspective camera,
 * coordinates on the focal plane measured from the principal point. For a
 * perspective camera only depths beyond the camera's near clipping distance
 * count. Its field data "ProjectionMatrix" holds the image's 3x4 matrix
 * (12 values, row-major): world to (u w, v w, w), u the column, v the row
 * counted from the top row (j = H - 1), w > 0 in front of the source -- the
 * layout of OpenCV's K [R | t] and of plastimatch's matrices; affine (last
 * row 0 0 0 1) for a parallel view.
 */
#ifndef vtkMCXProjectorBase_h
#define vtkMCXProjectorBase_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkMCXTypes.h" // for the array names and constants
#include "vtkImageAlgorithm.h"

#include <string> // for std::string

class vtkCamera;
class vtkDoubleArray;
class vtkPiecewiseFunction;

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXProjectorBase : public vtkImageAlgorithm
{
public:
  vtkTypeMacro(vtkMCXProjectorBase, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Camera of the view; without one, the explicit parallel detector is used. */
  virtual void SetCamera(vtkCamera*);
  vtkGetObjectMacro(Camera, vtkCamera);
  ///@}

  ///@{
  /**
   * A view given as a 3x4 projection matrix (row-major, the layout of the
   * output's ProjectionMatrix field, any nonzero scale): perspective, or
   * parallel when affine (last row 0 0 0 c; the rays along its rows' null
   * direction, oblique where those rows are not perpendicular): used
   * instead of the camera and the explicit detector when
   * UseProjectionMatrix is on (default off), with ImageSize, which must
   * then be set. A matrix that is no camera (not finite, rank below 3 and
   * not affine, affine with dependent rows, skewed pixels) fails the
   * request with the reason.
   */
  virtual void SetProjectionMatrix(const double matrix[12]);
  void GetProjectionMatrix(double matrix[12]) const;
  vtkSetMacro(UseProjectionMatrix, bool);
  vtkGetMacro(UseProjectionMatrix, bool);
  vtkBooleanMacro(UseProjectionMatrix, bool);
  ///@}

  ///@{
  /**
   * With a projection matrix: the distance from the source of the plane on
   * which the output's pixels are measured (its spacing and, with
   * PlaceOnDetectorPlane, where it lies); 0 (default) puts it through the
   * centre of the volume's support. The values do not depend on it. An
   * affine (parallel) matrix has no source: its pixels are its own.
   */
  vtkSetClampMacro(FocalPlaneDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(FocalPlaneDistance, double);
  ///@}

  ///@{
  /**
   * Unit, orthogonal image axes of the explicit parallel detector (default x
   * and y: a view along z). Image axis 0 runs along U and axis 1 along V.
   */
  vtkSetVector3Macro(DetectorAxisU, double);
  vtkGetVector3Macro(DetectorAxisU, double);
  vtkSetVector3Macro(DetectorAxisV, double);
  vtkGetVector3Macro(DetectorAxisV, double);
  ///@}

  ///@{
  /**
   * Explicit parallel detector only: when CenterOnVolume is on (default) the
   * image is centred on the projected support of g; when off, on
   * DetectorCenter (detector-plane coordinates, default 0, 0). The support
   * is where the input data place the volume, also when a filter upstream
   * left the direction out of the pipeline information (ParaView's input
   * post filter does; the image's information then told the unturned
   * framing, and the image itself is framed again on the data).
   */
  vtkSetVector2Macro(DetectorCenter, double);
  vtkGetVector2Macro(DetectorCenter, double);
  vtkSetMacro(CenterOnVolume, bool);
  vtkGetMacro(CenterOnVolume, bool);
  vtkBooleanMacro(CenterOnVolume, bool);
  ///@}

  ///@{
  /**
   * Where the output lies (default off). Off: in the XY plane, its origin
   * and spacing in detector-plane coordinates (pixel (i, j) at
   * (Origin[0] + i s, Origin[1] + j s, 0)). On: in the view's detector plane
   * in world space, with the direction matrix (U, V, U x V) of the detector
   * axes (a rotation), so that a 3D scene shows the image where the
   * detector of its view is, facing the view. The plane is the camera's
   * focal plane (for an off-axis or sheared camera: the plane at the
   * camera's distance from the centre of projection, parallel to the
   * screen), or for an explicit detector the plane through the centre of
   * the volume's support. The values do not change.
   */
  vtkSetMacro(PlaceOnDetectorPlane, bool);
  vtkGetMacro(PlaceOnDetectorPlane, bool);
  vtkBooleanMacro(PlaceOnDetectorPlane, bool);
  ///@}

  ///@{
  /** Image size in pixels; 0 picks it automatically (see the class description). */
  vtkSetVector2Macro(ImageSize, int);
  vtkGetVector2Macro(ImageSize, int);
  ///@}

  ///@{
  /** Square pixel size in world units on the detector plane; 0 = automatic. */
  vtkSetClampMacro(PixelSpacing, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(PixelSpacing, double);
  ///@}

  ///@{
  /** Longest image side when both size and spacing are automatic (default 512). */
  vtkSetClampMacro(DefaultImageSize, int, 1, 1 << 16);
  vtkGetMacro(DefaultImageSize, int);
  ///@}

  ///@{
  /**
   * Transfer function from data values to g (used with an index input);
   * without one, g is the data value. Negative and NaN values count as 0.
   */
  virtual void SetTransferFunction(vtkPiecewiseFunction*);
  vtkGetObjectMacro(TransferFunction, vtkPiecewiseFunction);
  ///@}

  ///@{
  /** Reconstruction kernel, vtkMCXTypes::TENT (default) or BOX. */
  vtkSetClampMacro(Kernel, int, 0, 1);
  vtkGetMacro(Kernel, int);
  ///@}

  /** Includes the camera's and the transfer function's modification times. */
  vtkMTimeType GetMTime() override;

protected:
  vtkMCXProjectorBase();
  ~vtkMCXProjectorBase() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * The failure of a request as all the processes that share the work see
   * it (the first one's, or "" when none failed); this one process's by
   * default. A subclass whose processes wait for each other agrees here, so
   * that all fail or none.
   */
  virtual std::string AgreeOnFailure(vtkInformation* inInfo, const std::string& failure);
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * Frames the image again (no camera) when the input data place the volume
   * elsewhere than its information said, as when a filter upstream dropped
   * the DIRECTION key; call it first in RequestData. False (reported) when
   * the data's volume cannot be framed, and (reported once, by
   * RequestInformation) when the information could make no image.
   */
  bool FrameOnInputData(vtkDataObject* input, vtkInformation* inInfo);

  /**
   * Gives the output its extent, origin and spacing, a zeroed LineIntegral
   * array, and field data that hold only the ProjectionMatrix (call it first).
   */
  vtkDoubleArray* AllocateLineIntegral(vtkImageData* output);

  /** The output's origin and direction matrix (see PlaceOnDetectorPlane). */
  void OutputPlacement(double origin[3], double direction[9]) const;

  vtkCamera* Camera = nullptr;
  double ProjectionMatrix[12] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1 };
  bool UseProjectionMatrix = false;
  double FocalPlaneDistance = 0.0;
  double DetectorAxisU[3] = { 1, 0, 0 };
  double DetectorAxisV[3] = { 0, 1, 0 };
  double DetectorCenter[2] = { 0, 0 };
  bool CenterOnVolume = true;
  bool PlaceOnDetectorPlane = false;
  int ImageSize[2] = { 0, 0 };
  double PixelSpacing = 0.0;
  int DefaultImageSize = 512;
  vtkPiecewiseFunction* TransferFunction = nullptr;
  int Kernel = 0;

  // The geometry computed by the last RequestInformation (or
  // FrameOnInputData); defined in vtkMCXProjectorBaseInternals.h for the
  // subclasses.
  struct vtkInternals;
  vtkInternals* Internals;

private:
  vtkMCXProjectorBase(const vtkMCXProjectorBase&) = delete;
  void operator=(const vtkMCXProjectorBase&) = delete;
};

#endif
