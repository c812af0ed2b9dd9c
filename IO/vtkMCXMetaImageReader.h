/**
 * @class   vtkMCXMetaImageReader
 * @brief   A MetaImage volume (.mha, .mhd) placed in DICOM patient space
 *          (LPS) by its TransformMatrix and Offset, as ITK places it.
 *
 * VTK's vtkMetaImageReader keeps ElementSpacing and Offset (Position) and
 * drops the orientation. This reader reads the voxels with it and places
 * them as ITK writes and reads MetaImage (the world is LPS): the centre of
 * voxel (i, j, k) at Offset + i s0 r0 + j s1 r1 + k s2 r2, where s are the
 * ElementSpacing and r0, r1, r2 the rows of TransformMatrix (also spelled
 * Orientation or Rotation: row a is the direction of axis a).
 * AnatomicalOrientation is read and, as ITK, SimpleITK, Slicer and
 * plastimatch do, ignored: writers use it in both senses (ITK writes "RAI"
 * for the identity, others "LPS" for the same matrix), so it says nothing
 * the matrix does not. A matrix that is not finite or spans no volume, and
 * a non-finite or far origin, are errors. The header is checked against the
 * file first (CheckHeader). An error is one vtkErrorMacro
 * line naming the file and leaves an empty output.
 */
#ifndef vtkMCXMetaImageReader_h
#define vtkMCXMetaImageReader_h

#include "MonteCarloXRayIOModule.h" // for export macro
#include "vtkMetaImageReader.h"

class MONTECARLOXRAYIO_EXPORT vtkMCXMetaImageReader : public vtkMetaImageReader
{
public:
  static vtkMCXMetaImageReader* New();
  vtkTypeMacro(vtkMCXMetaImageReader, vtkMetaImageReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Whether RequestInformation checks the header against the file (CheckMetaImageHeader in
   * mcxHeaderCheck.h: sizes, type, the bytes the data hold) before the
   * superclass trusts it (default: on). A failed check is one vtkErrorMacro
   * line, the text mcxray prints, and an empty output. vtkMCXVolumeReader
   * turns it off: it checked the header itself.
   */
  vtkSetMacro(CheckHeader, bool);
  vtkGetMacro(CheckHeader, bool);
  vtkBooleanMacro(CheckHeader, bool);
  ///@}

protected:
  vtkMCXMetaImageReader() = default;
  ~vtkMCXMetaImageReader() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMCXMetaImageReader(const vtkMCXMetaImageReader&) = delete;
  void operator=(const vtkMCXMetaImageReader&) = delete;

  // Reads the header's placement into the Data* members; "" or the reason.
  std::string Place();

  bool CheckHeader = true;
  bool Failed = false; // the last RequestInformation reported an error
};

#endif
