// Samples per second of the sampling and projection kernels, on 1 and 2
// threads, next to the machine's own ceilings measured in the same run:
// streaming read and memcpy bandwidth, and independent random 4-byte reads
// from a 1.6 GB array with 4 KiB pages and with transparent huge pages (the
// cost floor of a sample that reads one scattered index entry).
//
// Kernel rows: the fused path (vtkMCXProjector on a vtkMCXDensityIndex, the
// samples never stored), the stored cloud's sampling (vtkMCXPointSampler,
// refilled in place) and the stored cloud's projection, each with point and
// footprint deposits, the projections in a parallel and a perspective view
// (oblique, 512^2), M = 2^22 - 1; and a new view's sort of every voxel
// (ViewOrderSort, the view-ordered cloud's, 256^2). Volumes: the bonsai CT (256^3) and, with
// --large, the CT chest upsampled (linear) past 400 M voxels (654 x 687 x
// 894: a 2.5 GB peak and a few seconds to build on 2 cores).
//
// Names: Ceiling/<what>/threads:<n>, <path>/<volume>/<view>/<deposit>/threads:<n>
// (ViewOrderSort's deposit "none": its items are the voxels sorted).
// Run through Testing/Benchmarks/kernel-rates, which reports medians per
// core and the ratio to a baseline build.
//
// Usage: BenchmarkKernels [--large] [--large-voxels N] [--exponent M] [benchmark flags]
#include "mcxHugePageAllocator.h"
#include "mcxVolumeReader.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"

#include "mcxUpsample.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkXMLImageDataReader.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <sys/mman.h>
#include <time.h>

namespace
{
int SampleExponent = 22;

// ---- Ceilings ----------------------------------------------------------

std::string FirstLine(const char* path)
{
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return in || !line.empty() ? line : std::string("(unreadable)");
}

// This process's anonymous memory on huge pages, in MiB (smaps_rollup).
double AnonHugeMiB()
{
  std::ifstream in("/proc/self/smaps_rollup");
  std::string key;
  double kilobytes = 0;
  while (in >> key)
  {
    if (key == "AnonHugePages:")
    {
      in >> kilobytes;
      break;
    }
  }
  return kilobytes / 1024;
}

// Runs f(thread, threads) on `threads` std::threads (the ceilings do not go
// through vtkSMPTools: they must not depend on its backend).
template <typename F>
void OnThreads(int threads, const F& f)
{
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t)
  {
    pool.emplace_back(f, t, threads);
  }
  f(0, threads);
  for (std::thread& thread : pool)
  {
    thread.join();
  }
}

// A range [begin, end) of n split over threads.
std::pair<std::size_t, std::size_t> Share(std::size_t n, int thread, int threads)
{
  return { n * thread / threads, n * (thread + 1) / threads };
}

const std::size_t StreamBytes = std::size_t(512) << 20;

void StreamRead(benchmark::State& state, int threads)
{
  std::vector<std::uint64_t> buffer(StreamBytes / 8, 1);
  std::vector<std::uint64_t> sums(threads);
  for (auto _ : state)
  {
    OnThreads(threads,
      [&](int t, int n)
      {
        const auto range = Share(buffer.size(), t, n);
        // Four sums: no dependency chain longer than the loads.
        std::uint64_t s[4] = { 0, 0, 0, 0 };
        for (std::size_t i = range.first; i + 4 <= range.second; i += 4)
        {
          s[0] += buffer[i];
          s[1] += buffer[i + 1];
          s[2] += buffer[i + 2];
          s[3] += buffer[i + 3];
        }
        sums[t] = s[0] + s[1] + s[2] + s[3];
      });
    benchmark::DoNotOptimize(sums.data());
  }
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(StreamBytes));
}

void Memcpy(benchmark::State& state, int threads)
{
  std::vector<char> source(StreamBytes, 1), target(StreamBytes, 0);
  for (auto _ : state)
  {
    OnThreads(threads,
      [&](int t, int n)
      {
        const auto range = Share(StreamBytes, t, n);
        std::memcpy(
          target.data() + range.first, source.data() + range.first, range.second - range.first);
      });
    benchmark::DoNotOptimize(target.data());
    benchmark::ClobberMemory();
  }
  // Bytes copied: each is read once and written once.
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(StreamBytes));
}

// 400 M 4-byte entries: 1.6 GB, far past every cache and a 4 KiB TLB's reach.
const std::size_t RandomEntries = 400000000;
const std::size_t ReadsPerIteration = std::size_t(1) << 24;

// Reads at addresses that do not depend on earlier loads (as a sample's
// index entry), so the core overlaps as many misses as it can track.
std::uint64_t RandomReads(
  const std::uint32_t* a, std::uint64_t n, std::size_t count, std::uint64_t seed)
{
  std::uint64_t sum = 0, x = seed;
  for (std::size_t i = 0; i < count; ++i)
  {
    x += 0x9E3779B97F4A7C15ull; // splitmix64's step and a cheap half of its finaliser
    std::uint64_t z = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    z ^= z >> 27;
    sum += a[static_cast<std::uint64_t>((static_cast<unsigned __int128>(z) * n) >> 64)];
  }
  return sum;
}

// huge: transparent huge pages, as mcx::HugePageAllocator asks for them;
// else 4 KiB pages (MADV_NOHUGEPAGE).
void RandomRead(benchmark::State& state, bool huge, int threads)
{
  const std::size_t bytes = RandomEntries * sizeof(std::uint32_t);
  const double hugeBefore = AnonHugeMiB();
  std::uint32_t* a = nullptr;
  mcx::HugePageAllocator<std::uint32_t> allocator;
  if (huge)
  {
    a = allocator.allocate(RandomEntries);
  }
  else
  {
    void* memory = nullptr;
    if (posix_memalign(&memory, std::size_t(2) << 20, bytes) != 0)
    {
      state.SkipWithError("out of memory");
      return;
    }
    madvise(memory, bytes, MADV_NOHUGEPAGE);
    a = static_cast<std::uint32_t*>(memory);
  }
  for (std::size_t i = 0; i < RandomEntries; ++i)
  {
    a[i] = static_cast<std::uint32_t>(i);
  }
  // What the kernel granted (0 where THP is "never", or memory fragmented).
  state.counters["huge_MiB"] = std::max(0.0, AnonHugeMiB() - hugeBefore);
  std::vector<std::uint64_t> sums(threads);
  std::uint64_t round = 0;
  for (auto _ : state)
  {
    ++round;
    OnThreads(threads,
      [&](int t, int n)
      { sums[t] = RandomReads(a, RandomEntries, ReadsPerIteration / n, round * 64 + t); });
    benchmark::DoNotOptimize(sums.data());
  }
  if (huge)
  {
    allocator.deallocate(a, RandomEntries);
  }
  else
  {
    std::free(a);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(ReadsPerIteration));
  state.SetLabel("reads");
}

// ---- Kernels -----------------------------------------------------------

struct Volume
{
  std::string Name;
  vtkSmartPointer<vtkImageData> Image;
  vtkSmartPointer<vtkMCXDensityIndex> Index;
  vtkSmartPointer<vtkPiecewiseFunction> TF;
  vtkSmartPointer<vtkCamera> Views[2]; // parallel, perspective
};

// The same oblique view for both projections: the perspective one of
// BenchmarkCore, and its parallel twin covering the volume.
void MakeViews(Volume& v)
{
  double bounds[6];
  v.Image->GetBounds(bounds);
  const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  const double size =
    std::max(bounds[1] - bounds[0], std::max(bounds[3] - bounds[2], bounds[5] - bounds[4]));
  for (int perspective = 0; perspective < 2; ++perspective)
  {
    auto camera = vtkSmartPointer<vtkCamera>::New();
    camera->SetFocalPoint(centre);
    camera->SetPosition(centre[0] + 1.2 * size, centre[1] - 1.5 * size, centre[2] + 0.8 * size);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(30);
    camera->SetClippingRange(0.1 * size, 10 * size);
    camera->SetParallelProjection(perspective == 0);
    camera->SetParallelScale(0.5 * std::sqrt(3.0) * size);
    v.Views[perspective] = camera;
  }
}

// The bonsai (BenchmarkCore's TF: 0 below 20 % of the range), or the CT
// chest upsampled, with the peers' HU-to-attenuation TF (every tissue
// voxel weighs). Null, the reason printed, when the file is missing.
std::unique_ptr<Volume> Load(bool large, double largeVoxels)
{
  auto v = std::make_unique<Volume>();
  v->TF = vtkSmartPointer<vtkPiecewiseFunction>::New();
  if (!large)
  {
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName((std::string(MCXRAY_SHARED_DATA_DIR) + "/ct_bonsai.vti").c_str());
    reader->Update();
    v->Image = reader->GetOutput();
    if (!v->Image || v->Image->GetNumberOfPoints() == 0)
    {
      std::cerr << "BenchmarkKernels: cannot read the bonsai CT" << std::endl;
      return nullptr;
    }
    double range[2];
    v->Image->GetPointData()->GetScalars()->GetRange(range);
    v->TF->AddPoint(range[0] + 0.2 * (range[1] - range[0]), 0.0);
    v->TF->AddPoint(range[1], 1.0);
    v->Name = "bonsai";
  }
  else
  {
    std::string error;
    vtkSmartPointer<vtkImageData> chest = mcxio::ReadVolume(
      std::string(MCXRAY_SHARED_DATA_DIR) + "/ct_chest_cta_totalseg.nii.gz", error);
    if (!chest)
    {
      std::cerr << "BenchmarkKernels: cannot read the CT chest: " << error << std::endl;
      return nullptr;
    }
    v->Image = mcxbench::Upsample(chest, largeVoxels);
    v->TF->AddPoint(-1000, 0.0);
    v->TF->AddPoint(4000, 0.011);
    v->Name = "large";
  }
  v->Index = vtkSmartPointer<vtkMCXDensityIndex>::New();
  v->Index->SetInputData(v->Image);
  v->Index->Update();
  MakeViews(*v);
  return v;
}

// The cores a timed loop kept busy (process CPU time over wall time), and
// the threads vtkSMPTools said it would use: on a shared machine a 2-thread
// row may not get 2 cores.
class CoresUsed
{
public:
  CoresUsed()
    : Cpu(Now(CLOCK_PROCESS_CPUTIME_ID))
    , Wall(Now(CLOCK_MONOTONIC))
  {
  }
  void Report(benchmark::State& state) const
  {
    const double wall = Now(CLOCK_MONOTONIC) - this->Wall;
    state.counters["cores_used"] =
      wall > 0 ? (Now(CLOCK_PROCESS_CPUTIME_ID) - this->Cpu) / wall : 0;
    state.counters["smp_threads"] = vtkSMPTools::GetEstimatedNumberOfThreads();
  }

private:
  static double Now(clockid_t clock)
  {
    timespec t{};
    clock_gettime(clock, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }
  double Cpu, Wall;
};

std::string Dimensions(vtkImageData* image)
{
  int d[3];
  image->GetDimensions(d);
  return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
}

const int Deposits[2] = { vtkMCXTypes::POINT, vtkMCXTypes::FOOTPRINT };

// The fused path: samples generated and projected, never stored.
void Fused(benchmark::State& state, Volume* v, int view, int deposit, int threads)
{
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(v->Index->GetOutputPort());
  projector->SetTransferFunction(v->TF);
  projector->SetCamera(v->Views[view]);
  projector->SetImageSize(512, 512);
  projector->SetSampleExponent(SampleExponent);
  projector->SetDeposit(Deposits[deposit]);
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads },
    [&]()
    {
      projector->Update(); // the first run: allocations, footprint tables
      const CoresUsed cores;
      for (auto _ : state)
      {
        projector->Modified();
        projector->Update();
      }
      cores.Report(state);
    });
  state.SetItemsProcessed(state.iterations() * projector->GetNumberOfSamples());
  state.SetLabel(Dimensions(v->Image));
}

vtkSmartPointer<vtkMCXPointSampler> Sampler(Volume* v, int deposit)
{
  auto sampler = vtkSmartPointer<vtkMCXPointSampler>::New();
  sampler->SetInputConnection(v->Index->GetOutputPort());
  sampler->SetTransferFunction(v->TF);
  sampler->SetSampleExponent(SampleExponent);
  sampler->SetDeposit(Deposits[deposit]);
  sampler->ReusePointsOn(); // as the viewer's: a TF edit refills the cloud in place
  return sampler;
}

// The stored cloud's sampling (a TF edit's regeneration; no view).
void CloudSampling(benchmark::State& state, Volume* v, int deposit, int threads)
{
  auto sampler = Sampler(v, deposit);
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads },
    [&]()
    {
      sampler->Update(); // the first cloud, allocated
      const CoresUsed cores;
      for (auto _ : state)
      {
        sampler->Modified();
        sampler->Update();
      }
      cores.Report(state);
    });
  state.SetItemsProcessed(state.iterations() * sampler->GetOutput()->GetNumberOfPoints());
  state.SetLabel(Dimensions(v->Image));
}

// The stored cloud's projection (a camera move), the cloud made once.
void CloudProjection(benchmark::State& state, Volume* v, int view, int deposit, int threads)
{
  auto sampler = Sampler(v, deposit);
  sampler->Update();
  vtkNew<vtkPolyData> cloud;
  cloud->ShallowCopy(sampler->GetOutput());
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputData(cloud);
  projector->SetCamera(v->Views[view]);
  projector->SetImageSize(512, 512);
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads },
    [&]()
    {
      projector->Update();
      const CoresUsed cores;
      for (auto _ : state)
      {
        projector->Modified();
        projector->Update();
      }
      cores.Report(state);
    });
  state.SetItemsProcessed(state.iterations() * cloud->GetNumberOfPoints());
  state.SetLabel(Dimensions(v->Image));
}

// A new view's sort (vtkMCXPointSampler's VIEW_ORDERED, no control image,
// 2^19 - 1 points, 256^2 pixels of the perspective view): each iteration
// turns the ordering view 10 degrees one way or back, so every update sorts
// every voxel again, into the previous order's arrays (a later view's cost);
// first_view_s is the first view's, into fresh arrays.
void ViewOrderSort(benchmark::State& state, Volume* v, int threads)
{
  auto sampler = vtkSmartPointer<vtkMCXPointSampler>::New();
  sampler->SetInputConnection(v->Index->GetOutputPort());
  sampler->SetTransferFunction(v->TF);
  sampler->SetStrategyToViewOrdered();
  sampler->SetSampleExponent(19);
  sampler->ControlVariateOff();
  vtkNew<vtkCamera> camera;
  camera->DeepCopy(v->Views[1]);
  const int size = 256;
  double turn = 10.0;
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads },
    [&]()
    {
      sampler->SetOrderingView(camera, size, size);
      const auto start = std::chrono::steady_clock::now();
      sampler->Update(); // the first view: fresh arrays
      state.counters["first_view_s"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const CoresUsed cores;
      for (auto _ : state)
      {
        camera->Azimuth(turn);
        turn = -turn;
        sampler->SetOrderingView(camera, size, size);
        sampler->Update();
      }
      cores.Report(state);
    });
  state.SetItemsProcessed(state.iterations() * v->Image->GetNumberOfPoints());
  state.SetLabel(Dimensions(v->Image));
}

void RegisterKernels(Volume* v)
{
  for (int threads = 1; threads <= 2; ++threads)
  {
    benchmark::RegisterBenchmark(
      ("ViewOrderSort/" + v->Name + "/perspective/none/threads:" + std::to_string(threads)).c_str(),
      ViewOrderSort, v, threads)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  }
  const char* views[2] = { "parallel", "perspective" };
  const char* deposits[2] = { "point", "footprint" };
  for (int d = 0; d < 2; ++d)
  {
    for (int threads = 1; threads <= 2; ++threads)
    {
      const std::string tail =
        std::string("/") + deposits[d] + "/threads:" + std::to_string(threads);
      for (int view = 0; view < 2; ++view)
      {
        const std::string middle = "/" + v->Name + "/" + views[view];
        benchmark::RegisterBenchmark(("Fused" + middle + tail).c_str(), Fused, v, view, d, threads)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
        benchmark::RegisterBenchmark(
          ("CloudProjection" + middle + tail).c_str(), CloudProjection, v, view, d, threads)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
      }
      benchmark::RegisterBenchmark(
        ("CloudSampling/" + v->Name + "/any" + tail).c_str(), CloudSampling, v, d, threads)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    }
  }
}
}

int main(int argc, char* argv[])
{
  // Our flags first; the rest goes to Google Benchmark.
  bool large = false;
  double largeVoxels = 4.0e8;
  std::vector<char*> rest = { argv[0] };
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--large") == 0)
      large = true;
    else if (std::strcmp(argv[i], "--large-voxels") == 0 && i + 1 < argc)
      largeVoxels = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--exponent") == 0 && i + 1 < argc)
      SampleExponent = std::atoi(argv[++i]);
    else
      rest.push_back(argv[i]);
  }
  int restCount = static_cast<int>(rest.size());
  benchmark::Initialize(&restCount, rest.data());
  if (benchmark::ReportUnrecognizedArguments(restCount, rest.data()))
  {
    std::cerr << "usage: BenchmarkKernels [--large] [--large-voxels N] [--exponent M] "
                 "[benchmark flags]"
              << std::endl;
    return 2;
  }
  const std::string thp = FirstLine("/sys/kernel/mm/transparent_hugepage/enabled");
  const std::string defrag = FirstLine("/sys/kernel/mm/transparent_hugepage/defrag");
  std::cerr << "transparent_hugepage/enabled: " << thp << "; defrag: " << defrag << std::endl;
  benchmark::AddCustomContext("thp_enabled", thp);
  benchmark::AddCustomContext("thp_defrag", defrag);
  benchmark::AddCustomContext("sample_exponent", std::to_string(SampleExponent));

  for (int threads = 1; threads <= 2; ++threads)
  {
    const std::string n = "/threads:" + std::to_string(threads);
    benchmark::RegisterBenchmark(("Ceiling/StreamRead" + n).c_str(), StreamRead, threads)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
    benchmark::RegisterBenchmark(("Ceiling/Memcpy" + n).c_str(), Memcpy, threads)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
    for (const bool huge : { false, true })
    {
      benchmark::RegisterBenchmark(
        ((huge ? "Ceiling/RandomRead4B/huge" : "Ceiling/RandomRead4B/4KiB") + n).c_str(),
        RandomRead, huge, threads)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    }
  }
  // Loaded before the runs (not timed); the large one only when asked.
  std::vector<std::unique_ptr<Volume>> volumes;
  for (const bool which : { false, true })
  {
    if (which && !large)
    {
      continue;
    }
    volumes.push_back(Load(which, largeVoxels));
    if (!volumes.back())
    {
      return 1;
    }
    std::cerr << volumes.back()->Name << ": " << Dimensions(volumes.back()->Image) << std::endl;
    RegisterKernels(volumes.back().get());
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
