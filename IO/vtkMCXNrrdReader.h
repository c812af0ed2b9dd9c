/**
 * @class   vtkMCXNrrdReader
 * @brief   A NRRD volume (.nrrd, .nhdr) placed in DICOM patient space (LPS)
 *          by its header's space, space directions and space origin.
 *
 * VTK's vtkNrrdReader keeps the lengths of the space directions as the
 * spacing and drops their orientation (and reverses the rows of a LAS
 * volume). This reader reads the voxels with it, in the file's order, and
 * places them as the NRRD format defines: the centre of sample (i, j, k) at
 * space origin + i d0 + j d1 + k d2, in the header's space converted to LPS:
 * - right-anterior-superior (RAS): x and y negated; left-anterior-superior
 *   (LAS): y negated; left-posterior-superior (LPS), scanner-xyz and
 *   3D-right-handed: as they are (as ITK reads them);
 * - a header with space dimension 3 and no space: taken as LPS;
 * - 3D-left-handed, the time spaces and unknown names are errors, as are
 *   space directions that are missing, not finite, zero or span no volume.
 * A header without any space field keeps VTK's axis-aligned placement
 * (spacings, origin 0). A first axis of 9 or fewer samples that the header
 * calls spatial (a space direction, or the kind domain or space) stays an
 * axis, where vtkNrrdReader would read it as the voxels' components. An error is one vtkErrorMacro
 * line naming the file and leaves an empty output.
 */
#ifndef vtkMCXNrrdReader_h
#define vtkMCXNrrdReader_h

#include "MonteCarloXRayIOModule.h" // for export macro
#include "vtkNrrdReader.h"

#include <string> // for the placement's problems

class MONTECARLOXRAYIO_EXPORT vtkMCXNrrdReader : public vtkNrrdReader
{
public:
  static vtkMCXNrrdReader* New();
  vtkTypeMacro(vtkMCXNrrdReader, vtkNrrdReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Places a header's text in LPS: origin, spacing and unit directions
   * (direction[3 * r + a], row r of axis a) of the image axes VTK's reader
   * makes (a leading "none" axis is the voxels' components). extent is the
   * image's extent. Returns "" on success, else the reason; a header
   * without any space field gives the identity with VTK's spacing.
   */
  static std::string PlaceHeader(const std::string& header, const int extent[6],
    const double vtkSpacing[3], double origin[3], double spacing[3], double direction[9]);

protected:
  vtkMCXNrrdReader();
  ~vtkMCXNrrdReader() override = default;

  int ReadHeader(vtkCharArray* headerBuffer) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMCXNrrdReader(const vtkMCXNrrdReader&) = delete;
  void operator=(const vtkMCXNrrdReader&) = delete;

  std::string PlacementProblem; // from the last ReadHeader
  bool Failed = false;          // the last RequestInformation reported an error
};

#endif
