/**
 * @class   vtkMCXNIFTIReader
 * @brief   A NIfTI-1 or NIfTI-2 volume (.nii, .nii.gz) in world space and
 *          physical values, as mcxray reads it.
 *
 * VTK's vtkNIFTIImageReader gives the voxels on a grid at the origin and
 * leaves the header's placement and scaling to the caller (ParaView's own
 * NIfTI reader ignores the sform). This reader applies them, in DICOM
 * patient space (LPS, vtkMCXPatientSpace) like every MonteCarloXRay reader:
 * - world = diag(-1, -1, 1) x form x (spacing x index), form the sform when
 *   the file has one, else the qform (NIfTI's world is RAS: x and y are
 *   negated): the output's origin, spacing (the steps' lengths) and
 *   direction matrix; a form that places no volume is an error;
 * - values = scl_slope x stored + scl_inter (float64), unless scl_slope is 0
 *   (no scaling, as NIfTI-1 says) or the pair is 1 and 0.
 * The header is checked against the file first (CheckHeader: a negative
 * dimension or data shorter than the header claims is an error before VTK's
 * reader allocates). An error is one vtkErrorMacro line (the wrapped reader's own reports are
 * folded into it) and leaves an empty output.
 */
#ifndef vtkMCXNIFTIReader_h
#define vtkMCXNIFTIReader_h

#include "MonteCarloXRayIOModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkNew.h" // for the wrapped reader

#include <string> // for the placement's problems

class vtkNIFTIImageReader;

class MONTECARLOXRAYIO_EXPORT vtkMCXNIFTIReader : public vtkImageAlgorithm
{
public:
  static vtkMCXNIFTIReader* New();
  vtkTypeMacro(vtkMCXNIFTIReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The .nii or .nii.gz file (default: none). */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  /** 1 if the file name ends in .nii or .nii.gz (what ParaView asks a reader). */
  int CanReadFile(const char* name);

  ///@{
  /**
   * Whether RequestInformation checks the header against the file (CheckNiftiHeader in
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
  vtkMCXNIFTIReader();
  ~vtkMCXNIFTIReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;

private:
  vtkMCXNIFTIReader(const vtkMCXNIFTIReader&) = delete;
  void operator=(const vtkMCXNIFTIReader&) = delete;

  // The header's placement and scaling, from the last RequestInformation.
  bool Rescale() const;
  std::string Place(vtkInformation* readerInfo); // "" or why the placement is unusable

  double Origin[3] = { 0, 0, 0 }; // LPS
  double Spacing[3] = { 1, 1, 1 };
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 }; // LPS

  vtkNew<vtkNIFTIImageReader> Reader;
  bool CheckHeader = true;
  bool Failed = false; // the last RequestInformation reported an error
};

#endif
