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

// The radiograph of 4 material channels of 512^2 line integrals of a body
// (up to 300 g/cm^3 x mm, varying per pixel), its inputs held by it.
constexpr int Size = 512;

static void AddChannels(vtkMCXPolychromaticRadiograph* radiograph)
{
  for (int m = 0; m < 4; ++m)
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(Size, Size, 1);
    vtkNew<vtkDoubleArray> values;
    values->SetName(vtkMCXTypes::LineIntegralName());
    values->SetNumberOfValues(Size * Size);
    for (vtkIdType p = 0; p < Size * Size; ++p)
    {
      values->SetValue(p, (m + 1) * 20.0 * (1.0 + (p % 97) / 97.0));
    }
    image->GetPointData()->SetScalars(values);
    radiograph->AddInputData(image);
  }
}

static void PolychromaticRemap(benchmark::State& state)
{
  vtkNew<vtkMCXPolychromaticRadiograph> radiograph;
  AddChannels(radiograph);
  bool hard = false;
  for (auto _ : state)
  {
    // A spectrum change: the model is rebuilt and every pixel re-mapped.
    radiograph->SetSpectrum(hard ? "101kVp,3mmAl" : "101kVp,2.5mmAl");
    hard = !hard;
    radiograph->Update();
    benchmark::DoNotOptimize(radiograph->GetOutput());
  }
  state.counters["pixels"] = Size * Size;
}
BENCHMARK(PolychromaticRemap)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same re-map with the model kept (an effect change, e.g. the noise):
// the per-pixel sums alone.
static void PolychromaticPixels(benchmark::State& state)
{
  vtkNew<vtkMCXPolychromaticRadiograph> radiograph;
  AddChannels(radiograph);
  radiograph->SetSpectrum("101kVp,2.5mmAl");
  bool log = false;
  for (auto _ : state)
  {
    radiograph->SetNegativeLog(log);
    log = !log;
    radiograph->Update();
    benchmark::DoNotOptimize(radiograph->GetOutput());
  }
  state.counters["pixels"] = Size * Size;
}
BENCHMARK(PolychromaticPixels)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
