// The checks that a DICOM series' images make one volume as vtk-dicom's
// vtkDICOMReader sorts them (vtkMCXDICOMSeriesReader's): every image placed
// and stacked, and the slices evenly spaced.
#ifndef mcxDicomSliceChecks_h
#define mcxDicomSliceChecks_h

#include <string>

class vtkDICOMReader;

namespace mcxio
{

/// Whether the images stack into one volume as reader (its information
/// updated) reads it: each with a position, the first image's orientation
/// and pixel spacing (> 0), and a finite rescale; and every image of the
/// series in the volume (its slice sorter leaves out what does not stack,
/// a tilted slice). Empty when they do, else which image does not and why.
std::string CheckSlicesStack(vtkDICOMReader* reader);

/// Repeated positions, gaps of more than 1.5 times the median spacing
/// (missing slices) and slices off the even spacing the volume gives them,
/// along normal (the slices' normal in patient space); empty when the
/// slices are evenly spaced.
std::string CheckSliceSpacing(vtkDICOMReader* reader, const double normal[3]);

} // namespace mcxio

#endif
