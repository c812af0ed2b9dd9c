// The per-pixel cost of a polychromatic radiograph: 512^2 pixels, 4 material
// channels, a 101 kVp spectrum in 1 keV bins (100 bins from 1 keV), through
// vtkMCXPolychromaticRadiograph (vtkSMPTools threads), without re-sampling:
// what a spectrum or detector change costs.
#include "vtkMCXPolychromaticRadiograph.h"
#include "vtkMCXTypes.h"

#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <benchmark/benchmark.h>

#include <vector>

static void PolychromaticRemap(benchmark::State& state)
{
  constexpr int size = 512;
  std::vector<vtkSmartPointer<vtkImageData>> channels;
  for (int m = 0; m < 4; ++m)
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(size, size, 1);
    vtkNew<vtkDoubleArray> values;
    values->SetName(vtkMCXTypes::LineIntegralName());
    values->SetNumberOfValues(size * size);
    for (vtkIdType p = 0; p < size * size; ++p)
    {
      // Line integrals of a body: up to 300 g/cm^3 x mm, varying per pixel.
      values->SetValue(p, (m + 1) * 20.0 * (1.0 + (p % 97) / 97.0));
    }
    image->GetPointData()->SetScalars(values);
    channels.push_back(image);
  }
  vtkNew<vtkMCXPolychromaticRadiograph> radiograph;
  for (auto& channel : channels)
  {
    radiograph->AddInputData(channel);
  }
  bool hard = false;
  for (auto _ : state)
  {
    // A spectrum change: the model is rebuilt and every pixel re-mapped.
    radiograph->SetSpectrum(hard ? "101kVp,3mmAl" : "101kVp,2.5mmAl");
    hard = !hard;
    radiograph->Update();
    benchmark::DoNotOptimize(radiograph->GetOutput());
  }
  state.counters["pixels"] = size * size;
}
BENCHMARK(PolychromaticRemap)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same re-map with the model kept (an effect change, e.g. the noise):
// the per-pixel sums alone.
static void PolychromaticPixels(benchmark::State& state)
{
  constexpr int size = 512;
  std::vector<vtkSmartPointer<vtkImageData>> channels;
  for (int m = 0; m < 4; ++m)
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(size, size, 1);
    vtkNew<vtkDoubleArray> values;
    values->SetName(vtkMCXTypes::LineIntegralName());
    values->SetNumberOfValues(size * size);
    for (vtkIdType p = 0; p < size * size; ++p)
    {
      values->SetValue(p, (m + 1) * 20.0 * (1.0 + (p % 97) / 97.0));
    }
    image->GetPointData()->SetScalars(values);
    channels.push_back(image);
  }
  vtkNew<vtkMCXPolychromaticRadiograph> radiograph;
  for (auto& channel : channels)
  {
    radiograph->AddInputData(channel);
  }
  radiograph->SetSpectrum("101kVp,2.5mmAl");
  bool log = false;
  for (auto _ : state)
  {
    radiograph->SetNegativeLog(log);
    log = !log;
    radiograph->Update();
    benchmark::DoNotOptimize(radiograph->GetOutput());
  }
  state.counters["pixels"] = size * size;
}
BENCHMARK(PolychromaticPixels)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
