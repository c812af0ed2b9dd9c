// Scaling on MPI: a real CT (the CT chest) upsampled (linear) past 400 M voxels, each
// process making only its z-slab of it; the time of each stage (slowest
// process), the bytes each process exchanges, and each process's peak memory.
// Run it under mpiexec with 1 and with 2 processes (run-benchmarks does):
//
//   mpiexec -np N BenchmarkDistributed [--quick] [--data DIR]
//
// One machine's cores are shared among its processes (vtkSMPTools threads =
// cores / processes), so 1 and 2 processes use the same 2 cores here: the
// ratio shows the cost of distribution, not a speed-up of more hardware.
// Stages: the upsampled slab (the volume this process holds), its index, and
// a TF edit: the fused projector (levels gathered, the process's own samples
// generated and deposited, the exact sums added), 2^24 - 1 samples at 256^2,
// point and footprint deposits, median of 3.
#include "vtkMCXDensityIndex.h"
#include "vtkMCXDistributed.h"
#include "vtkMCXProjector.h"

#include "vtkCommunicator.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkImageInterpolator.h"
#include "vtkImageResize.h"
#include "vtkInformation.h"
#include "vtkMPIController.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkNIFTIImageReader.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Wall time of a collective stage: the slowest process's.
template <typename Work>
double Timed(vtkMultiProcessController* controller, const Work& work)
{
  controller->Barrier();
  const Clock::time_point start = Clock::now();
  work();
  double mine = Since(start), slowest = 0;
  controller->AllReduce(&mine, &slowest, 1, vtkCommunicator::MAX_OP);
  return slowest;
}

double PeakMegabytes(vtkMultiProcessController* controller)
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  double mine = usage.ru_maxrss / 1024.0, largest = 0; // kB on Linux
  controller->AllReduce(&mine, &largest, 1, vtkCommunicator::MAX_OP);
  return largest;
}
}

int main(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller);
  const int processes = controller->GetNumberOfProcesses();
  const bool first = controller->GetLocalProcessId() == 0;
  bool quick = false;
  std::string data = MCXRAY_SHARED_DATA_DIR;
  for (int a = 1; a < argc; ++a)
  {
    if (std::strcmp(argv[a], "--quick") == 0)
    {
      quick = true;
    }
    else if (std::strcmp(argv[a], "--data") == 0 && a + 1 < argc)
    {
      data = argv[++a];
    }
  }
  // The machine's cores shared among its processes (one machine here).
  vtkSMPTools::Initialize(std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / processes));
  const double leastVoxels = quick ? 20e6 : 400e6;
  const int exponent = quick ? 20 : 24;
  const int size = 256;

  vtkNew<vtkNIFTIImageReader> reader; // the CT chest in HU, as BenchmarkPeers reads it
  reader->SetFileName((data + "/ct_chest_cta_totalseg.nii.gz").c_str());
  reader->UpdateInformation();
  int wholeIn[6];
  reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeIn);
  const double inVoxels = static_cast<double>(wholeIn[1] - wholeIn[0] + 1) *
    (wholeIn[3] - wholeIn[2] + 1) * (wholeIn[5] - wholeIn[4] + 1);
  if (!(inVoxels > 0))
  {
    if (first)
    {
      std::fprintf(
        stderr, "BenchmarkDistributed: cannot read %s/ct_chest_cta_totalseg.nii.gz\n", data.c_str());
    }
    controller->Finalize();
    return 1;
  }
  const double factor = std::cbrt(leastVoxels / inVoxels) * (1 + 1e-3);
  int dims[3];
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = static_cast<int>(std::ceil((wholeIn[2 * a + 1] - wholeIn[2 * a] + 1) * factor));
  }
  const double voxels = static_cast<double>(dims[0]) * dims[1] * dims[2];
  vtkNew<vtkImageInterpolator> linear;
  linear->SetInterpolationModeToLinear();
  vtkNew<vtkImageResize> resize; // streams: makes only the slab asked of it
  resize->SetInputConnection(reader->GetOutputPort());
  resize->SetInterpolator(linear);
  resize->SetOutputDimensions(dims);
  int whole[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 }, slab[6];
  mcx::ZSlabExtent(whole, controller->GetLocalProcessId(), processes, slab);
  const double upsample = Timed(controller, [&] { resize->UpdateExtent(slab); });

  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputConnection(resize->GetOutputPort());
  const double indexing = Timed(controller, [&] { index->UpdateExtent(slab); });
  const double levels = index->GetOutput()->GetFieldData()->GetArray("LevelValues")->GetNumberOfTuples();
  double allLevels = 0;
  controller->AllReduce(&levels, &allLevels, 1, vtkCommunicator::MAX_OP);

  vtkNew<vtkPiecewiseFunction> tf; // HU to attenuation per mm (plastimatch's), 0 at air
  tf->AddPoint(-1000, 0);
  tf->AddPoint(4000, 0.011);
  double edits[2] = { 0, 0 };
  double error[2] = { 0, 0 };
  for (int deposit = 0; deposit < 2; ++deposit)
  {
    vtkNew<vtkMCXProjector> projector;
    projector->SetInputConnection(index->GetOutputPort());
    projector->SetTransferFunction(tf);
    projector->SetDeposit(deposit);
    projector->SetSampleExponent(exponent);
    projector->SetImageSize(size, size);
    std::vector<double> seconds;
    for (int repetition = 0; repetition < 3; ++repetition)
    {
      tf->AddPoint(3000, 0.0088 + 1e-6 * repetition); // a TF edit
      seconds.push_back(Timed(controller, [&] { projector->Update(); }));
    }
    std::sort(seconds.begin(), seconds.end());
    edits[deposit] = seconds[1];
    if (first)
    {
      error[deposit] =
        projector->GetOutput()->GetFieldData()->GetArray("EstimatedRelativeError")->GetTuple1(0);
    }
  }
  const double peak = PeakMegabytes(controller);
  if (first)
  {
    // Bytes one process sends per TF edit (an all-gather of L level values
    // and L counts from each process, one 512-byte status, and the all-reduce
    // of the image's two exact sums, 3 words each per pixel); an all-reduce
    // or all-gather also receives about as much.
    const double perEdit = 8.0 * allLevels * 2 + 512 + 48.0 * size * size;
    std::printf("| processes | voxels | upsampled slab | index | TF edit, point (2^%d - 1, %d^2) | "
                "TF edit, footprint | estimated error (point, footprint) | levels | bytes sent per "
                "process per TF edit | peak memory per process |\n",
      exponent, size);
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    std::printf("| %d | %.0f M (%dx%dx%d) | %.2f s | %.2f s | %.3f s | %.3f s | %.4f, %.4f | %.0f | "
                "%.1f MB | %.0f MB |\n",
      processes, voxels / 1e6, dims[0], dims[1], dims[2], upsample, indexing, edits[0], edits[1],
      error[0], error[1], allLevels, perEdit / 1e6, peak);
  }
  controller->Finalize();
  return 0;
}
