// vtkMCXDensityIndex: exact levels for every scalar type, float binning,
// non-finite voxels, and thread-count independence.
#include "mcxTestHelpers.h"
#include "vtkMCXDensityIndex.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkSMPTools.h"
#include "vtkTypeInt64Array.h"
#include "vtkTypeUInt32Array.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <vector>

namespace
{
vtkSmartPointer<vtkImageData> Index(vtkImageData* volume, int floatLevels = 4096)
{
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  index->SetNumberOfFloatLevels(floatLevels);
  index->Update();
  return index->GetOutput();
}

vtkDataArray* Field(vtkImageData* index, const char* name)
{
  return index->GetFieldData()->GetArray(name);
}

// The index must equal a brute-force grouping of ids by exact value.
void ExpectExactIndex(vtkImageData* volume)
{
  vtkSmartPointer<vtkImageData> index = Index(volume);
  std::map<double, std::vector<vtkIdType>> expected;
  vtkDataArray* scalars = volume->GetPointData()->GetScalars();
  for (vtkIdType id = 0; id < scalars->GetNumberOfTuples(); ++id)
  {
    expected[scalars->GetTuple1(id)].push_back(id);
  }
  vtkDataArray* values = Field(index, vtkMCXTypes::LevelValuesName());
  vtkDataArray* offsets = Field(index, vtkMCXTypes::LevelOffsetsName());
  vtkDataArray* ids = Field(index, vtkMCXTypes::SortedVoxelIdsName());
  ASSERT_NE(nullptr, values);
  ASSERT_EQ(static_cast<vtkIdType>(expected.size()), values->GetNumberOfTuples());
  ASSERT_TRUE(vtkTypeUInt32Array::SafeDownCast(ids) != nullptr);
  vtkIdType level = 0;
  for (const auto& entry : expected)
  {
    EXPECT_EQ(entry.first, values->GetTuple1(level));
    const auto begin = static_cast<vtkIdType>(offsets->GetTuple1(level));
    const auto end = static_cast<vtkIdType>(offsets->GetTuple1(level + 1));
    ASSERT_EQ(static_cast<vtkIdType>(entry.second.size()), end - begin);
    for (vtkIdType i = begin; i < end; ++i)
    {
      EXPECT_EQ(entry.second[i - begin], static_cast<vtkIdType>(ids->GetTuple1(i)));
    }
    ++level;
  }
  EXPECT_EQ(0, Field(index, vtkMCXTypes::NonFiniteVoxelCountName())->GetTuple1(0));
  // Geometry travels unchanged.
  int extent[6], expectedExtent[6];
  index->GetExtent(extent);
  volume->GetExtent(expectedExtent);
  for (int a = 0; a < 6; ++a)
  {
    EXPECT_EQ(expectedExtent[a], extent[a]);
  }
  EXPECT_EQ(0, index->GetPointData()->GetNumberOfArrays());
}
}

class EveryScalarType : public ::testing::TestWithParam<int>
{
};

TEST_P(EveryScalarType, IntegerValuesGetOneExactLevelEach)
{
  const int type = GetParam();
  const int dims[3] = { 7, 5, 3 };
  const bool isSigned = type != VTK_UNSIGNED_CHAR && type != VTK_UNSIGNED_SHORT &&
    type != VTK_UNSIGNED_INT && type != VTK_UNSIGNED_LONG && type != VTK_UNSIGNED_LONG_LONG;
  auto volume = mcxtest::MakeVolume(type, dims,
    [&](int i, int j, int k)
    {
      const int v = (i * 13 + j * 7 + k * 3) % 17;
      return isSigned ? v - 8.0 : static_cast<double>(v);
    });
  ExpectExactIndex(volume);
}

INSTANTIATE_TEST_SUITE_P(DensityIndex, EveryScalarType,
  ::testing::Values(VTK_CHAR, VTK_SIGNED_CHAR, VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_UNSIGNED_SHORT,
    VTK_INT, VTK_UNSIGNED_INT, VTK_LONG, VTK_UNSIGNED_LONG, VTK_LONG_LONG, VTK_UNSIGNED_LONG_LONG,
    VTK_ID_TYPE, VTK_FLOAT, VTK_DOUBLE));

TEST(DensityIndex, WideIntegerRangeUsesDistinctValues)
{
  // int32 values at the limits of the type: the range is too wide to bin directly.
  const int dims[3] = { 4, 3, 2 };
  const double values[] = { std::numeric_limits<int>::min(), -1, 0, 5,
    std::numeric_limits<int>::max() };
  auto volume = mcxtest::MakeVolume(
    VTK_INT, dims, [&](int i, int j, int k) { return values[(i + j + k) % 5]; });
  ExpectExactIndex(volume);
}

TEST(DensityIndex, FloatDataIsBinnedAndNonFiniteVoxelsAreCounted)
{
  const int dims[3] = { 10, 1, 1 };
  const double data[] = { 0.0, 1.0, NAN, 2.5, INFINITY, 10.0, -INFINITY, 9.99, 5.0, 0.001 };
  auto volume = mcxtest::MakeVolume(VTK_FLOAT, dims, [&](int i, int, int) { return data[i]; });
  vtkSmartPointer<vtkImageData> index = Index(volume, 4);
  // Range 0..10, 4 bins of width 2.5: {0, 1, 0.001}, {2.5}, {5}, {10, 9.99};
  // each level is the mean of its values.
  vtkDataArray* levels = Field(index, vtkMCXTypes::LevelValuesName());
  vtkDataArray* offsets = Field(index, vtkMCXTypes::LevelOffsetsName());
  ASSERT_EQ(4, levels->GetNumberOfTuples());
  const double means[] = { (0.0 + 1.0 + 0.001f) / 3, 2.5, 5.0, (10.0 + 9.99f) / 2 };
  const double counts[] = { 3, 1, 1, 2 };
  for (int l = 0; l < 4; ++l)
  {
    EXPECT_NEAR(means[l], levels->GetTuple1(l), 1e-14);
    EXPECT_EQ(counts[l], offsets->GetTuple1(l + 1) - offsets->GetTuple1(l));
  }
  EXPECT_EQ(3, Field(index, vtkMCXTypes::NonFiniteVoxelCountName())->GetTuple1(0));
  EXPECT_DOUBLE_EQ(2.5, Field(index, vtkMCXTypes::LevelBinWidthName())->GetTuple1(0));
}

TEST(DensityIndex, IdenticalForOneAndTwoThreads)
{
  const int dims[3] = { 97, 61, 43 };
  auto volume = mcxtest::MakeVolume(VTK_SHORT, dims,
    [&](int i, int j, int k) { return mcxtest::Phantom(i, j, k, dims) * 10 - 1000; });
  vtkSmartPointer<vtkImageData> one, two;
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ 1 }, [&]() { one = Index(volume); });
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ 2 }, [&]() { two = Index(volume); });
  for (const char* name : { vtkMCXTypes::LevelValuesName(),
         vtkMCXTypes::LevelOffsetsName(), vtkMCXTypes::SortedVoxelIdsName() })
  {
    vtkDataArray* a = Field(one, name);
    vtkDataArray* b = Field(two, name);
    ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples());
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      ASSERT_EQ(a->GetTuple1(i), b->GetTuple1(i)) << name << " " << i;
    }
  }
}

TEST(DensityIndex, RejectsMultiComponentScalars)
{
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(2, 2, 2);
  volume->AllocateScalars(VTK_FLOAT, 3);
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  index->Update(); // reports an error, produces no index
  EXPECT_EQ(
    nullptr, index->GetOutput()->GetFieldData()->GetArray(vtkMCXTypes::LevelValuesName()));
}
