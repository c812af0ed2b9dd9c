/**
 * @class   vtkMCXMetaImageReader
 * @brief   A MetaImage volume (.mha, .mhd) placed in DICOM patient space
 *          (LPS) by its TransformMatrix, Offset and AnatomicalOrientation.
 *
 * VTK's vtkMetaImageReader keeps ElementSpacing and Offset (Position) and
 * drops the orientation. This reader reads the voxels with it and places
 * them as ITK writes and reads MetaImage (the world is LPS): the centre of
 * voxel (i, j, k) at Offset + i s0 r0 + j s1 r1 + k s2 r2, where s are the
 * ElementSpacing and r0, r1, r2 the rows of TransformMatrix (also spelled
 * Orientation or Rotation: row a is the direction of axis a). When the
 * matrix is the identity (or absent) and AnatomicalOrientation names three
 * distinct axes, its letters give the directions instead, as MetaIO defines
 * them: each is where the axis comes from (R: the axis runs to the left,
 * +x; L: -x; A: +y, to the posterior; P: -y; I: +z; S: -z), so "RAI" is
 * the identity. ITK ignores AnatomicalOrientation; it differs from this
 * reader only on a header whose matrix is the identity and whose
 * orientation is not RAI. A matrix that is not finite or spans no volume,
 * and a non-finite or far origin, are errors. An error is one vtkErrorMacro
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

  bool Failed = false; // the last RequestInformation reported an error
};

#endif
