// Interactive rendering with vtkMCXXRayMapper (run under an X display:
// Testing/with-display): frames per second for a camera change with 1 M,
// 4 M and 16 M points at 256^2 and 512^2 (each frame projects every point),
// and the latency from a TF edit to the complete image of 4 M points (and
// of 256 K and 1 M footprint points); camera changes with 256 K and 1 M
// footprint points (each frame builds new footprint tables). The
// paper (one 2 GHz core, 256^2): 21.28, 5.32 and 1.39 fps; 2.28 s per TF edit.
#include "mcxHeadScene.h"

#include "vtkCamera.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <benchmark/benchmark.h>

namespace
{
// The head scene with every frame showing all points, framed by ResetCamera.
struct Scene : mcxtest::HeadScene
{
  Scene(int exponent, int size, bool perspective)
    : HeadScene(exponent, size, size)
  {
    this->Mapper->ProgressiveRefinementOff();
    this->Renderer->GetActiveCamera()->SetParallelProjection(!perspective);
    this->Renderer->ResetCamera();
    this->Window->Render();
  }
};

// Arguments: sample exponent, image size, perspective (0/1).
void CameraChange(benchmark::State& state)
{
  Scene scene(
    static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), state.range(2) != 0);
  for (auto _ : state)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(1);
    scene.Window->Render();
  }
  const double points = static_cast<double>(scene.Mapper->GetNumberOfAccumulatedSamples());
  state.counters["fps"] =
    benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points));
  state.SetLabel("points");
}

// A TF edit: the sampler regenerates 4 M points, the mapper projects them all.
void TransferFunctionEdit(benchmark::State& state)
{
  Scene scene(22, static_cast<int>(state.range(0)), true);
  double level = 0.0;
  for (auto _ : state)
  {
    level = level == 0.0 ? 0.1 : 0.0;
    scene.TransferFunction->AddPoint(1500, level); // replaces the point at 1500
    scene.Window->Render();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * ((1 << 22) - 1)));
  state.SetLabel("points");
}

// The same edit with the footprint deposit (a cloud of voxel centres):
// arguments sample exponent and image size. 2^20 - 1 footprint points give
// about 1-2 % at 256^2 (the accuracy report), where the point deposit needs
// 2^26 - 1.
void FootprintTransferFunctionEdit(benchmark::State& state)
{
  Scene scene(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), true);
  scene.Sampler->SetDepositToFootprint();
  scene.Window->Render();
  double level = 0.0;
  for (auto _ : state)
  {
    level = level == 0.0 ? 0.1 : 0.0;
    scene.TransferFunction->AddPoint(1500, level); // replaces the point at 1500
    scene.Window->Render();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * ((1 << state.range(0)) - 1)));
  state.SetLabel("points");
}

// A camera change with the footprint deposit: every frame takes a new
// footprint table (a ladder of them in perspective), seen obliquely (20
// degrees of elevation), and projects every point. Arguments: sample
// exponent, image size, perspective (0/1).
void FootprintCameraChange(benchmark::State& state)
{
  Scene scene(
    static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), state.range(2) != 0);
  scene.Sampler->SetDepositToFootprint();
  scene.Renderer->GetActiveCamera()->Elevation(20);
  scene.Window->Render();
  for (auto _ : state)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(1);
    scene.Window->Render();
  }
  const double points = static_cast<double>(scene.Mapper->GetNumberOfAccumulatedSamples());
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * points));
  state.SetLabel("points");
}
}

BENCHMARK(CameraChange)
  ->ArgsProduct({ { 20, 22, 24 }, { 256, 512 }, { 0, 1 } })
  ->Unit(benchmark::kMillisecond)
  ->UseRealTime();
BENCHMARK(TransferFunctionEdit)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(FootprintTransferFunctionEdit)
  ->ArgsProduct({ { 18, 20 }, { 256 } })
  ->Unit(benchmark::kMillisecond)
  ->UseRealTime();

BENCHMARK(FootprintCameraChange)
  ->ArgsProduct({ { 18, 20 }, { 256 }, { 0, 1 } })
  ->Unit(benchmark::kMillisecond)
  ->UseRealTime();

BENCHMARK_MAIN();
