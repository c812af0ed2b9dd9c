#include "vtkMCXMaterialFractions.h"

#include "mcxMaterialDecomposition.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXSMPExecutor.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>

namespace mcx
{

vtkIdType FillMaterialFractions(const MaterialSet& set, vtkPolyData* cloud, vtkImageData* grid,
  vtkDataArray* values, const std::vector<int>& channels, const std::vector<double*>& weights)
{
  const vtkIdType count = cloud->GetNumberOfPoints();
  int dims[3], extent[6];
  grid->GetDimensions(dims);
  grid->GetExtent(extent);
  // The world-to-voxel map once, then every point in parallel: a point's
  // weights depend on it alone, so any split of the work gives the same.
  vtkMatrix4x4* toIndex = grid->GetPhysicalToIndexMatrix();
  double m[12];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m[4 * r + c] = toIndex->GetElement(r, c);
    }
  }
  vtkDataArray* points = cloud->GetPoints() ? cloud->GetPoints()->GetData() : nullptr;
  std::atomic<vtkIdType> outside(-1);
  const std::size_t k = channels.size();
  mcx::SMPExecutor().For(0, count, 4096,
    [&](std::int64_t begin, std::int64_t end)
    {
      std::vector<double> fractions(set.Size());
      for (std::int64_t i = begin; i < end; ++i)
      {
        double x[3];
        points->GetTuple(i, x);
        int index[3];
        bool centre = true;
        for (int a = 0; a < 3; ++a)
        {
          const double ijk =
            m[4 * a] * x[0] + m[4 * a + 1] * x[1] + m[4 * a + 2] * x[2] + m[4 * a + 3];
          index[a] = static_cast<int>(std::lround(ijk)) - extent[2 * a];
          // Voxel centres only: a point between voxels has no material of its own.
          centre = centre && std::abs(ijk - std::round(ijk)) <= 1e-3 && index[a] >= 0 &&
            index[a] < dims[a];
        }
        if (!centre)
        {
          // The first such point, whichever thread finds it: the message is the same on every run.
          vtkIdType seen = outside.load();
          while ((seen < 0 || i < seen) && !outside.compare_exchange_weak(seen, i))
          {
          }
          for (std::size_t c = 0; c < k; ++c)
          {
            weights[c][i] = 0.0;
          }
          continue;
        }
        const vtkIdType voxel =
          index[0] + dims[0] * (index[1] + static_cast<vtkIdType>(dims[1]) * index[2]);
        set.FixedFractionsAt(values->GetComponent(voxel, 0), fractions.data());
        for (std::size_t c = 0; c < k; ++c)
        {
          weights[c][i] = channels[c] < 0 ? 1.0 : fractions[channels[c]];
        }
      }
    });
  return outside.load();
}

vtkSmartPointer<vtkDoubleArray> IndexVoxelValues(vtkImageData* index)
{
  IndexView view;
  if (!view.Read(index).empty())
  {
    return nullptr;
  }
  const std::int64_t voxels =
    static_cast<std::int64_t>(view.Dimensions[0]) * view.Dimensions[1] * view.Dimensions[2];
  auto values = vtkSmartPointer<vtkDoubleArray>::New();
  values->SetNumberOfValues(static_cast<vtkIdType>(voxels));
  double* v = values->GetPointer(0);
  std::fill(v, v + voxels, std::numeric_limits<double>::quiet_NaN());
  vtkDataArray* ids = view.Ids;
  // Each level writes its own voxels: levels in parallel write disjoint ids.
  mcx::SMPExecutor().For(0, view.NumberOfLevels, 1,
    [&](std::int64_t begin, std::int64_t end)
    {
      for (std::int64_t l = begin; l < end; ++l)
      {
        const double value = view.LevelValues[l];
        for (std::int64_t i = view.LevelOffsets[l]; i < view.LevelOffsets[l + 1]; ++i)
        {
          v[static_cast<std::int64_t>(ids->GetComponent(static_cast<vtkIdType>(i), 0))] = value;
        }
      }
    });
  return values;
}

} // namespace mcx
