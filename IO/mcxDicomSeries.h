// A DICOM series of the checked read (mcxVolumeReader.h):
// vtkMCXDICOMSeriesReader (with vtk-dicom) with the series numbered from 1,
// as vtkMCXVolumeReader and the command line number them. Where IO is built
// without vtk-dicom (ParaView's VTK), a folder is one line of error.
#ifndef mcxDicomSeries_h
#define mcxDicomSeries_h

#include "mcxVolumeReader.h"
#include "vtkSmartPointer.h"

#include <string>

class vtkImageData;

namespace mcxio
{

/// The series of folder: options.DicomSeries is its number (1, 2, ...) in
/// the folder's list, or 0 when the folder must hold exactly one (else error
/// lists them and says to choose one with options.DicomSeriesName, as
/// "--series N"). Slices at repeated positions and uneven gaps (missing
/// slices) are errors that say where; so are short pixel data. On failure
/// returns null with error set to one line. options.MemoryBudget (0: any)
/// bounds the voxels before they are read. The series is read in a child
/// process unless options.DicomInThisProcess.
vtkSmartPointer<vtkImageData> ReadDicomSeries(
  const std::string& folder, const VolumeReadOptions& options, std::string& error);

} // namespace mcxio

#endif
