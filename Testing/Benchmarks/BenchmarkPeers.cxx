// MonteCarloXRay against plastimatch drr (the peer DRR tool) in one run, with
// the same cone-beam geometry and HU-to-attenuation map, render time only: our
// index is built once per volume (its time is reported apart), and
// plastimatch's own "Total time" leaves out its start-up and loading. Volumes:
// the CT body, the CT chest, and the CT chest upsampled (linear) past 400 M
// voxels, where plastimatch's cost grows with the voxels and ours does not.
// For each volume and image size (256^2, 512^2): the exact reference,
// plastimatch `exact`, and our point and footprint deposits at growing M
// and every voxel once, all against the reference; the time each method
// takes to reach 2 %, 1 % and plastimatch's own error, our best method at
// each and its speedup over plastimatch (printed as a Markdown table too);
// and the latency of a TF edit to a complete 2 % image in the interactive
// mapper (a stored footprint cloud, 256^2). VTK's GPU ray-cast mapper
// (additive, software GL) is measured beside them on the small volumes.
// Writes volumes.csv, peers.csv, time-to-target.csv and tf-edit.csv.
//
// Usage: BenchmarkPeers [--quick] [--cases LIST] [--output DIR] [--data DIR]
//   --quick: small images, sample counts and "large" volume (a smoke run);
//   --cases: some of body,chest,large (default all), e.g. --cases large.
#include "mcxAccuracyMeasures.h"
#include "mcxPeerRuns.h"
#include "mcxTransferFunctionSpec.h"
#include "mcxVolumeReader.h"

#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"
#include "vtkMCXXRayMapper.h"

#include "mcxUpsample.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMetaImageWriter.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using mcxbench::Clock;
using mcxbench::PeerRun;
using mcxbench::RenderWithVTK;
using mcxbench::Since;

// Hounsfield units to plastimatch's attenuation, mu = 0.0022 (1 + HU/1000)
// per mm (measured from its output), clamped at air.
const char* const AttenuationTF = "-1000:0,4000:0.011";
const mcxbench::ConeBeam Beam;

struct VolumeCase
{
  std::string Key; // its name for --cases
  std::string Name;
  std::string File;
  double LeastVoxels; // upsample (linear) until the volume has at least these; 0: as read
  bool GPUPeer;       // VTK's GPU ray cast beside (its 3D texture must fit)
  // Every voxel once too (the fused DRR and the TF edit of a cloud): not
  // where the voxels far outnumber the samples that reach 2 % (the
  // upsampled volume's 400 M).
  bool EveryVoxel;
};

// plastimatch's geometry: gantry 0 puts the source at +x of the isocentre,
// the detector beyond it, columns along +y and the top row towards +z.
vtkSmartPointer<vtkCamera> ConeBeamCamera(vtkImageData* volume)
{
  double bounds[6];
  volume->GetBounds(bounds);
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetFocalPoint(
    (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2);
  const double* iso = camera->GetFocalPoint();
  camera->SetPosition(iso[0] + Beam.SourceToIsocentre, iso[1], iso[2]);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(
    2 * vtkMath::DegreesFromRadians(std::atan(Beam.DetectorSize / 2 / Beam.SourceToDetector)));
  camera->SetClippingRange(1.0, 10 * Beam.SourceToIsocentre);
  return camera;
}

// One render of ours: samples, render seconds (median of up to 3 runs, fresh
// projectors: the TF, the footprint tables and the projection each time),
// and the error against the reference.
struct Run
{
  double Samples = 0;
  double Seconds = 0;
  double Error = 1;
};

Run Render(vtkAlgorithm* index, vtkPiecewiseFunction* tf, vtkCamera* camera, int size, int m,
  int deposit, vtkImageData* reference, int strategy = vtkMCXTypes::HYBRID)
{
  Run run;
  std::vector<double> seconds;
  for (int repetition = 0; repetition < 3; ++repetition)
  {
    auto projector = mcxbench::MakeProjector(index, tf, camera, size, m, strategy, deposit);
    const Clock::time_point start = Clock::now();
    projector->Update();
    seconds.push_back(Since(start));
    run.Samples = mcxbench::FieldValue(projector->GetOutput(), "SampleCount");
    run.Error = mcxbench::RelativeRMS(mcxbench::Values(projector->GetOutput()), reference);
    if (seconds.back() > 1.0)
    {
      break; // long runs vary little
    }
  }
  run.Seconds = mcxbench::Median(seconds);
  return run;
}

// The TF edit of the interactive path: a node at 200 HU that doubles the
// contrast-filled vessels' and soft tissue's weight, added and removed in turn.
const double EditDensity = 200;

void ToggleEdit(vtkPiecewiseFunction* tf, bool on, double baseValue)
{
  if (on)
  {
    tf->AddPoint(EditDensity, 2 * baseValue);
  }
  else
  {
    tf->RemovePoint(EditDensity);
  }
}

struct EditResult
{
  double FirstRenderSeconds = 0; // the first cloud (VIEW_ORDERED: with the sort)
  double MedianMilliseconds = 0;
  double Errors[2] = { 1, 1 }; // without and with the edit
  vtkIdType Points = 0;
};

// A stored footprint cloud of 2^m - 1 points, or of every voxel
// (`strategy`), refilled in place as the viewer's, drawn by the mapper in a
// 256^2 window with the cone-beam camera, progressive refinement off (every
// render projects every point): the median
// time of a TF edit to the complete image; the error of each of the two TFs'
// clouds, projected off line (the mapper's image is the projector's, bit for
// bit: TestMapper).
EditResult MeasureTransferFunctionEdit(vtkAlgorithm* index, vtkPiecewiseFunction* tf,
  vtkCamera* camera, int size, int m, int strategy, vtkImageData* reference, int repetitions)
{
  EditResult result;
  const double baseValue = tf->GetValue(EditDensity);
  vtkNew<vtkMCXPointSampler> sampler;
  sampler->SetInputConnection(index->GetOutputPort());
  sampler->SetTransferFunction(tf);
  sampler->SetSampleExponent(m);
  sampler->SetStrategy(strategy);
  sampler->SetDepositToFootprint();
  sampler->ReusePointsOn(); // as the viewer's pipeline: the mapper is the cloud's only consumer
  sampler->SetOrderingView(camera, size, size); // used by VIEW_ORDERED only
  vtkNew<vtkMCXXRayMapper> mapper;
  mapper->SetInputConnection(sampler->GetOutputPort());
  mapper->ProgressiveRefinementOff();
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->SetActiveCamera(camera);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(size, size);
  window->AddRenderer(renderer);
  const Clock::time_point first = Clock::now();
  window->Render();
  result.FirstRenderSeconds = Since(first);
  std::vector<double> milliseconds;
  for (int r = 0; r < repetitions; ++r)
  {
    ToggleEdit(tf, r % 2 == 0, baseValue);
    const Clock::time_point start = Clock::now();
    window->Render();
    milliseconds.push_back(1000 * Since(start));
  }
  result.MedianMilliseconds = mcxbench::Median(milliseconds);
  result.Points = sampler->GetOutput()->GetNumberOfPoints();

  for (int edited = 0; edited < 2; ++edited)
  {
    ToggleEdit(tf, edited == 1, baseValue);
    sampler->Update();
    vtkNew<vtkPolyData> cloud;
    cloud->DeepCopy(sampler->GetOutput());
    double seconds = 0;
    auto exact = edited ? mcxbench::Reference(index, tf, camera, size, 1e-3, 9, seconds)
                        : vtkSmartPointer<vtkImageData>(reference);
    vtkNew<vtkMCXProjector> projector;
    projector->SetInputData(cloud);
    projector->SetCamera(camera);
    projector->SetImageSize(size, size);
    projector->Update();
    result.Errors[edited] = mcxbench::RelativeRMS(mcxbench::Values(projector->GetOutput()), exact);
  }
  ToggleEdit(tf, false, baseValue);
  return result;
}

// The least m in [first, last] whose view-ordered footprint cloud (sorted
// for `camera` at size^2) is within `target` of the reference (last if none).
int ViewOrderedExponentForTarget(vtkAlgorithm* index, vtkPiecewiseFunction* tf, vtkCamera* camera,
  int size, vtkImageData* reference, double target, int first, int last)
{
  vtkNew<vtkMCXPointSampler> sampler;
  sampler->SetInputConnection(index->GetOutputPort());
  sampler->SetTransferFunction(tf);
  sampler->SetStrategyToViewOrdered();
  sampler->SetOrderingView(camera, size, size);
  sampler->SetDepositToFootprint();
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(sampler->GetOutputPort());
  projector->SetCamera(camera);
  projector->SetImageSize(size, size);
  for (int m = first; m < last; ++m)
  {
    sampler->SetSampleExponent(m); // the sort is kept
    projector->Update();
    if (mcxbench::RelativeRMS(mcxbench::Values(projector->GetOutput()), reference) <= target)
    {
      return m;
    }
  }
  return last;
}

std::string Quoted(const std::string& text)
{
  return '"' + text + '"';
}

// A target error: 2 %, 1 %, or the error plastimatch reached in the case.
struct Target
{
  double Error;
  std::string Name;
};

// The first run of a sweep within a target (the cheapest), or its last run
// (Found false: the sweep's cap came first).
struct Reached
{
  Run Value;
  bool Found = false;
};

Reached FirstWithin(const std::vector<Run>& runs, double target)
{
  Reached reached;
  for (const Run& run : runs)
  {
    reached.Value = run;
    if (run.Error <= target)
    {
      reached.Found = true;
      break;
    }
  }
  return reached;
}

// A case at a target: plastimatch, and our best method there.
struct SummaryRow
{
  std::string Volume;
  double Voxels = 0;
  int Size = 0;
  Target Goal;
  mcxbench::PeerRun Peer;
  std::string Method;
  Reached Best;
  double Speedup = 0;        // 0 without plastimatch
  bool SpeedupBound = false; // an upper bound: no method reached the target
};

std::string Ratio(double peerSeconds, double ours, bool bound, int& nonsense)
{
  const double ratio = peerSeconds / ours;
  nonsense += std::isfinite(ratio) && ratio > 0 ? 0 : 1;
  std::ostringstream text;
  text << (bound ? "<" : "") << ratio;
  return text.str();
}

// Writes a time-to-target.csv row: the first columns as before (each
// deposit's first run within the target, plastimatch, and the speedup over
// the faster deposit), then the target's name, every voxel once, and our
// best method of all (every voxel once included): the fastest within the
// target, or where none is, the most accurate run (">": not reached, its
// speedup "<" a bound from the fastest last run).
SummaryRow AtTarget(std::ostream& csv, const std::string& volume, double voxels, int size,
  const Target& goal, const std::vector<Run> sweeps[2], const std::vector<Run>& every,
  const mcxbench::PeerRun& peer, int& nonsense)
{
  const Reached deposit[2] = { FirstWithin(sweeps[0], goal.Error),
    FirstWithin(sweeps[1], goal.Error) };
  csv << Quoted(volume) << ',' << size << ',' << goal.Error;
  for (const Reached& r : deposit)
  {
    csv << ',' << (r.Found ? "" : ">") << static_cast<long long>(r.Value.Samples) << ','
        << (r.Found ? "" : ">") << r.Value.Seconds << ',' << r.Value.Error;
  }
  if (peer.Done)
  {
    const bool any = deposit[0].Found || deposit[1].Found;
    double ours = std::numeric_limits<double>::infinity();
    for (const Reached& r : deposit)
    {
      ours = r.Found || !any ? std::min(ours, r.Value.Seconds) : ours;
    }
    csv << ',' << peer.RenderSeconds << ',' << peer.Error << ','
        << Ratio(peer.RenderSeconds, ours, !any, nonsense);
  }
  else
  {
    csv << ",,,";
  }
  SummaryRow row;
  row.Volume = volume;
  row.Voxels = voxels;
  row.Size = size;
  row.Goal = goal;
  row.Peer = peer;
  const Reached once = FirstWithin(every, goal.Error);
  const std::pair<const char*, Reached> methods[3] = { { "point", deposit[0] },
    { "footprint", deposit[1] }, { "every voxel", once } };
  double fastestLast = std::numeric_limits<double>::infinity();
  for (int k = 0; k < (every.empty() ? 2 : 3); ++k)
  {
    const Reached& r = methods[k].second;
    fastestLast = std::min(fastestLast, r.Value.Seconds);
    const bool better = row.Method.empty() ||
      (r.Found && (!row.Best.Found || r.Value.Seconds < row.Best.Value.Seconds)) ||
      (!r.Found && !row.Best.Found && r.Value.Error < row.Best.Value.Error);
    if (better)
    {
      row.Method = methods[k].first;
      row.Best = r;
    }
  }
  std::string speedup;
  if (peer.Done)
  {
    const double ours = row.Best.Found ? row.Best.Value.Seconds : fastestLast;
    speedup = Ratio(peer.RenderSeconds, ours, !row.Best.Found, nonsense);
    row.Speedup = peer.RenderSeconds / ours;
    row.SpeedupBound = !row.Best.Found;
  }
  const char* mark = row.Best.Found ? "" : ">";
  csv << ',' << goal.Name << ',';
  if (!every.empty())
  {
    csv << every[0].Seconds << ',' << every[0].Error;
  }
  else
  {
    csv << ',';
  }
  csv << ',' << row.Method << ',' << mark << static_cast<long long>(row.Best.Value.Samples) << ','
      << mark << row.Best.Value.Seconds << ',' << row.Best.Value.Error << ',' << speedup << '\n';
  return row;
}

// The summary of time-to-target.csv as a Markdown table.
void PrintSummary(const std::vector<SummaryRow>& rows)
{
  std::cout << "\n| volume | voxels | size | target | plastimatch s | plastimatch error | our best "
               "method | samples | seconds | error | speedup |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SummaryRow& r : rows)
  {
    char peer[64] = "- | -", speedup[32] = "-", line[512];
    if (r.Peer.Done)
    {
      std::snprintf(peer, sizeof(peer), "%.3g | %.2f %%", r.Peer.RenderSeconds, 100 * r.Peer.Error);
      std::snprintf(speedup, sizeof(speedup), "%s%.2f", r.SpeedupBound ? "<" : "", r.Speedup);
    }
    const char* mark = r.Best.Found ? "" : ">";
    std::snprintf(line, sizeof(line),
      "| %s | %.1f M | %d^2 | %s (%.2f %%) | %s | %s | %s%.0f | %s%.3g | %.2f %% | %s |\n",
      r.Volume.c_str(), r.Voxels / 1e6, r.Size, r.Goal.Name.c_str(), 100 * r.Goal.Error, peer,
      r.Method.c_str(), mark, r.Best.Value.Samples, mark, r.Best.Value.Seconds,
      100 * r.Best.Value.Error, speedup);
    std::cout << line;
  }
  std::cout << std::endl;
}
}

int main(int argc, char* argv[])
{
  // --cases LIST (comma-separated: body, chest, large) is ours; the rest
  // is the accuracy benchmarks' command line.
  std::vector<std::string> chosen;
  std::vector<char*> rest = { argv[0] };
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--cases") == 0 && i + 1 < argc)
    {
      std::istringstream list(argv[++i]);
      for (std::string key; std::getline(list, key, ',');)
      {
        chosen.push_back(key);
      }
    }
    else
    {
      rest.push_back(argv[i]);
    }
  }
  mcxbench::BenchmarkArguments arguments;
  if (!mcxbench::ParseArguments(static_cast<int>(rest.size()), rest.data(),
        "BenchmarkPeers [--cases body,chest,large]", MCXRAY_SHARED_DATA_DIR, arguments))
  {
    return 2;
  }
  const bool quick = arguments.Quick;
  const std::string& output = arguments.Output;
  const std::string& data = arguments.Data;
  const bool havePlastimatch = std::system("plastimatch --version > /dev/null 2>&1") == 0;
  if (!havePlastimatch)
  {
    std::cerr << "plastimatch not found: the peer columns stay empty" << std::endl;
  }
  const std::vector<int> sizes = quick ? std::vector<int>{ 64 } : std::vector<int>{ 256, 512 };
  // Sample exponents swept per deposit: from a first one until the last
  // target is reached or the cap.
  const std::array<int, 2> pointRange =
    quick ? std::array<int, 2>{ 14, 18 } : std::array<int, 2>{ 18, 30 };
  const std::array<int, 2> footprintRange =
    quick ? std::array<int, 2>{ 10, 16 } : std::array<int, 2>{ 14, 26 };
  const std::vector<VolumeCase> cases = {
    { "body", "CT body", data + "/ct_body_totalseg.nii.gz", 0, true, true },
    { "chest", "CT chest", data + "/ct_chest_cta_totalseg.nii.gz", 0, true, true },
    { "large",
      quick ? "CT chest upsampled past 8 M voxels" : "CT chest upsampled past 400 M voxels",
      data + "/ct_chest_cta_totalseg.nii.gz", quick ? 8.0e6 : 4.0e8, false, false },
  };
  for (const std::string& key : chosen)
  {
    if (std::none_of(cases.begin(), cases.end(), [&](const VolumeCase& c) { return c.Key == key; }))
    {
      std::cerr << "BenchmarkPeers: no case " << key << " (body, chest, large)" << std::endl;
      return 2;
    }
  }

  std::ofstream volumes(output + "/volumes.csv");
  volumes << "volume,dimensions,voxels,index_seconds,peak_resident_megabytes\n";
  std::ofstream peers(output + "/peers.csv");
  peers << "volume,size,tool,method,samples,seconds,error\n";
  std::ofstream targets(output + "/time-to-target.csv");
  targets << "volume,size,target,point_samples,point_seconds,point_error,footprint_samples,"
             "footprint_seconds,footprint_error,plastimatch_exact_seconds,plastimatch_error,"
             "speedup,target_name,every_voxel_seconds,every_voxel_error,best_method,best_samples,"
             "best_seconds,best_error,best_speedup\n";
  std::ofstream edits(output + "/tf-edit.csv");
  edits << "volume,size,cloud,points,first_render_ms,median_ms,error,error_after_edit\n";

  int nonsense = 0; // failed peers, non-finite errors: the run must fail loudly
  std::vector<SummaryRow> summary;
  for (const VolumeCase& c : cases)
  {
    if (!chosen.empty() && std::find(chosen.begin(), chosen.end(), c.Key) == chosen.end())
    {
      continue;
    }
    vtkSmartPointer<vtkImageData> volume = mcxbench::ReadInStoredFrame(c.File, c.Name);
    if (!volume)
    {
      continue;
    }
    std::string error;
    if (c.LeastVoxels > 0)
    {
      volume = mcxbench::Upsample(volume, c.LeastVoxels);
    }
    int dims[3];
    volume->GetDimensions(dims);
    std::cout << c.Name << ": " << dims[0] << " x " << dims[1] << " x " << dims[2] << std::endl;
    double range[2] = { 0, 1 };
    vtkSmartPointer<vtkPiecewiseFunction> tf =
      mcxapp::MakeTransferFunction(AttenuationTF, range, error);
    vtkSmartPointer<vtkCamera> camera = ConeBeamCamera(volume);

    vtkNew<vtkMCXDensityIndex> index;
    index->SetInputData(volume);
    const Clock::time_point indexStart = Clock::now();
    index->Update();
    const double indexSeconds = Since(indexStart);

    const std::string mha = output + "/plastimatch_input.mha";
    if (havePlastimatch)
    {
      vtkNew<vtkMetaImageWriter> writer;
      writer->SetInputData(volume);
      writer->SetFileName(mha.c_str());
      writer->SetCompression(false);
      writer->Write();
    }
    for (int size : sizes)
    {
      double referenceSeconds = 0;
      auto reference = mcxbench::Reference(index, tf, camera, size, 1e-3, 9, referenceSeconds);
      peers << Quoted(c.Name) << ',' << size << ",MonteCarloXRay,reference,0," << referenceSeconds
            << ',' << mcxbench::FieldValue(reference, "EstimatedRelativeError") << '\n';
      PeerRun peer;
      if (havePlastimatch)
      {
        peer =
          mcxbench::RunPlastimatch(mha, output, camera->GetFocalPoint(), size, Beam, reference);
        nonsense += peer.Done && std::isfinite(peer.Error) ? 0 : 1;
        if (peer.Done)
        {
          peers << Quoted(c.Name) << ',' << size << ",plastimatch,exact (render),0,"
                << peer.RenderSeconds << ',' << peer.Error << '\n';
          peers << Quoted(c.Name) << ',' << size << ",plastimatch,exact (whole process),0,"
                << peer.ProcessSeconds << ',' << peer.Error << '\n';
        }
      }
      double gpuSeconds = 0, gpuError = 0;
      if (c.GPUPeer && RenderWithVTK(volume, tf, camera, size, reference, gpuSeconds, gpuError))
      {
        peers << Quoted(c.Name) << ',' << size
              << ",VTK GPU ray cast (additive; software GL),8-bit,0," << gpuSeconds << ','
              << gpuError << '\n';
      }
      // The targets: 2 %, 1 % and, where it ran, plastimatch's own error.
      std::vector<Target> goals = { { 0.02, "2 %" }, { 0.01, "1 %" } };
      if (peer.Done)
      {
        goals.push_back({ peer.Error, "plastimatch's error" });
      }
      double least = 1;
      for (const Target& goal : goals)
      {
        least = std::min(least, goal.Error);
      }
      // Each deposit's sweep, until the least target is reached or the cap.
      std::vector<Run> sweeps[2];
      const int deposits[2] = { vtkMCXTypes::POINT, vtkMCXTypes::FOOTPRINT };
      for (int d = 0; d < 2; ++d)
      {
        const std::array<int, 2>& span = d == 0 ? pointRange : footprintRange;
        for (int m = span[0]; m <= span[1] && (sweeps[d].empty() || sweeps[d].back().Error > least);
             ++m)
        {
          const Run last = Render(index, tf, camera, size, m, deposits[d], reference);
          sweeps[d].push_back(last);
          peers << Quoted(c.Name) << ',' << size << ",MonteCarloXRay,"
                << (d == 0 ? "hybrid point" : "hybrid footprint") << ',' << last.Samples << ','
                << last.Seconds << ',' << last.Error << '\n';
          nonsense += std::isfinite(last.Error) && last.Seconds > 0 ? 0 : 1;
        }
      }
      std::vector<Run> every;
      if (c.EveryVoxel)
      {
        // The fused DRR of every voxel once: one run, no sample count.
        every.push_back(Render(
          index, tf, camera, size, 0, vtkMCXTypes::FOOTPRINT, reference, vtkMCXTypes::EVERY_VOXEL));
        peers << Quoted(c.Name) << ',' << size << ",MonteCarloXRay,every voxel footprint,"
              << every[0].Samples << ',' << every[0].Seconds << ',' << every[0].Error << '\n';
        nonsense += std::isfinite(every[0].Error) && every[0].Seconds > 0 ? 0 : 1;
      }
      for (const Target& goal : goals)
      {
        summary.push_back(
          AtTarget(targets, c.Name, static_cast<double>(volume->GetNumberOfPoints()), size, goal,
            sweeps, every, peer, nonsense));
      }
      // The interactive path at the smallest size: the footprint count that
      // reached 2 %, every voxel of non-zero weight once (where they are
      // fewer than 2^30 points), and the view-ordered count that reaches 2 %.
      if (size == sizes.front())
      {
        const double twoPercent = 0.02;
        const int m = static_cast<int>(
          std::lround(std::log2(FirstWithin(sweeps[1], twoPercent).Value.Samples + 1)));
        const int viewOrderedM = ViewOrderedExponentForTarget(
          index, tf, camera, size, reference, twoPercent, footprintRange[0], m);
        for (const int strategy : { vtkMCXTypes::HYBRID, vtkMCXTypes::EVERY_VOXEL,
               vtkMCXTypes::VIEW_ORDERED })
        {
          if (strategy == vtkMCXTypes::EVERY_VOXEL && !c.EveryVoxel)
          {
            continue;
          }
          const EditResult edit = MeasureTransferFunctionEdit(index, tf, camera, size,
            strategy == vtkMCXTypes::VIEW_ORDERED ? viewOrderedM : m, strategy, reference,
            quick ? 3 : 9);
          edits << Quoted(c.Name) << ',' << size << ','
                << (strategy == vtkMCXTypes::HYBRID           ? "sampled"
                       : strategy == vtkMCXTypes::EVERY_VOXEL ? "every voxel"
                                                                     : "view ordered")
                << ',' << edit.Points << ',' << 1000 * edit.FirstRenderSeconds << ','
                << edit.MedianMilliseconds << ',' << edit.Errors[0] << ',' << edit.Errors[1]
                << '\n';
          nonsense += std::isfinite(edit.Errors[0]) && std::isfinite(edit.Errors[1]) ? 0 : 1;
        }
      }
      std::cout << "  " << size << "^2 done" << std::endl;
    }
    std::remove(mha.c_str());
    volumes << Quoted(c.Name) << ',' << dims[0] << 'x' << dims[1] << 'x' << dims[2] << ','
            << volume->GetNumberOfPoints() << ',' << indexSeconds << ','
            << mcxbench::PeakResidentMegabytes() << '\n';
  }
  PrintSummary(summary);
  std::cout << "wrote " << output << std::endl;
  if (nonsense > 0)
  {
    std::cerr << nonsense << " runs failed or gave non-finite errors" << std::endl;
    return 1;
  }
  return 0;
}
