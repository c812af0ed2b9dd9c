// The checked reading of any volume format the project reads, as functions
// (vtkMCXVolumeReader is the same as a VTK reader): the header checked first
// (mcxHeaderCheck.h), then the reader the file's extension names, into
// vtkImageData in physical units placed in LPS (spacing, origin and
// direction as the file states them), or one line of error.
#ifndef mcxVolumeReader_h
#define mcxVolumeReader_h

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

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
  // A DICOM folder is read in a child process of its own (vtk-dicom's parser
  // reads past its buffer on some files); true where this read is contained already.
  bool DicomInThisProcess = false;
};

/// Reads path (.vti, .mha/.mhd, .nii/.nii.gz, .nrrd/.nhdr, .vtk, .slc, or a
/// DICOM series directory, read with vtk-dicom where it is available:
/// mcxDicomSeries.h), its header checked first (mcxHeaderCheck.h). On
/// failure returns null and sets error to one line ("cannot read 'path':
/// ..."). (In this process: mcxContainedReader.h reads in a child.)
vtkSmartPointer<vtkImageData> ReadVolume(
  const std::string& path, const VolumeReadOptions& options, std::string& error);

/// Every file a ReadVolume of path may open, as paths (the output guard of
/// mcxray compares them by device and inode): path itself, the data files
/// its header names (mcxHeaderCheck.h's DataFiles: as the readers parse
/// the header), and for a folder every file the DICOM series reader's walk
/// finds (each is opened to learn its series) and a DICOMDIR.
std::vector<std::string> InputFiles(const std::string& path);

/// The same with the default options.
vtkSmartPointer<vtkImageData> ReadVolume(const std::string& path, std::string& error);

} // namespace mcxio

#endif
