// A DICOM series read with vtk-dicom (dgobbi's vtkDICOMReader, as hospitals
// export series): the folder's series found by vtkDICOMDirectory, one
// chosen, its slices sorted by position along the slice normal, rescale
// slope and intercept applied (CT in HU), and the volume placed in patient
// space by the patient matrix. VTK's own vtkDICOMImageReader trusts its
// headers and passes truncated slices silently.
#ifndef mcxDicomSeries_h
#define mcxDicomSeries_h

#include "vtkSmartPointer.h"

#include <string>

class vtkImageData;

namespace mcxapp
{

/// The series of folder: series is its number (1, 2, ...) in the folder's
/// list, or 0 when the folder must hold exactly one (else error lists them).
/// Slices at repeated positions and uneven gaps (missing slices) are errors
/// that say where; so are short pixel data. On failure returns null with
/// error set to one line.
vtkSmartPointer<vtkImageData> ReadDicomSeries(
  const std::string& folder, int series, std::string& error);

} // namespace mcxapp

#endif
