// Reads any volume format the command line accepts into vtkImageData in
// physical units (spacing, origin and direction as the file states them).
#ifndef mcxVolumeReader_h
#define mcxVolumeReader_h

#include "vtkSmartPointer.h"

#include <string>

class vtkImageData;

namespace mcxapp
{

/// Reads path (.vti, .mha/.mhd, .nii/.nii.gz, .nrrd/.nhdr, .vtk, .slc, or a
/// DICOM series directory), its header checked first (mcxHeaderCheck.h) and,
/// with memoryBudget > 0, the voxels it claims held to that many bytes. On
/// failure returns null and sets error to one line. (In this process: the
/// command line reads through ReadVolumeContained.)
vtkSmartPointer<vtkImageData> ReadVolume(
  const std::string& path, std::string& error, unsigned long long memoryBudget = 0);

/// The real CT bundled with the project (VTK's headsq, quarter resolution).
std::string BundledVolumePath();

} // namespace mcxapp

#endif
