// What accuracy costs in time: convergence of each method against the exact
// reference (the paper's Figure 4), accuracy against wall time, the paper's
// Table 1, TF-edit latency, scaling with voxels and samples, memory, and how
// well the error estimate and the target-accuracy control keep their promise.
// (The peers, plastimatch and VTK's ray cast, are BenchmarkPeers'.) Writes CSV
// files into the output folder; Testing/Benchmarks/accuracy-report turns them
// into plots and a Markdown report.
//
// Usage: BenchmarkAccuracy [--quick] [--output DIR] [--data DIR]
#include "mcxAccuracyMeasures.h"
#include "mcxTransferFunctionSpec.h"
#include "mcxVolumeReader.h"

#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkImageResize.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkSmartPointer.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using mcxbench::Clock;
using mcxbench::FieldValue;
using mcxbench::MakeProjector;
using mcxbench::Median;
using mcxbench::Reference;
using mcxbench::RelativeRMS;
using mcxbench::Since;
using mcxbench::Values;

struct Case
{
  std::string Name; // short label
  std::string File; // in the data folder
  std::string TF;   // mcxray --tf spec
  double PaperVoxels;
  double PaperIndexSeconds;
  double PaperOfflineSeconds;
};

// The paper's volumes were a CT head, a CT body and an MRI angiography.
// Hounsfield units map to plastimatch's attenuation, mu = 0.0022 (1 + HU/1000)
// per mm (measured from its output), clamped at air.
const char* const AttenuationTF = "-1000:0,4000:0.011";

struct View
{
  std::string Name;
  vtkSmartPointer<vtkCamera> Camera;
};

std::vector<View> Views(vtkImageData* volume)
{
  double bounds[6];
  volume->GetBounds(bounds);
  const double centre[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  const double size =
    std::max(bounds[1] - bounds[0], std::max(bounds[3] - bounds[2], bounds[5] - bounds[4]));
  std::vector<View> views(2);
  views[0].Name = "parallel-y";
  views[0].Camera = vtkSmartPointer<vtkCamera>::New();
  views[0].Camera->SetFocalPoint(centre);
  views[0].Camera->SetPosition(centre[0], centre[1] - 2 * size, centre[2]);
  views[0].Camera->SetViewUp(0, 0, 1);
  views[0].Camera->ParallelProjectionOn();
  views[0].Camera->SetParallelScale(0.6 * size);
  views[1].Name = "oblique-perspective";
  views[1].Camera = vtkSmartPointer<vtkCamera>::New();
  views[1].Camera->SetFocalPoint(centre);
  views[1].Camera->SetPosition(
    centre[0] + 1.2 * size, centre[1] - 1.5 * size, centre[2] + 0.8 * size);
  views[1].Camera->SetViewUp(0, 0, 1);
  views[1].Camera->SetViewAngle(30);
  views[1].Camera->SetClippingRange(0.1 * size, 10 * size);
  return views;
}

}

int main(int argc, char* argv[])
{
  mcxbench::BenchmarkArguments arguments;
  if (!mcxbench::ParseArguments(argc, argv, "BenchmarkAccuracy", MCXRAY_SHARED_DATA_DIR, arguments))
  {
    return 2;
  }
  const bool quick = arguments.Quick;
  const std::string& output = arguments.Output;
  const std::string& data = arguments.Data;
  const int size = quick ? 64 : 256;
  const double tolerance = quick ? 1e-2 : 1e-3;
  std::vector<int> exponents =
    quick ? std::vector<int>{ 14, 16 } : std::vector<int>{ 16, 18, 20, 22, 24, 26 };

  std::vector<Case> cases = {
    { "CT head (headsq)", std::string(MCXRAY_TEST_DATA_DIR) + "/ct_head_headsq.vti",
      "1000:0,1500:1", 10420224, 3.29, 4.71 },
    { "CT body (TotalSegmentator)", data + "/ct_body_totalseg.nii.gz", AttenuationTF, 7829520,
      3.87, 5.04 },
    { "angiography (aneurism)", data + "/angio_aneurism.vti", "60:0,255:1", 8126464, 3.36,
      4.61 },
  };

  std::ofstream convergence(output + "/convergence.csv");
  convergence << "volume,view,method,samples,seconds,true_error,estimated_error\n";
  std::ofstream references(output + "/reference.csv");
  references << "volume,view,size,seconds,estimated_error,rays_per_axis\n";
  std::ofstream table1(output + "/table1.csv");
  table1 << "volume,voxels,index_seconds,offline_seconds_16M,tf_edit_seconds_4M,paper_voxels,paper_"
            "index_seconds,paper_offline_seconds_16M\n";
  std::ofstream targets(output + "/targets.csv");
  targets << "volume,deposit,target,samples,seconds,true_error,estimated_error\n";
  int nonsense = 0; // target rows that cannot be right: a broken control must fail the run

  struct Method
  {
    const char* Name;
    int Strategy;
    int Deposit;
  };
  const Method methods[] = { { "hybrid", vtkMCXTypes::HYBRID, vtkMCXTypes::POINT },
    { "mc", vtkMCXTypes::MONTE_CARLO, vtkMCXTypes::POINT },
    { "qmc", vtkMCXTypes::QUASI_MONTE_CARLO, vtkMCXTypes::POINT },
    { "hybrid footprint", vtkMCXTypes::HYBRID, vtkMCXTypes::FOOTPRINT },
    { "mc footprint", vtkMCXTypes::MONTE_CARLO, vtkMCXTypes::FOOTPRINT } };
  for (const Case& c : cases)
  {
    vtkSmartPointer<vtkImageData> volume = mcxbench::ReadInStoredFrame(c.File, c.Name);
    if (!volume)
    {
      continue;
    }
    std::string error;
    double range[2] = { 0, 1 };
    vtkSmartPointer<vtkPiecewiseFunction> tf = mcxapp::MakeTransferFunction(c.TF, range, error);
    std::cout << c.Name << std::endl;

    vtkNew<vtkMCXDensityIndex> index;
    index->SetInputData(volume);
    std::vector<double> indexTimes;
    for (int r = 0; r < 5; ++r)
    {
      index->Modified();
      const Clock::time_point start = Clock::now();
      index->Update();
      indexTimes.push_back(Since(start));
    }

    // Table 1: off-line rendering of 16 M samples, oblique perspective 256^2.
    const std::vector<View> views = Views(volume);
    std::vector<double> offline;
    for (int r = 0; r < (quick ? 1 : 5); ++r)
    {
      auto projector = MakeProjector(index, tf, views[1].Camera, 256, quick ? 16 : 24);
      const Clock::time_point start = Clock::now();
      projector->Update();
      offline.push_back(Since(start));
    }
    // TF-edit latency: resampling a stored 4 M-point cloud after a TF change.
    vtkNew<vtkMCXPointSampler> sampler;
    sampler->SetInputConnection(index->GetOutputPort());
    sampler->SetTransferFunction(tf);
    sampler->SetSampleExponent(quick ? 16 : 22);
    sampler->Update();
    std::vector<double> edits;
    for (int r = 0; r < (quick ? 1 : 5); ++r)
    {
      tf->AddPoint(tf->GetRange()[1] + 1.0, tf->GetValue(tf->GetRange()[1])); // a TF edit
      const Clock::time_point start = Clock::now();
      sampler->Update();
      edits.push_back(Since(start));
    }
    table1 << '"' << c.Name << "\"," << volume->GetNumberOfPoints() << ',' << Median(indexTimes)
           << ',' << Median(offline) << ',' << Median(edits) << ','
           << static_cast<long long>(c.PaperVoxels) << ',' << c.PaperIndexSeconds << ','
           << c.PaperOfflineSeconds << '\n';

    for (const View& view : views)
    {
      double referenceSeconds = 0;
      auto reference = Reference(index, tf, view.Camera, size, tolerance, 9, referenceSeconds);
      references << '"' << c.Name << "\"," << view.Name << ',' << size << ',' << referenceSeconds
                 << ',' << FieldValue(reference, "EstimatedRelativeError") << ','
                 << FieldValue(reference, "RaysPerPixelAxis") << '\n';
      for (const Method& method : methods)
      {
        for (int m : exponents)
        {
          if (method.Deposit == vtkMCXTypes::FOOTPRINT && m > 24)
          {
            continue; // far below the reference's own error already
          }
          auto projector =
            MakeProjector(index, tf, view.Camera, size, m, method.Strategy, method.Deposit);
          const Clock::time_point start = Clock::now();
          projector->Update();
          const double seconds = Since(start);
          convergence << '"' << c.Name << "\"," << view.Name << ',' << method.Name << ','
                      << projector->GetNumberOfSamples() << ',' << seconds << ','
                      << RelativeRMS(Values(projector->GetOutput()), reference) << ','
                      << FieldValue(projector->GetOutput(), "EstimatedRelativeError") << '\n';
        }
      }
      std::cout << "  " << view.Name << " done" << std::endl;
    }

    // The target-accuracy control, checked against the reference.
    {
      double seconds = 0;
      auto reference = Reference(index, tf, views[0].Camera, size, tolerance, 9, seconds);
      for (int deposit : { vtkMCXTypes::POINT, vtkMCXTypes::FOOTPRINT })
      {
        for (double target : { 0.05, 0.02, 0.01 })
        {
          auto projector =
            MakeProjector(index, tf, views[0].Camera, size, 0, vtkMCXTypes::HYBRID, deposit);
          projector->SetTargetRelativeError(target);
          projector->SetMaximumSampleExponent(quick ? 20 : 28);
          const Clock::time_point start = Clock::now();
          projector->Update();
          const double seconds = Since(start);
          const double samples = FieldValue(projector->GetOutput(), "SampleCount");
          const double truth = RelativeRMS(Values(projector->GetOutput()), reference);
          const double estimate = FieldValue(projector->GetOutput(), "EstimatedRelativeError");
          targets << '"' << c.Name << "\"," << (deposit ? "footprint" : "point") << ',' << target
                  << ',' << static_cast<long long>(samples) << ',' << seconds << ',' << truth << ','
                  << estimate << '\n';
          // The control's promise (the target, with the estimate's slack, or
          // the largest count allowed) and finite numbers.
          const double largest = std::ldexp(1.0, projector->GetMaximumSampleExponent()) - 1;
          if (!(samples >= 65535) || !std::isfinite(truth) || !std::isfinite(estimate) ||
            (truth > 1.5 * target && samples < largest))
          {
            std::cerr << "nonsense target row: " << c.Name << ", target " << target << ", "
                      << samples << " samples, error " << truth << ", estimate " << estimate
                      << std::endl;
            ++nonsense;
          }
        }
      }
    }

  }

  // Scaling: time against voxel count at fixed M (resampled head), and against M.
  std::ofstream scaling(output + "/scaling.csv");
  scaling << "kind,voxels,samples,index_seconds,offline_seconds,index_bytes_per_voxel\n";
  {
    std::string error;
    vtkSmartPointer<vtkImageData> head =
      mcxio::ReadVolume(std::string(MCXRAY_TEST_DATA_DIR) + "/ct_head_headsq.vti", error);
    double range[2] = { 0, 1 };
    vtkSmartPointer<vtkPiecewiseFunction> tf =
      mcxapp::MakeTransferFunction("1000:0,1500:1", range, error);
    const std::vector<double> factors =
      quick ? std::vector<double>{ 1, 2 } : std::vector<double>{ 1, 2, 3, 4 };
    for (double factor : factors)
    {
      vtkNew<vtkImageResize> resize;
      resize->SetInputData(head);
      resize->SetOutputDimensions(static_cast<int>(64 * factor), static_cast<int>(64 * factor),
        static_cast<int>(93 * factor));
      resize->InterpolateOff();
      resize->Update();
      vtkNew<vtkMCXDensityIndex> index;
      index->SetInputConnection(resize->GetOutputPort());
      Clock::time_point start = Clock::now();
      index->Update();
      const double indexSeconds = Since(start);
      vtkFieldData* fd = index->GetOutput()->GetFieldData();
      double bytes = 0;
      for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
      {
        bytes += static_cast<double>(fd->GetArray(a)->GetActualMemorySize()) * 1024.0;
      }
      auto projector =
        MakeProjector(index, tf, Views(resize->GetOutput())[1].Camera, 256, quick ? 16 : 22);
      start = Clock::now();
      projector->Update();
      const double voxels = static_cast<double>(resize->GetOutput()->GetNumberOfPoints());
      scaling << "voxels," << static_cast<long long>(voxels) << ','
              << projector->GetNumberOfSamples() << ',' << indexSeconds << ',' << Since(start)
              << ',' << bytes / voxels << '\n';
    }
    vtkNew<vtkMCXDensityIndex> index;
    index->SetInputData(head);
    index->Update();
    for (int m : quick ? std::vector<int>{ 14, 16 } : std::vector<int>{ 18, 20, 22, 24, 26 })
    {
      auto projector = MakeProjector(index, tf, Views(head)[1].Camera, 256, m);
      const Clock::time_point start = Clock::now();
      projector->Update();
      scaling << "samples," << head->GetNumberOfPoints() << ',' << projector->GetNumberOfSamples()
              << ",0," << Since(start) << ",0\n";
    }
  }
  // Cost control of the footprint: the bundled CT in a lateral parallel view
  // at 512^2 (a tent covers about 17 x 9 pixels), the full footprint against
  // kernels split at smaller reaches and the point deposit, error against
  // time (error x sqrt(seconds) compares them at equal time under M^-1/2).
  {
    std::ofstream reach(output + "/footprint-reach.csv");
    reach << "deposit,reach,samples,seconds,true_error,error_x_sqrt_seconds\n";
    std::string error;
    vtkSmartPointer<vtkImageData> head =
      mcxio::ReadVolume(std::string(MCXRAY_TEST_DATA_DIR) + "/ct_head_headsq.vti", error);
    double range[2] = { 0, 1 };
    vtkSmartPointer<vtkPiecewiseFunction> tf =
      mcxapp::MakeTransferFunction("1000:0,1500:1", range, error);
    vtkNew<vtkMCXDensityIndex> index;
    index->SetInputData(head);
    index->Update();
    vtkNew<vtkCamera> camera;
    camera->SetFocalPoint(100.8, 100.8, 69);
    camera->SetPosition(450, 100.8, 69);
    camera->SetViewUp(0, 0, -1);
    camera->ParallelProjectionOn();
    camera->SetParallelScale(80);
    const int pixels = quick ? 128 : 512;
    double seconds = 0;
    auto reference = Reference(index, tf, camera, pixels, quick ? 1e-2 : 3e-4, 27, seconds);
    const int m = quick ? 16 : 20;
    for (double r : { 0.0, 2.0, 4.0, 8.0, 16.0 })
    {
      auto projector = MakeProjector(index, tf, camera, pixels, r > 0 ? m : m + 4,
        vtkMCXTypes::HYBRID, r > 0 ? vtkMCXTypes::FOOTPRINT : vtkMCXTypes::POINT);
      projector->SetFootprintReach(r > 0 ? r : 16.0);
      projector->Update(); // the tables once, then a timed run
      projector->Modified();
      const Clock::time_point start = Clock::now();
      projector->Update();
      const double t = Since(start);
      const double e = RelativeRMS(Values(projector->GetOutput()), reference);
      reach << (r > 0 ? "footprint," : "point,") << r << ',' << projector->GetNumberOfSamples()
            << ',' << t << ',' << e << ',' << e * std::sqrt(t) << '\n';
    }
  }
  std::ofstream memory(output + "/memory.csv");
  memory << "peak_resident_megabytes\n" << mcxbench::PeakResidentMegabytes() << '\n';
  std::cout << "wrote " << output << std::endl;
  if (nonsense > 0)
  {
    std::cerr << nonsense << " target-accuracy rows are nonsense: the control is broken"
              << std::endl;
    return 1;
  }
  return 0;
}
