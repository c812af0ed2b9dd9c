#include "vtkMCXDensityArrayPrivate.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkPointData.h"

namespace mcx
{

vtkDataArray* ChooseDensityArray(
  vtkImageData* image, const char* coloured, int association, std::string& problem)
{
  vtkPointData* pd = image->GetPointData();
  if (coloured && *coloured && association == vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    problem = std::string("the coloured array '") + coloured +
      "' is cell data; the X-ray needs densities at the points (apply Cell Data to Point Data)";
    return nullptr;
  }
  if (coloured && *coloured)
  {
    if (vtkDataArray* array = pd->GetArray(coloured))
    {
      if (array->GetNumberOfComponents() == 1)
      {
        return array;
      }
      problem = std::string("the coloured array '") + coloured + "' has " +
        std::to_string(array->GetNumberOfComponents()) +
        " components; colour by a one-component density array";
      return nullptr;
    }
  }
  if (vtkDataArray* scalars = pd->GetScalars())
  {
    if (scalars->GetNumberOfComponents() == 1)
    {
      return scalars;
    }
  }
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pd->GetArray(a);
    if (array && array->GetNumberOfComponents() == 1)
    {
      return array;
    }
  }
  problem =
    "the image has no one-component point array to show as an X-ray (a density such as CT values)";
  return nullptr;
}

} // namespace mcx
