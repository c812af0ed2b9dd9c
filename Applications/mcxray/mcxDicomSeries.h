// A DICOM series for the command line: vtkMCXDICOMSeriesReader (IO/, with
// vtk-dicom) with the series numbered as --series numbers them.
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
