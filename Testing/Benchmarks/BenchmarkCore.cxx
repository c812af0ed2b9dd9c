// Throughput of the core stages on 2 cores, next to memcpy bandwidth
// measured in the same run: index (voxels/s), stored point-cloud sampling
// (points/s) and off-line sampling + projection in an oblique perspective
// view (samples/s), on the bundled CT and on a 256^3 real volume; the
// footprint table of a parallel view (tables/s).
//
// Run through Testing/Benchmarks/run-benchmarks, which reports medians.
#include "mcxFootprint.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"
#include "vtkMCXRadiograph.h"

#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkXMLImageDataReader.h"

#include <benchmark/benchmark.h>

#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace
{
struct Volume
{
  vtkSmartPointer<vtkImageData> Image;
  vtkSmartPointer<vtkMCXDensityIndex> Index;
  vtkSmartPointer<vtkPiecewiseFunction> TF;
  vtkSmartPointer<vtkCamera> Camera;
};

// Volumes by name: "bundled" (headsq, 64x64x93 int16) and "256cubed" (bonsai, 256^3 uint8).
Volume& Get(const std::string& name)
{
  static std::map<std::string, Volume> volumes;
  auto found = volumes.find(name);
  if (found != volumes.end())
  {
    return found->second;
  }
  const std::string path = name == "bundled"
    ? std::string(MCXRAY_TEST_DATA_DIR) + "/ct_head_headsq.vti"
    : std::string(MCXRAY_SHARED_DATA_DIR) + "/ct_bonsai.vti";
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  Volume v;
  v.Image = reader->GetOutput();
  v.Index = vtkSmartPointer<vtkMCXDensityIndex>::New();
  v.Index->SetInputData(v.Image);
  v.Index->Update();
  double range[2];
  v.Image->GetPointData()->GetScalars()->GetRange(range);
  v.TF = vtkSmartPointer<vtkPiecewiseFunction>::New();
  v.TF->AddPoint(range[0] + 0.2 * (range[1] - range[0]), 0.0);
  v.TF->AddPoint(range[1], 1.0);
  double bounds[6];
  v.Image->GetBounds(bounds);
  const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  const double size =
    std::max(bounds[1] - bounds[0], std::max(bounds[3] - bounds[2], bounds[5] - bounds[4]));
  v.Camera = vtkSmartPointer<vtkCamera>::New();
  v.Camera->SetFocalPoint(centre);
  v.Camera->SetPosition(centre[0] + 1.2 * size, centre[1] - 1.5 * size, centre[2] + 0.8 * size);
  v.Camera->SetViewUp(0, 0, 1);
  v.Camera->SetViewAngle(30);
  v.Camera->SetClippingRange(0.1 * size, 10 * size);
  return volumes[name] = v;
}

const char* VolumeName(int id)
{
  return id == 0 ? "bundled" : "256cubed";
}

void Index(benchmark::State& state)
{
  Volume& v = Get(VolumeName(static_cast<int>(state.range(0))));
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(v.Image);
  for (auto _ : state)
  {
    index->Modified();
    index->Update();
  }
  state.SetItemsProcessed(state.iterations() * v.Image->GetNumberOfPoints());
  state.SetLabel("voxels");
}

void StoredPointCloud(benchmark::State& state)
{
  Volume& v = Get(VolumeName(static_cast<int>(state.range(0))));
  vtkNew<vtkMCXPointSampler> sampler;
  sampler->SetInputConnection(v.Index->GetOutputPort());
  sampler->SetTransferFunction(v.TF);
  sampler->SetSampleExponent(static_cast<int>(state.range(1)));
  sampler->ReusePointsOn(); // a TF edit in an interactive pipeline: nothing keeps the old cloud
  sampler->Update();        // the first cloud, allocated: not a TF edit
  for (auto _ : state)
  {
    sampler->Modified();
    sampler->Update();
  }
  state.SetItemsProcessed(state.iterations() * sampler->GetNumberOfSamples());
  state.SetLabel("points");
}

void OfflinePerspective(benchmark::State& state)
{
  Volume& v = Get(VolumeName(static_cast<int>(state.range(0))));
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(v.Index->GetOutputPort());
  projector->SetTransferFunction(v.TF);
  projector->SetCamera(v.Camera);
  projector->SetImageSize(512, 512);
  projector->SetSampleExponent(static_cast<int>(state.range(1)));
  for (auto _ : state)
  {
    projector->Modified();
    projector->Update();
  }
  state.SetItemsProcessed(state.iterations() * projector->GetNumberOfSamples());
  state.SetLabel("samples");
}

// The cost of each radiograph effect on a 512^2 line-integral image, after
// accumulation: 0 none (a pass-through), 1 Beer-Lambert, 2 + Poisson noise of
// 10^4 photons per pixel, 3 + the negative log. For scale, the off-line
// projection of 2^24 - 1 samples into such an image takes about 150 ms.
void RadiographEffects(benchmark::State& state)
{
  const int size = 512;
  vtkNew<vtkImageData> image;
  image->SetDimensions(size, size, 1);
  vtkNew<vtkDoubleArray> values;
  values->SetName("LineIntegral");
  values->SetNumberOfValues(size * size);
  for (vtkIdType p = 0; p < size * size; ++p)
  {
    values->SetValue(
      p, 4.0 * static_cast<double>(p % size) / size); // 0 .. 4: transmissions 1 .. 0.018
  }
  image->GetPointData()->SetScalars(values);
  vtkNew<vtkMCXRadiograph> physics;
  physics->SetInputData(image);
  physics->SetBeerLambert(state.range(0) >= 1);
  physics->SetPhotonsPerPixel(state.range(0) >= 2 ? 1e4 : 0.0);
  physics->SetNegativeLog(state.range(0) >= 3);
  for (auto _ : state)
  {
    physics->Modified();
    physics->Update();
  }
  state.SetItemsProcessed(state.iterations() * size * size);
  state.SetLabel("pixels");
}

// The footprint table of a parallel view (what a camera change with a
// footprint cloud rebuilds before it deposits): a voxel about one pixel
// wide (tent), seen along an axis (0) or obliquely (1). A perspective view
// builds a ladder of such tables, coarser, in parallel.
void FootprintTable(benchmark::State& state)
{
  const double axis[3][2] = { { 0.96, 0 }, { 0, 0.96 }, { 0, 0 } };
  const double oblique[3][2] = { { 0.8, 0.3 }, { -0.2, 0.9 }, { 0.5, -0.4 } };
  const auto& axes = state.range(0) == 0 ? axis : oblique;
  const mcx::FootprintPlan plan = mcx::FootprintPlan::For(mcx::Kernel::Tent, axes, 16.0);
  for (auto _ : state)
  {
    mcx::FootprintTable table;
    table.Build(axes, plan);
    benchmark::DoNotOptimize(table.Increments(0, 0));
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel("tables");
}

void Memcpy(benchmark::State& state)
{
  const std::size_t bytes = std::size_t(1) << 28;
  std::vector<char> source(bytes, 1), target(bytes, 0);
  for (auto _ : state)
  {
    std::memcpy(target.data(), source.data(), bytes);
    benchmark::DoNotOptimize(target.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(bytes));
}
}

BENCHMARK(Memcpy)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(Index)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(StoredPointCloud)
  ->Args({ 0, 24 })
  ->Args({ 1, 24 })
  ->Unit(benchmark::kMillisecond)
  ->UseRealTime();
BENCHMARK(OfflinePerspective)
  ->Args({ 0, 24 })
  ->Args({ 1, 24 })
  ->Unit(benchmark::kMillisecond)
  ->UseRealTime();
BENCHMARK(RadiographEffects)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(FootprintTable)->DenseRange(0, 1)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
