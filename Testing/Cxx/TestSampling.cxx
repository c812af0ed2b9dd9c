// vtkMCXPointSampler: weights, world placement, Halton prefixes, determinism.
#include "mcxTestHelpers.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"

#include "vtkFieldData.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

namespace
{
vtkSmartPointer<vtkPolyData> Sample(vtkMCXDensityIndex* index, int m, int strategy,
  vtkPiecewiseFunction* tf, int precision = vtkAlgorithm::DOUBLE_PRECISION, vtkTypeUInt64 seed = 5)
{
  vtkNew<vtkMCXPointSampler> sampler;
  sampler->SetInputConnection(index->GetOutputPort());
  sampler->SetSampleExponent(m);
  sampler->SetStrategy(strategy);
  sampler->SetDeposit(vtkMCXTypes::POINT); // the paper's samples: positions with kernel offsets
  sampler->SetTransferFunction(tf);
  sampler->SetOutputPointsPrecision(precision);
  sampler->SetSeed(seed);
  sampler->Update();
  return sampler->GetOutput();
}
}

TEST(PointSampler, WeightIsTheIntegralOverM)
{
  const int dims[3] = { 6, 5, 4 };
  const double spacing[3] = { 0.5, 2.0, 3.0 };
  auto volume = mcxtest::MakeVolume(
    VTK_UNSIGNED_CHAR, dims, [](int i, int j, int k) { return (i + j + k) % 4; }, spacing);
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  vtkNew<vtkPiecewiseFunction> tf; // 0 -> 0, 3 -> 6, linear: g = 2 f
  tf->AddPoint(0, 0);
  tf->AddPoint(3, 6);
  auto cloud = Sample(index, 10, vtkMCXTypes::HYBRID, tf);
  double sum = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
        sum += 2.0 * ((i + j + k) % 4);
  const double integral = sum * spacing[0] * spacing[1] * spacing[2];
  EXPECT_DOUBLE_EQ(integral, mcxtest::FieldValue(cloud, "Integral"));
  EXPECT_DOUBLE_EQ(integral / 1023, mcxtest::FieldValue(cloud, "SampleWeight"));
  EXPECT_EQ(1023, cloud->GetNumberOfPoints());
  // The cloud carries its own fields, not the index's (SortedVoxelIds alone
  // is 4 bytes per voxel): exactly these.
  vtkFieldData* fd = cloud->GetFieldData();
  std::set<std::string> names;
  for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
  {
    names.insert(fd->GetArrayName(a));
  }
  const std::set<std::string> expected = { "SampleWeight", "Integral", "SampleExponent", "Deposit",
    "Kernel", "Strategy", "Seed", "VoxelAxes", "SupportCorners" };
  EXPECT_EQ(expected, names);
}

TEST(PointSampler, PointsLieInTheKernelSupportOfTheirVoxelInWorldSpace)
{
  // One non-zero voxel, rotated and offset grid: every point must be within
  // one spacing (tent) of that voxel's world position along each grid axis,
  // and their mean must be the voxel position within 5 standard errors.
  const int dims[3] = { 5, 4, 3 };
  const double spacing[3] = { 1e-6, 2e-6, 3e-6 };
  const double origin[3] = { 10.0, -20.0, 5.0 };
  auto volume = mcxtest::MakeVolume(
    VTK_FLOAT, dims, [](int i, int j, int k) { return i == 3 && j == 1 && k == 2 ? 7.0 : 0.0; },
    spacing, origin);
  volume->SetExtent(2, 6, -1, 2, 10, 12);
  const double c = std::cos(0.3), s = std::sin(0.3);
  volume->SetDirectionMatrix(c, -s, 0, s, c, 0, 0, 0, 1);
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  auto cloud = Sample(index, 14, vtkMCXTypes::HYBRID, nullptr);
  double voxel[3];
  volume->TransformIndexToPhysicalPoint(5, 0, 12, voxel); // extent start + (3, 1, 2)
  const double axes[3][3] = { { c, s, 0 }, { -s, c, 0 }, { 0, 0, 1 } };
  double mean[3] = { 0, 0, 0 };
  const vtkIdType n = cloud->GetNumberOfPoints();
  for (vtkIdType i = 0; i < n; ++i)
  {
    double x[3];
    cloud->GetPoint(i, x);
    for (int a = 0; a < 3; ++a)
    {
      const double along = ((x[0] - voxel[0]) * axes[a][0] + (x[1] - voxel[1]) * axes[a][1] +
                             (x[2] - voxel[2]) * axes[a][2]) /
        spacing[a];
      ASSERT_LT(std::fabs(along), 1.0 + 1e-6);
      mean[a] += along / n;
    }
  }
  // Tent offsets have variance 1/6 voxel^2 per axis.
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_LT(std::fabs(mean[a]), 5.0 * std::sqrt(1.0 / 6.0 / n));
  }
  EXPECT_NEAR(
    7.0 * spacing[0] * spacing[1] * spacing[2], mcxtest::FieldValue(cloud, "Integral"), 1e-30);
}

TEST(PointSampler, HaltonPrefixIsExactlyTheSmallerRun)
{
  const int dims[3] = { 16, 12, 9 };
  auto volume = mcxtest::MakeVolume(
    VTK_SHORT, dims, [&](int i, int j, int k) { return mcxtest::Phantom(i, j, k, dims); });
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  for (int strategy : { vtkMCXTypes::HYBRID, vtkMCXTypes::QUASI_MONTE_CARLO,
         vtkMCXTypes::MONTE_CARLO })
  {
    auto big = Sample(index, 16, strategy, nullptr);
    auto small = Sample(index, 9, strategy, nullptr);
    ASSERT_EQ(511, small->GetNumberOfPoints());
    for (vtkIdType i = 0; i < small->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3];
      big->GetPoint(i, a);
      small->GetPoint(i, b);
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_EQ(a[c], b[c]) << "strategy " << strategy << " point " << i;
      }
    }
  }
}

TEST(PointSampler, SameSeedSamePointsForOneAndTwoThreads)
{
  const int dims[3] = { 40, 30, 20 };
  auto volume = mcxtest::MakeVolume(
    VTK_SHORT, dims, [&](int i, int j, int k) { return mcxtest::Phantom(i, j, k, dims); });
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  for (int strategy : { vtkMCXTypes::HYBRID, vtkMCXTypes::MONTE_CARLO,
         vtkMCXTypes::QUASI_MONTE_CARLO })
  {
    vtkSmartPointer<vtkPolyData> one, two, otherSeed;
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ 1 },
      [&]() { one = Sample(index, 20, strategy, nullptr, vtkAlgorithm::SINGLE_PRECISION); });
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ 2 },
      [&]() { two = Sample(index, 20, strategy, nullptr, vtkAlgorithm::SINGLE_PRECISION); });
    otherSeed = Sample(index, 20, strategy, nullptr, vtkAlgorithm::SINGLE_PRECISION, 6);
    const float* a = static_cast<const float*>(one->GetPoints()->GetVoidPointer(0));
    const float* b = static_cast<const float*>(two->GetPoints()->GetVoidPointer(0));
    const float* c = static_cast<const float*>(otherSeed->GetPoints()->GetVoidPointer(0));
    const std::size_t n = 3 * static_cast<std::size_t>(one->GetNumberOfPoints());
    EXPECT_TRUE(std::equal(a, a + n, b));
    EXPECT_FALSE(std::equal(a, a + n, c));
  }
}

TEST(PointSampler, ZeroTransferFunctionGivesNoPoints)
{
  const int dims[3] = { 4, 4, 4 };
  auto volume = mcxtest::MakeVolume(VTK_UNSIGNED_CHAR, dims, [](int, int, int) { return 9; });
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  vtkNew<vtkPiecewiseFunction> zero;
  zero->AddPoint(0, 0);
  zero->AddPoint(255, 0);
  auto cloud = Sample(index, 10, vtkMCXTypes::HYBRID, zero);
  EXPECT_EQ(0, cloud->GetNumberOfPoints());
  EXPECT_EQ(0.0, mcxtest::FieldValue(cloud, "Integral"));
}

TEST(PointSampler, ATFEditNeverChangesPointsSomeoneStillHolds)
{
  const int dims[3] = { 8, 8, 8 };
  auto volume = mcxtest::MakeVolume(
    VTK_SHORT, dims, [&](int i, int j, int k) { return mcxtest::Phantom(i, j, k, dims); });
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(0, 0);
  tf->AddPoint(400, 1);
  vtkNew<vtkMCXPointSampler> sampler;
  sampler->SetInputConnection(index->GetOutputPort());
  sampler->SetTransferFunction(tf);
  sampler->SetSampleExponent(12);
  sampler->Update();
  vtkSmartPointer<vtkPoints> held = sampler->GetOutput()->GetPoints();
  double before[3];
  held->GetPoint(100, before);
  tf->AddPoint(50, 1); // re-sample: the held points must stay as they were
  sampler->Update();
  double after[3];
  held->GetPoint(100, after);
  EXPECT_NE(held.Get(), sampler->GetOutput()->GetPoints());
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_EQ(before[a], after[a]);
  }
  // Once let go, the next cloud holds the new samples (refilling in place, with
  // ReusePoints on, is Pipeline.ReusePointsRefillsOnlyACloudThatNothingElseHolds).
  vtkPoints* current = sampler->GetOutput()->GetPoints();
  held = nullptr;
  double expected[3];
  current->GetPoint(100, expected);
  tf->AddPoint(60, 0.5);
  sampler->Update();
  vtkNew<vtkMCXPointSampler> fresh;
  fresh->SetInputConnection(index->GetOutputPort());
  fresh->SetTransferFunction(tf);
  fresh->SetSampleExponent(12);
  fresh->Update();
  for (vtkIdType i = 0; i < fresh->GetOutput()->GetNumberOfPoints(); ++i)
  {
    double a[3], b[3];
    fresh->GetOutput()->GetPoint(i, a);
    sampler->GetOutput()->GetPoint(i, b);
    ASSERT_EQ(a[0], b[0]);
    ASSERT_EQ(a[1], b[1]);
    ASSERT_EQ(a[2], b[2]);
  }
}
