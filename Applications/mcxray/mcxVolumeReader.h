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
/// DICOM series directory). On failure returns null and sets error to one line.
vtkSmartPointer<vtkImageData> ReadVolume(const std::string& path, std::string& error);

/// The real CT bundled with the project (VTK's headsq, quarter resolution).
std::string BundledVolumePath();

} // namespace mcxapp

#endif
