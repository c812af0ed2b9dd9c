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
 * Space names are compared as teem compares them (any case, without spaces
 * or hyphens). A header without any space field keeps VTK's axis-aligned
 * placement (spacings, origin 0). The axes are the header's own: a first
 * axis is the voxels' components when its space direction is "none" or its
 * kind no domain (else, without either, when it has at most 9 samples, as
 * vtkNrrdReader guesses), whatever order the fields come in; 2 or 3 spatial
 * axes; a non-spatial axis after them is an error. Raw data shorter than
 * the header claims is an error before the read (VTK's reader only warns
 * and leaves zeros); the whole header is checked against the file before
 * VTK's reader parses it (CheckHeader). An error is one vtkErrorMacro
 * line naming the file and leaves an empty output.
 */
#ifndef vtkMCXNrrdReader_h
#define vtkMCXNrrdReader_h

#include "MonteCarloXRayIOModule.h" // for export macro
#include "vtkNrrdReader.h"

#include <string> // for the placement's problems
#include <vector> // for the data files

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

  ///@{
  /**
   * Whether RequestInformation checks the header against the file (CheckNrrdHeader in
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
  vtkMCXNrrdReader();
  ~vtkMCXNrrdReader() override = default;

  int ReadHeader(vtkCharArray* headerBuffer) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMCXNrrdReader(const vtkMCXNrrdReader&) = delete;
  void operator=(const vtkMCXNrrdReader&) = delete;

  // "" or why the header's dimension and sizes are no image VTK's reader
  // can read (checked before it reads them).
  static std::string CheckLayout(const std::string& header);
  // The extent, components and spacings of the header's own sizes.
  void SetLayout(const std::string& header);

  // The files that hold the voxels, and their bytes, as the header says.
  std::vector<std::string> DataFileNames() const;
  unsigned long long DataBytes() const;

  bool CheckHeader = true;
  std::string PlacementProblem; // from the last ReadHeader
  bool Failed = false;          // the last RequestInformation reported an error
};

#endif
