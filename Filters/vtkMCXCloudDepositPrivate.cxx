#include "vtkMCXCloudDepositPrivate.h"

#include "vtkMCXPointSampler.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkPolyData.h"

#include <cmath>

namespace mcx
{

namespace
{
double Field(vtkFieldData* fd, const char* name, double fallback)
{
  vtkDataArray* array = fd ? fd->GetArray(name) : nullptr;
  return array && array->GetNumberOfTuples() > 0 ? array->GetTuple1(0) : fallback;
}
}

DepositSettings CloudDepositSettings(vtkPolyData* cloud, const ProjectionGeometry& geometry,
  const double origin[3], const double matrix[9])
{
  DepositSettings settings;
  vtkFieldData* fd = cloud->GetFieldData();
  vtkDataArray* axes = fd ? fd->GetArray(vtkMCXPointSampler::VoxelAxesName()) : nullptr;
  const bool footprint = Field(fd, vtkMCXPointSampler::DepositName(), vtkMCXPointSampler::POINT) ==
      vtkMCXPointSampler::FOOTPRINT &&
    axes && axes->GetNumberOfValues() == 9;
  if (!footprint)
  {
    return settings;
  }
  settings.Mode = Deposit::Footprint;
  settings.Reconstruction =
    Field(fd, vtkMCXPointSampler::KernelName(), 0) == vtkMCXPointSampler::BOX ? Kernel::Box
                                                                              : Kernel::Tent;
  settings.Seed = static_cast<std::uint64_t>(Field(fd, vtkMCXPointSampler::SeedName(), 0));
  settings.Stratified = Field(fd, vtkMCXPointSampler::StrategyName(), vtkMCXPointSampler::HYBRID) !=
    vtkMCXPointSampler::MONTE_CARLO;
  for (int i = 0; i < 9; ++i)
  {
    settings.VoxelMatrix[i] =
      axes->GetComponent(i / axes->GetNumberOfComponents(), i % axes->GetNumberOfComponents());
    if (!std::isfinite(settings.VoxelMatrix[i]))
    {
      return DepositSettings(); // not a sampler's cloud: deposit its points as points
    }
  }
  vtkDataArray* support = fd->GetArray(vtkMCXPointSampler::SupportCornersName());
  if (geometry.Perspective && support && support->GetNumberOfValues() == 24)
  {
    // The sampler's support: the same tables for every prefix of the cloud.
    double corners[24];
    for (int i = 0; i < 24; ++i)
    {
      const double p = support->GetComponent(
        i / support->GetNumberOfComponents(), i % support->GetNumberOfComponents());
      corners[i] = p;
    }
    double world[24];
    for (int c = 0; c < 8; ++c)
    {
      for (int r = 0; r < 3; ++r)
      {
        world[3 * c + r] = origin[r] + matrix[3 * r] * corners[3 * c] +
          matrix[3 * r + 1] * corners[3 * c + 1] + matrix[3 * r + 2] * corners[3 * c + 2];
      }
    }
    SupportDepthRange(geometry, world, settings.Depths);
  }
  else if (geometry.Perspective && cloud->GetNumberOfPoints() > 0)
  {
    // The points' bounds, grown by the kernel's reach along each axis.
    double bounds[6];
    cloud->GetBounds(bounds);
    const double radius = KernelRadius(settings.Reconstruction);
    for (int r = 0; r < 3; ++r)
    {
      const double* m = settings.VoxelMatrix + 3 * r;
      const double grow = radius * (std::fabs(m[0]) + std::fabs(m[1]) + std::fabs(m[2]));
      bounds[2 * r] -= grow;
      bounds[2 * r + 1] += grow;
    }
    double corners[24];
    for (int c = 0; c < 8; ++c)
    {
      const double p[3] = { bounds[c & 1], bounds[2 + ((c >> 1) & 1)], bounds[4 + ((c >> 2) & 1)] };
      for (int r = 0; r < 3; ++r)
      {
        corners[3 * c + r] =
          origin[r] + matrix[3 * r] * p[0] + matrix[3 * r + 1] * p[1] + matrix[3 * r + 2] * p[2];
      }
    }
    SupportDepthRange(geometry, corners, settings.Depths);
  }
  return settings;
}

} // namespace mcx
