#include "vtkMCXSampledCloudPrivate.h"

#include "mcxProjectionGeometry.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXPointSampler.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"

#include <algorithm>

namespace mcx
{
void WriteCloudFields(vtkMCXPointSampler* self, const mcx::IndexView& view, double integral,
  vtkIdType count, int exponent, vtkFieldData* fd)
{
  fd->Initialize();
  mcx::AddFieldValue(
    fd, vtkMCXTypes::SampleWeightName(), count > 0 ? integral / static_cast<double>(count) : 0.0);
  mcx::AddFieldValue(fd, vtkMCXTypes::IntegralName(), integral);
  if (exponent >= 0)
  {
    mcx::AddFieldValue(fd, vtkMCXTypes::SampleExponentName(), static_cast<long long>(exponent));
  }
  mcx::AddFieldValue(fd, vtkMCXTypes::DepositName(), static_cast<long long>(self->GetDeposit()));
  mcx::AddFieldValue(fd, vtkMCXTypes::KernelName(), static_cast<long long>(self->GetKernel()));
  mcx::AddFieldValue(fd, vtkMCXTypes::StrategyName(), static_cast<long long>(self->GetStrategy()));
  mcx::AddFieldValue(fd, vtkMCXTypes::SeedName(), static_cast<long long>(self->GetSeed()));
  double origin[3], axes[9];
  view.SourceToWorld(origin, axes);
  vtkNew<vtkDoubleArray> voxelAxes;
  voxelAxes->SetName(vtkMCXTypes::VoxelAxesName());
  voxelAxes->SetNumberOfValues(9);
  std::copy(axes, axes + 9, voxelAxes->GetPointer(0));
  fd->AddArray(voxelAxes);
  double corners[24];
  mcx::ComputeSupportCorners(view.Extent, view.Origin, view.Spacing, view.Direction,
    mcx::KernelRadius(static_cast<mcx::Kernel>(self->GetKernel())), corners);
  vtkNew<vtkDoubleArray> support;
  support->SetName(vtkMCXTypes::SupportCornersName());
  support->SetNumberOfValues(24);
  std::copy(corners, corners + 24, support->GetPointer(0));
  fd->AddArray(support);
}
}
