#include "vtkMCXCloudDeposit.h"

#include "vtkMCXPointSampler.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace mcx
{

namespace
{
// GeometryToValues' place of the near distance.
constexpr int NearDistanceValue = 14;

// Whether two of GeometryToValues' values make the same image: equal to
// 1e-6 of their size (a unit vector's, a length's in the data's units), a
// shift of the image by at most about 1e-6 of its width. The camera a
// viewer renders with can differ from the one it ordered by in the last
// float digits (measured: 3e-8 of the pixel spacing in `mcxray view`).
bool CloseGeometryValue(double a, double b)
{
  return a == b || std::fabs(a - b) <= 1e-6 * std::max({ 1.0, std::fabs(a), std::fabs(b) });
}

// Whether the near planes at geometry.NearDistance and at `otherNear` both
// leave every sample of the cloud (inside its SupportCorners) in view, so
// that the two geometries make the same image: ParaView resets the
// clipping range when it renders, after the sampler took the camera.
bool NearPlanesClipNothing(vtkPolyData* cloud, const ProjectionGeometry& geometry, double otherNear)
{
  if (!geometry.Perspective)
  {
    return true; // a parallel view clips nothing at its near plane
  }
  double depths[2];
  return CloudSupportDepths(cloud, geometry, depths) && geometry.NearDistance < depths[0] &&
    otherNear < depths[0];
}

double Field(vtkFieldData* fd, const char* name, double fallback)
{
  vtkDataArray* array = fd ? fd->GetArray(name) : nullptr;
  return array && array->GetNumberOfTuples() > 0 ? array->GetTuple1(0) : fallback;
}
}

DepositSettings CloudDepositSettings(vtkPolyData* cloud, const ProjectionGeometry& geometry,
  const double origin[3], const double matrix[9], double footprintReach)
{
  DepositSettings settings;
  vtkFieldData* fd = cloud->GetFieldData();
  vtkDataArray* axes = fd ? fd->GetArray(vtkMCXTypes::VoxelAxesName()) : nullptr;
  const bool footprint =
    Field(fd, vtkMCXTypes::DepositName(), vtkMCXTypes::POINT) == vtkMCXTypes::FOOTPRINT && axes &&
    axes->GetNumberOfValues() == 9;
  if (!footprint)
  {
    return settings;
  }
  settings.Mode = Deposit::Footprint;
  settings.Reach = footprintReach;
  settings.Reconstruction =
    Field(fd, vtkMCXTypes::KernelName(), 0) == vtkMCXTypes::BOX ? Kernel::Box : Kernel::Tent;
  settings.Seed = static_cast<std::uint64_t>(Field(fd, vtkMCXTypes::SeedName(), 0));
  settings.Stratified =
    Field(fd, vtkMCXTypes::StrategyName(), vtkMCXTypes::HYBRID) != vtkMCXTypes::MONTE_CARLO;
  for (int i = 0; i < 9; ++i)
  {
    settings.VoxelMatrix[i] =
      axes->GetComponent(i / axes->GetNumberOfComponents(), i % axes->GetNumberOfComponents());
    if (!std::isfinite(settings.VoxelMatrix[i]))
    {
      return DepositSettings(); // not a sampler's cloud: deposit its points as points
    }
  }
  if (!geometry.Perspective)
  {
    return settings;
  }
  // The support's corners in cloud coordinates: the sampler's (the same
  // tables for every prefix of the cloud), else the points' bounds grown by
  // the kernel's reach along each axis.
  double corners[24];
  if (!CloudSupportCorners(cloud, corners))
  {
    if (cloud->GetNumberOfPoints() == 0)
    {
      return settings;
    }
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
    for (int c = 0; c < 8; ++c)
    {
      for (int a = 0; a < 3; ++a)
      {
        corners[3 * c + a] = bounds[2 * a + ((c >> a) & 1)];
      }
    }
  }
  double world[24];
  for (int c = 0; c < 8; ++c)
  {
    const double* p = corners + 3 * c;
    for (int r = 0; r < 3; ++r)
    {
      world[3 * c + r] =
        origin[r] + matrix[3 * r] * p[0] + matrix[3 * r + 1] * p[1] + matrix[3 * r + 2] * p[2];
    }
  }
  SupportDepthRange(geometry, world, settings.Depths);
  return settings;
}

bool IsEveryVoxelCloud(vtkPolyData* cloud)
{
  return Field(cloud->GetFieldData(), vtkMCXTypes::StrategyName(), vtkMCXTypes::HYBRID) ==
    vtkMCXTypes::EVERY_VOXEL;
}

std::vector<double> CloudControlImage(
  vtkPolyData* cloud, const ProjectionGeometry& geometry, double& variance)
{
  variance = 0.0;
  vtkFieldData* fd = cloud->GetFieldData();
  vtkDataArray* image = fd ? fd->GetArray(vtkMCXTypes::ControlImageName()) : nullptr;
  vtkDataArray* view = fd ? fd->GetArray(vtkMCXTypes::ControlViewName()) : nullptr;
  const vtkIdType pixels = static_cast<vtkIdType>(geometry.Size[0]) * geometry.Size[1];
  if (!image || !view || image->GetNumberOfComponents() != 1 ||
    image->GetNumberOfTuples() != pixels || view->GetNumberOfComponents() != 1 ||
    view->GetNumberOfTuples() != GeometryValueCount)
  {
    return std::vector<double>();
  }
  double wanted[GeometryValueCount];
  GeometryToValues(geometry, wanted);
  for (int i = 0; i < GeometryValueCount; ++i)
  {
    const double made = view->GetComponent(i, 0);
    if (!CloseGeometryValue(made, wanted[i]) &&
      !(i == NearDistanceValue && NearPlanesClipNothing(cloud, geometry, made)))
    {
      return std::vector<double>();
    }
  }
  vtkDataArray* made = fd->GetArray(vtkMCXTypes::ControlPointsName());
  vtkSmartPointer<vtkDoubleArray> these = ControlPointsOf(cloud->GetPoints());
  if (!made || made->GetNumberOfComponents() != 1 ||
    made->GetNumberOfTuples() != these->GetNumberOfTuples())
  {
    return std::vector<double>();
  }
  for (vtkIdType i = 0; i < these->GetNumberOfTuples(); ++i)
  {
    if (made->GetComponent(i, 0) != these->GetValue(i))
    {
      return std::vector<double>();
    }
  }
  // Absent: a control of every voxel, as before the variance was written.
  if (vtkDataArray* varianceArray = fd->GetArray(vtkMCXTypes::ControlVarianceName()))
  {
    if (varianceArray->GetNumberOfValues() != 1)
    {
      return std::vector<double>();
    }
    variance = varianceArray->GetComponent(0, 0);
    if (!(variance >= 0 && std::isfinite(variance)))
    {
      variance = 0.0;
      return std::vector<double>();
    }
  }
  std::vector<double> control(static_cast<std::size_t>(pixels));
  for (vtkIdType p = 0; p < pixels; ++p)
  {
    control[static_cast<std::size_t>(p)] = image->GetComponent(p, 0);
    if (!std::isfinite(control[static_cast<std::size_t>(p)]))
    {
      return std::vector<double>();
    }
  }
  return control;
}

bool CloudSupportCorners(vtkDataObject* data, double corners[24])
{
  vtkFieldData* fd = data ? data->GetFieldData() : nullptr;
  vtkDataArray* support = fd ? fd->GetArray(vtkMCXTypes::SupportCornersName()) : nullptr;
  if (!support || support->GetNumberOfValues() != 24)
  {
    return false;
  }
  const int components = support->GetNumberOfComponents();
  for (int i = 0; i < 24; ++i)
  {
    corners[i] = support->GetComponent(i / components, i % components);
  }
  return true;
}

bool CloudSupportDepths(vtkPolyData* cloud, const ProjectionGeometry& geometry, double depths[2])
{
  double corners[24];
  if (!CloudSupportCorners(cloud, corners))
  {
    return false;
  }
  CornerDepths(geometry, corners, depths);
  return std::isfinite(depths[0]) && std::isfinite(depths[1]);
}

vtkSmartPointer<vtkDoubleArray> ControlPointsOf(vtkPoints* points)
{
  auto values = vtkSmartPointer<vtkDoubleArray>::New();
  values->SetName(vtkMCXTypes::ControlPointsName());
  values->SetNumberOfValues(3);
  double first[3] = { 0, 0, 0 };
  if (points && points->GetNumberOfPoints() > 0)
  {
    points->GetPoint(0, first);
  }
  for (int a = 0; a < 3; ++a)
  {
    values->SetValue(a, first[a]);
  }
  return values;
}

vtkDataArray* CloudPointWeights(vtkObject* self, vtkPolyData* cloud, bool& valid)
{
  valid = true;
  vtkDataArray* weights = cloud->GetPointData()->GetArray(vtkMCXTypes::PointWeightName());
  if (!weights)
  {
    return nullptr;
  }
  std::string problem;
  const vtkIdType points = cloud->GetNumberOfPoints();
  const int type = weights->GetDataType();
  if ((type != VTK_FLOAT && type != VTK_DOUBLE) || weights->GetNumberOfComponents() != 1 ||
    weights->GetNumberOfTuples() != points)
  {
    problem = "it must be one float or double component per point, not " +
      std::to_string(weights->GetNumberOfComponents()) + " " + weights->GetDataTypeAsString() +
      " component(s) of " + std::to_string(weights->GetNumberOfTuples()) + " tuples for " +
      std::to_string(points) + " points";
  }
  else
  {
    problem = WithPointWeights(weights,
      [points](const auto* values)
      { return PointWeightProblem(values, static_cast<std::uint64_t>(points)); });
  }
  if (!problem.empty())
  {
    vtkErrorWithObjectMacro(self,
      "The cloud's " << vtkMCXTypes::PointWeightName() << " array cannot be used: " << problem
                     << ".");
    valid = false;
    return nullptr;
  }
  return weights;
}

} // namespace mcx
