// Pipeline economy: a TF change re-executes the sampler, not the index; a
// view change re-executes only the projection.
#include "mcxTestHelpers.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

TEST(Pipeline, EachChangeReExecutesOnlyWhatItAffects)
{
  const int dims[3] = { 12, 10, 8 };
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
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 100);
  camera->SetFocalPoint(6, 5, 4);
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(sampler->GetOutputPort());
  projector->SetCamera(camera);
  projector->SetImageSize(32, 32);

  mcxtest::ExecutionCounter indexRuns(index), samplerRuns(sampler), projectorRuns(projector);
  projector->Update();
  EXPECT_EQ(1, indexRuns.Count);
  EXPECT_EQ(1, samplerRuns.Count);
  EXPECT_EQ(1, projectorRuns.Count);

  projector->Update(); // nothing changed
  EXPECT_EQ(1, projectorRuns.Count);

  tf->AddPoint(200, 0.2); // TF edit: resample and reproject, never re-index
  projector->Update();
  EXPECT_EQ(1, indexRuns.Count);
  EXPECT_EQ(2, samplerRuns.Count);
  EXPECT_EQ(2, projectorRuns.Count);

  camera->Azimuth(30); // view change: reproject only
  projector->Update();
  EXPECT_EQ(1, indexRuns.Count);
  EXPECT_EQ(2, samplerRuns.Count);
  EXPECT_EQ(3, projectorRuns.Count);

  // Off-line projection from the index: a TF edit re-executes the projector only.
  vtkNew<vtkMCXProjector> offline;
  offline->SetInputConnection(index->GetOutputPort());
  offline->SetTransferFunction(tf);
  offline->SetSampleExponent(12);
  mcxtest::ExecutionCounter offlineRuns(offline);
  offline->Update();
  tf->AddPoint(300, 0.5);
  offline->Update();
  EXPECT_EQ(2, offlineRuns.Count);
  EXPECT_EQ(1, indexRuns.Count);
}

namespace
{
std::vector<double> Values(vtkDataArray* array)
{
  std::vector<double> values(static_cast<std::size_t>(array->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    values[static_cast<std::size_t>(i)] = array->GetTuple1(i);
  }
  return values;
}

std::vector<double> Coordinates(vtkPoints* points)
{
  std::vector<double> values(3 * static_cast<std::size_t>(points->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    points->GetPoint(i, values.data() + 3 * i);
  }
  return values;
}
}

TEST(Pipeline, ReusePointsRefillsOnlyACloudThatNothingElseHolds)
{
  const int dims[3] = { 12, 10, 8 };
  auto volume = mcxtest::MakeVolume(
    VTK_SHORT, dims, [&](int i, int j, int k) { return mcxtest::Phantom(i, j, k, dims); });
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(0, 0);
  tf->AddPoint(400, 1);
  auto makeSampler = [&](bool reuse)
  {
    vtkSmartPointer<vtkMCXPointSampler> sampler = vtkSmartPointer<vtkMCXPointSampler>::New();
    sampler->SetInputConnection(index->GetOutputPort());
    sampler->SetTransferFunction(tf);
    sampler->SetSampleExponent(10);
    sampler->SetReusePoints(reuse);
    return sampler;
  };
  auto reusing = makeSampler(true);
  auto fresh = makeSampler(false); // the reference: new points every time
  reusing->Update();

  // Nothing else holds the cloud: a TF edit refills the same points, and
  // they are the cloud a sampler without reuse makes.
  vtkWeakPointer<vtkPoints> first = reusing->GetOutput()->GetPoints();
  const void* memory = first->GetVoidPointer(0);
  tf->AddPoint(200, 0.2);
  reusing->Update();
  fresh->Update();
  ASSERT_TRUE(first);
  EXPECT_EQ(first.Get(), reusing->GetOutput()->GetPoints());
  EXPECT_EQ(memory, reusing->GetOutput()->GetPoints()->GetVoidPointer(0));
  EXPECT_EQ(
    Coordinates(fresh->GetOutput()->GetPoints()), Coordinates(reusing->GetOutput()->GetPoints()));

  // Points held elsewhere, or their array alone, are never rewritten.
  vtkSmartPointer<vtkPoints> held = reusing->GetOutput()->GetPoints();
  const std::vector<double> heldValues = Coordinates(held);
  tf->AddPoint(200, 0.6);
  reusing->Update();
  EXPECT_NE(held.Get(), reusing->GetOutput()->GetPoints());
  EXPECT_EQ(heldValues, Coordinates(held));
  vtkSmartPointer<vtkDataArray> heldArray = reusing->GetOutput()->GetPoints()->GetData();
  const std::vector<double> arrayValues = Coordinates(reusing->GetOutput()->GetPoints());
  tf->AddPoint(200, 0.1);
  reusing->Update();
  EXPECT_NE(heldArray.Get(), reusing->GetOutput()->GetPoints()->GetData());
  vtkNew<vtkPoints> view;
  view->SetData(heldArray);
  EXPECT_EQ(arrayValues, Coordinates(view));
  fresh->Update();
  EXPECT_EQ(
    Coordinates(fresh->GetOutput()->GetPoints()), Coordinates(reusing->GetOutput()->GetPoints()));

  // Without reuse the sampler keeps no old cloud alive, nor after reuse is turned off.
  vtkWeakPointer<vtkPoints> old = fresh->GetOutput()->GetPoints();
  vtkWeakPointer<vtkPoints> kept = reusing->GetOutput()->GetPoints();
  reusing->ReusePointsOff();
  tf->AddPoint(300, 0.5);
  fresh->Update();
  reusing->Update();
  EXPECT_FALSE(old);
  EXPECT_FALSE(kept);
}

namespace
{
// Checks an every-voxel cloud of `volume` under `tf`: each voxel of
// non-zero weight once, at its centre, with the weight TF / mean TF.
void ExpectEveryVoxelOnce(vtkPolyData* cloud, vtkImageData* volume, vtkPiecewiseFunction* tf)
{
  vtkDataArray* values = volume->GetPointData()->GetScalars();
  double total = 0;
  vtkIdType count = 0;
  for (vtkIdType v = 0; v < volume->GetNumberOfPoints(); ++v)
  {
    const double w = std::max(0.0, tf->GetValue(values->GetTuple1(v)));
    total += w;
    count += w > 0 ? 1 : 0;
  }
  ASSERT_EQ(count, cloud->GetNumberOfPoints());
  vtkDataArray* weights = cloud->GetPointData()->GetArray(vtkMCXTypes::PointWeightName());
  ASSERT_NE(nullptr, weights);
  ASSERT_EQ(count, weights->GetNumberOfTuples());
  std::vector<int> seen(static_cast<std::size_t>(volume->GetNumberOfPoints()), 0);
  double sum = 0;
  for (vtkIdType k = 0; k < count; ++k)
  {
    const vtkIdType v = volume->FindPoint(cloud->GetPoint(k));
    ASSERT_GE(v, 0);
    ++seen[static_cast<std::size_t>(v)];
    double centre[3];
    volume->GetPoint(v, centre);
    for (int a = 0; a < 3; ++a)
    {
      ASSERT_NEAR(centre[a], cloud->GetPoint(k)[a], 1e-4) << "point " << k;
    }
    const double expected = tf->GetValue(values->GetTuple1(v)) * count / total;
    ASSERT_NEAR(expected, weights->GetTuple1(k), 1e-6 * expected) << "point " << k;
    sum += weights->GetTuple1(k);
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n <= 1; }));
  EXPECT_NEAR(static_cast<double>(count), sum, 1e-5 * count);
  EXPECT_EQ(nullptr, cloud->GetFieldData()->GetArray("SampleExponent"));
  EXPECT_DOUBLE_EQ(
    mcxtest::FieldValue(cloud, "Integral") / count, mcxtest::FieldValue(cloud, "SampleWeight"));
}
}

TEST(Pipeline, EveryVoxelTFEditsKeepTheVoxelsAndRewriteTheWeights)
{
  // EVERY_VOXEL: a TF edit that keeps the same voxels keeps the points
  // (ReusePoints) and writes new weights; one that zeroes some voxels makes
  // a cloud of the others; the cloud is the same for one thread and two;
  // without reuse no old cloud is kept.
  const int dims[3] = { 12, 10, 8 };
  auto volume = mcxtest::MakeVolume(
    VTK_SHORT, dims, [&](int i, int j, int k) { return mcxtest::Phantom(i, j, k, dims); });
  const double spacing[3] = { 0.7, 1.1, 2.0 };
  volume->SetSpacing(spacing);
  volume->SetOrigin(-3, 4, 10);
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(0, 0);
  tf->AddPoint(400, 1);
  vtkNew<vtkMCXPointSampler> sampler;
  sampler->SetInputConnection(index->GetOutputPort());
  sampler->SetTransferFunction(tf);
  sampler->SetStrategyToEveryVoxel();
  sampler->SetDepositToFootprint();
  sampler->ReusePointsOn();
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ 1 }, [&]() { sampler->Update(); });
  vtkPolyData* cloud = sampler->GetOutput();
  ExpectEveryVoxelOnce(cloud, volume, tf);
  ASSERT_GT(cloud->GetNumberOfPoints(), 100);
  const std::vector<double> oneThread = Coordinates(cloud->GetPoints());
  const std::vector<double> oneThreadWeights =
    Values(cloud->GetPointData()->GetArray("PointWeight"));
  vtkNew<vtkMCXPointSampler> twoThreads; // a sampler of its own: nothing kept to reuse
  twoThreads->SetInputConnection(index->GetOutputPort());
  twoThreads->SetTransferFunction(tf);
  twoThreads->SetStrategyToEveryVoxel();
  twoThreads->SetDepositToFootprint();
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ 2 }, [&]() { twoThreads->Update(); });
  EXPECT_NE(cloud->GetPoints(), twoThreads->GetOutput()->GetPoints());
  EXPECT_EQ(oneThread, Coordinates(twoThreads->GetOutput()->GetPoints()));
  EXPECT_EQ(
    oneThreadWeights, Values(twoThreads->GetOutput()->GetPointData()->GetArray("PointWeight")));

  vtkWeakPointer<vtkPoints> first = cloud->GetPoints();
  tf->AddPoint(200, 0.9);
  sampler->Update();
  EXPECT_EQ(first.Get(), sampler->GetOutput()->GetPoints());
  ExpectEveryVoxelOnce(sampler->GetOutput(), volume, tf);

  tf->AddPoint(150, 0);
  tf->AddPoint(0, 0);
  sampler->Update();
  EXPECT_NE(first.Get(), sampler->GetOutput()->GetPoints());
  ExpectEveryVoxelOnce(sampler->GetOutput(), volume, tf);
  EXPECT_LT(
    sampler->GetOutput()->GetNumberOfPoints(), static_cast<vtkIdType>(oneThread.size() / 3));

  vtkWeakPointer<vtkPoints> kept = sampler->GetOutput()->GetPoints();
  sampler->ReusePointsOff();
  tf->AddPoint(200, 0.5);
  sampler->Update();
  EXPECT_FALSE(kept);
  ExpectEveryVoxelOnce(sampler->GetOutput(), volume, tf);
}

TEST(Pipeline, TheIndexTravelsThroughAVTKFile)
{
  // The index is plain VTK data: written as .vti and read back, it gives the
  // same image bit for bit.
  const int dims[3] = { 12, 10, 8 };
  auto volume = mcxtest::MakeVolume(
    VTK_SHORT, dims, [&](int i, int j, int k) { return mcxtest::Phantom(i, j, k, dims); });
  volume->SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1);
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  const std::string path =
    vtksys::SystemTools::GetCurrentWorkingDirectory() + "/pipeline_index.vti";
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputConnection(index->GetOutputPort());
  writer->SetFileName(path.c_str());
  ASSERT_EQ(1, writer->Write());
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(path.c_str());
  vtkSmartPointer<vtkImageData> images[2];
  vtkAlgorithm* sources[2] = { index, reader };
  for (int n = 0; n < 2; ++n)
  {
    vtkNew<vtkMCXProjector> projector;
    projector->SetInputConnection(sources[n]->GetOutputPort());
    projector->SetSampleExponent(14);
    projector->SetDetectorAxisU(0, 1, 0);
    projector->SetDetectorAxisV(0, 0, 1);
    projector->Update();
    images[n] = projector->GetOutput();
  }
  vtkDataArray* a = mcxtest::LineIntegral(images[0]);
  vtkDataArray* b = mcxtest::LineIntegral(images[1]);
  ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples());
  EXPECT_GT(a->GetRange()[1], 0.0);
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    ASSERT_EQ(a->GetTuple1(i), b->GetTuple1(i));
  }
}

TEST(Pipeline, AFailedRequestLeavesNoStaleOutput)
{
  // After a good run, a request that fails (an invalid view, a NaN TF, an
  // input the index cannot take) leaves an empty output, never the image,
  // cloud or index of the earlier request; the next good request works.
  vtkObject::GlobalWarningDisplayOff(); // the errors are expected
  const int dims[3] = { 8, 8, 8 };
  auto volume = mcxtest::MakeVolume(VTK_UNSIGNED_CHAR, dims, [](int i, int, int) { return i; });
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(0, 0);
  tf->AddPoint(7, 1);
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(index->GetOutputPort());
  projector->SetTransferFunction(tf);
  projector->SetSampleExponent(10);
  projector->Update();
  ASSERT_GT(projector->GetOutput()->GetNumberOfPoints(), 0);
  projector->SetDetectorAxisV(1, 0, 0); // along U: no view
  projector->Update();
  EXPECT_EQ(0, projector->GetOutput()->GetNumberOfPoints());
  projector->SetDetectorAxisV(0, 1, 0);
  projector->Update();
  EXPECT_GT(projector->GetOutput()->GetNumberOfPoints(), 0);

  vtkNew<vtkMCXPointSampler> sampler;
  sampler->SetInputConnection(index->GetOutputPort());
  sampler->SetTransferFunction(tf);
  sampler->SetSampleExponent(10);
  sampler->Update();
  ASSERT_EQ(1023, sampler->GetOutput()->GetNumberOfPoints());
  tf->AddPoint(3, std::nan(""));
  sampler->Update();
  EXPECT_EQ(0, sampler->GetOutput()->GetNumberOfPoints());
  tf->RemovePoint(3);

  index->Update();
  ASSERT_GT(index->GetOutput()->GetNumberOfPoints(), 0);
  auto vectors = mcxtest::MakeVolume(VTK_UNSIGNED_CHAR, dims, [](int i, int, int) { return i; });
  vectors->GetPointData()->GetScalars()->SetNumberOfComponents(2);
  vectors->GetPointData()->GetScalars()->SetNumberOfTuples(256);
  index->SetInputData(vectors);
  index->Update();
  EXPECT_EQ(0, index->GetOutput()->GetNumberOfPoints());
  vtkObject::GlobalWarningDisplayOn();
}
