// The checked reading of any volume format the project reads, as functions
// (vtkMCXVolumeReader is the same as a VTK reader): the header checked first
// (mcxHeaderCheck.h), then the reader the file's extension names, into
// vtkImageData in physical units placed in LPS (spacing, origin and
// direction as the file states them), or one line of error.
#ifndef mcxVolumeReader_h
#define mcxVolumeReader_h

#include "vtkSmartPointer.h"

#include <string>

class vtkImageData;

namespace mcxio
{

struct VolumeReadOptions
{
  unsigned long long MemoryBudget = 0; // bytes the claimed voxels may take; 0: any
  int DicomSeries = 0;                 // a folder's series (1, 2, ...); 0: its only one
  // How the caller's user sets the two, named in the messages that ask for
  // them (vtkMCXVolumeReader's setters; the command line's options).
  std::string MemoryBudgetName = "SetMemoryBudget";
  std::string DicomSeriesName = "SetDicomSeries(N)";
};

/// Reads path (.vti, .mha/.mhd, .nii/.nii.gz, .nrrd/.nhdr, .vtk, .slc, or a
/// DICOM series directory, read with vtk-dicom where it is available:
/// mcxDicomSeries.h), its header checked first (mcxHeaderCheck.h). On
/// failure returns null and sets error to one line ("cannot read 'path':
/// ..."). (In this process: mcxContainedReader.h reads in a child.)
vtkSmartPointer<vtkImageData> ReadVolume(
  const std::string& path, const VolumeReadOptions& options, std::string& error);

/// The same with the default options.
vtkSmartPointer<vtkImageData> ReadVolume(const std::string& path, std::string& error);

} // namespace mcxio

#endif
