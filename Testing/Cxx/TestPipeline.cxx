// Pipeline economy: a TF change re-executes the sampler, not the index; a
// view change re-executes only the projection.
#include "mcxTestHelpers.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"

#include <gtest/gtest.h>

namespace
{
struct ExecutionCounter
{
  int Count = 0;
  vtkNew<vtkCallbackCommand> Command;

  explicit ExecutionCounter(vtkAlgorithm* algorithm)
  {
    this->Command->SetClientData(&this->Count);
    this->Command->SetCallback([](vtkObject*, unsigned long, void* data, void*) { ++*static_cast<int*>(data); });
    algorithm->AddObserver(vtkCommand::StartEvent, this->Command);
  }
};
}

TEST(Pipeline, EachChangeReExecutesOnlyWhatItAffects)
{
  const int dims[3] = { 12, 10, 8 };
  auto volume = mcxtest::MakeVolume(VTK_SHORT, dims, [&](int i, int j, int k) { return mcxtest::Phantom(i, j, k, dims); });
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

  ExecutionCounter indexRuns(index), samplerRuns(sampler), projectorRuns(projector);
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
  ExecutionCounter offlineRuns(offline);
  offline->Update();
  tf->AddPoint(300, 0.5);
  offline->Update();
  EXPECT_EQ(2, offlineRuns.Count);
  EXPECT_EQ(1, indexRuns.Count);
}
