// The density array the X-ray representation shows, chosen as ParaView's
// Volume representation picks the array it colours by.
#ifndef vtkMCXDensityArrayPrivate_h
#define vtkMCXDensityArrayPrivate_h

#include <string>

class vtkDataArray;
class vtkImageData;

namespace mcx
{
// The coloured array when it is a one-component point array, else the active
// point scalars, else the first one-component point array; null when the
// image has none (problem says why).
vtkDataArray* ChooseDensityArray(
  vtkImageData* image, const char* coloured, int association, std::string& problem);
}

#endif
