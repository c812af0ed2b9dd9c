// Reads any volume format the command line accepts into vtkImageData in
// physical units (spacing, origin and direction as the file states them).
#ifndef mcxVolumeReader_h
#define mcxVolumeReader_h

#include "vtkSmartPointer.h"

#include <string>

class vtkImageData;

namespace mcxapp
{

struct VolumeReadOptions
{
  unsigned long long MemoryBudget = 0; // bytes the claimed voxels may take; 0: any
  int DicomSeries = 0;                  // a folder's series (1, 2, ...); 0: its only one
};

/// Reads path (.vti, .mha/.mhd, .nii/.nii.gz, .nrrd/.nhdr, .vtk, .slc, or a
/// DICOM series directory, read with vtk-dicom: mcxDicomSeries.h), its header
/// checked first (mcxHeaderCheck.h). On failure returns null and sets error
/// to one line. (In this process: the command line reads through
/// ReadVolumeContained.)
vtkSmartPointer<vtkImageData> ReadVolume(
  const std::string& path, const VolumeReadOptions& options, std::string& error);

/// The same with the default options.
vtkSmartPointer<vtkImageData> ReadVolume(const std::string& path, std::string& error);

/// The real CT bundled with the project (VTK's headsq, quarter resolution).
std::string BundledVolumePath();

} // namespace mcxapp

#endif
