// The material fractions of a footprint cloud's points, for every channel in
// one pass over the points: shared by vtkMCXMaterialWeights (one channel) and
// the X-ray mapper's polychromatic mode (all of them at once).
#ifndef vtkMCXMaterialFractions_h
#define vtkMCXMaterialFractions_h

#include "MonteCarloXRayFiltersModule.h" // for the export macro
#include "vtkSmartPointer.h"             // for IndexVoxelValues
#include "vtkType.h"

#include <vector>

class vtkDataArray;
class vtkDoubleArray;
class vtkImageData;
class vtkPolyData;

namespace mcx
{
struct MaterialSet;

/// For each point of `cloud` (voxel centres of `grid`), weights[k][i] = the
/// mass fraction of material channels[k] (-1: 1) at its voxel's value in
/// `values` (one value per voxel of grid, x fastest from the extent's first
/// voxel), as MaterialSet::FixedFractionsAt rounds it. Each weights[k] holds
/// the cloud's number of points. Returns the first point that is no voxel
/// centre (its weights 0), whatever the threads, or -1.
MONTECARLOXRAYFILTERS_EXPORT vtkIdType FillMaterialFractions(const MaterialSet& set,
  vtkPolyData* cloud, vtkImageData* grid, vtkDataArray* values, const std::vector<int>& channels,
  const std::vector<double*>& weights);

/// The value of each voxel of a density index (vtkMCXDensityIndex's output),
/// its level's value: exact for integer data, the level's mean for binned
/// floating-point data; NaN where the index left a voxel out. Null when
/// `index` is not a readable density index.
MONTECARLOXRAYFILTERS_EXPORT vtkSmartPointer<vtkDoubleArray> IndexVoxelValues(vtkImageData* index);

} // namespace mcx

#endif
