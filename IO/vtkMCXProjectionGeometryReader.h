/**
 * @class   vtkMCXProjectionGeometryReader
 * @brief   The poses of a geometry file as 3x4 projection matrices: RTK's
 *          circular geometry XML (every projection), a beam of a DICOM RT
 *          Plan (IEC 61217, head first supine), or a file of projection
 *          matrices (the JSON of mcxray's --output-geometry, or 12 numbers
 *          per pose as text), told apart by content.
 *
 * The matrices follow Core/mcxProjectionMatrix.h: P maps a world point in
 * patient space (LPS, mm) to (u w, v w, w), u the column, v the row counted
 * from the top, 0 at the first pixel's centre; give them to
 * vtkMCXProjector::SetProjectionMatrix with the detector's pixels as its
 * image size (GetImageSize). The conversion is mcxray's own
 * (mcxGeometryFilePoses, which --rtk-geometry, --rtplan and
 * --projection-matrices call): the same file and detector give the same
 * matrices here, in the command and in Python's mcxray.drr.
 *
 * RTK's file gives each projection's distances; the detector's first pixel
 * lies at DetectorOrigin (mm, RTK's projection origin) when
 * UseDetectorOrigin is on, else the grid is centred on RTK's detector
 * origin, as RTK's tools place it. An RT Plan's beam is chosen by Beam
 * (its BeamNumber or BeamName; empty: the plan's only beam); the source
 * lies SourceToAxisDistance from the isocentre only when the beam gives
 * no SourceAxisDistance, and the detector SourceToImageDistance from the
 * source. A vtkObject, not an algorithm: its product is a few numbers per
 * pose, for any pipeline to use.
 */
#ifndef vtkMCXProjectionGeometryReader_h
#define vtkMCXProjectionGeometryReader_h

#include "MonteCarloXRayIOModule.h" // for export macro
#include "vtkObject.h"

#include <memory> // for the poses

class MONTECARLOXRAYIO_EXPORT vtkMCXProjectionGeometryReader : public vtkObject
{
public:
  static vtkMCXProjectionGeometryReader* New();
  vtkTypeMacro(vtkMCXProjectionGeometryReader, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The geometry file: RTK's XML or a DICOM RT Plan. */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);

  /** RT Plan: the beam's BeamNumber or BeamName; empty (the default): the only beam. */
  vtkSetStringMacro(Beam);
  vtkGetStringMacro(Beam);

  /** Detector pixels (columns, rows). Default 512 x 512. */
  vtkSetVector2Macro(DetectorPixels, int);
  vtkGetVector2Macro(DetectorPixels, int);

  /** Pixel pitch on the detector (mm; along the columns, the rows). Default 0.8. */
  vtkSetVector2Macro(PixelPitch, double);
  void SetPixelPitch(double pitch) { this->SetPixelPitch(pitch, pitch); }
  vtkGetVector2Macro(PixelPitch, double);

  /** RT Plan: source to detector (mm). Default 1500. */
  vtkSetMacro(SourceToImageDistance, double);
  vtkGetMacro(SourceToImageDistance, double);

  /** RT Plan: source to isocentre (mm) of a beam that gives none. Default 1000. */
  vtkSetMacro(SourceToAxisDistance, double);
  vtkGetMacro(SourceToAxisDistance, double);

  /**
   * RT Plan: refuse a beam that gives its own SourceAxisDistance, so that a
   * distance the caller chose is never silently replaced (mcxray's --sad).
   * Off by default.
   */
  vtkSetMacro(UseSourceToAxisDistance, bool);
  vtkGetMacro(UseSourceToAxisDistance, bool);
  vtkBooleanMacro(UseSourceToAxisDistance, bool);

  /** RTK: the centre of the first pixel in RTK's detector frame (mm). */
  vtkSetVector2Macro(DetectorOrigin, double);
  vtkGetVector2Macro(DetectorOrigin, double);
  vtkSetMacro(UseDetectorOrigin, bool);
  vtkGetMacro(UseDetectorOrigin, bool);
  vtkBooleanMacro(UseDetectorOrigin, bool);

  /**
   * Reads the file and computes every pose. Returns false, with one error
   * line (the file, the projection or beam, and why), when the file gives no
   * poses; the previous poses are then gone.
   */
  bool Update();

  enum FileKinds
  {
    NoFile = 0,
    RTKGeometryFile = 1,
    RTPlanFile = 2,
    ProjectionMatricesFile = 3
  };

  /** What the last successful Update read (NoFile before one, or after a failure). */
  vtkGetMacro(FileKind, int);
  /** "none", "RTK geometry", "RT plan" or "projection matrices". */
  const char* GetFileKindAsString();

  ///@{
  /**
   * The kind of file the caller means (NoFile, the default: any). Update
   * tells the kind by the content; a file of another kind is then one error
   * line that names both (an RT plan asked for, an XML file given), not the
   * other reader's complaint.
   */
  vtkSetClampMacro(ExpectedFileKind, int, NoFile, ProjectionMatricesFile);
  vtkGetMacro(ExpectedFileKind, int);
  ///@}

  /** The poses the last Update gave: all of RTK's projections, or one beam. */
  int GetNumberOfPoses();

  /** Pose k's projection matrix, row by row. False for a k out of range. */
  bool GetProjectionMatrix(int k, double P[12]);

  /**
   * Pose k's detector pixels, columns and rows: DetectorPixels, or the size
   * a JSON file of matrices gives the pose. False for a k out of range.
   */
  bool GetImageSize(int k, int size[2]);

  /**
   * The distance (mm) from the source of the plane pose k's pixels are
   * measured on, for an image's spacing there (pitch x this / the
   * source-to-detector distance): RTK's SourceToDetectorDistance (the
   * detector), a beam's source-to-axis distance (the isocentre). 0 for a k
   * out of range.
   */
  double GetFocalPlaneDistance(int k);

protected:
  vtkMCXProjectionGeometryReader();
  ~vtkMCXProjectionGeometryReader() override;

  char* FileName = nullptr;
  char* Beam = nullptr;
  int DetectorPixels[2] = { 512, 512 };
  double PixelPitch[2] = { 0.8, 0.8 };
  double SourceToImageDistance = 1500.0;
  double SourceToAxisDistance = 1000.0;
  bool UseSourceToAxisDistance = false;
  double DetectorOrigin[2] = { 0, 0 };
  bool UseDetectorOrigin = false;
  int FileKind = NoFile;
  int ExpectedFileKind = NoFile;

private:
  vtkMCXProjectionGeometryReader(const vtkMCXProjectionGeometryReader&) = delete;
  void operator=(const vtkMCXProjectionGeometryReader&) = delete;

  struct PoseList;
  std::unique_ptr<PoseList> Poses;
};

#endif
