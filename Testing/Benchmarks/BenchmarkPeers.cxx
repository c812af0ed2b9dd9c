// MonteCarloXRay against plastimatch drr (the peer DRR tool) in one run, with
// the same cone-beam geometry and HU-to-attenuation map, render time only: our
// index is built once per volume (its time is reported apart), and
// plastimatch's own "Total time" leaves out its start-up and loading. Volumes:
// the CT body, the CT chest, and the CT chest upsampled (linear) past 400 M
// voxels, where plastimatch's cost grows with the voxels and ours does not.
// For each volume and image size (256^2, 512^2): the exact reference,
// plastimatch `exact`, and our point and footprint deposits at growing M, all
// against the reference; the time each deposit takes to reach 2 % and 1 %;
// and the latency of a TF edit to a complete 2 % image in the interactive
// mapper (a stored footprint cloud, 256^2). VTK's GPU ray-cast mapper
// (additive, software GL) is measured beside them on the small volumes.
// Writes volumes.csv, peers.csv, time-to-target.csv and tf-edit.csv.
//
// Usage: BenchmarkPeers [--quick] [--output DIR] [--data DIR]
//   --quick: small images, sample counts and "large" volume (a smoke run).
#include "mcxAccuracyMeasures.h"
#include "mcxTransferFunctionSpec.h"
#include "mcxVolumeReader.h"

#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"
#include "vtkMCXXRayMapper.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkImageInterpolator.h"
#include "vtkImageResize.h"
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
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"
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
using mcxbench::Since;

// Hounsfield units to plastimatch's attenuation, mu = 0.0022 (1 + HU/1000)
// per mm (measured from its output), clamped at air.
const char* const AttenuationTF = "-1000:0,4000:0.011";
const double Targets[2] = { 0.02, 0.01 };
const double SourceToIsocentre = 1000, SourceToDetector = 1500, DetectorSize = 600;

struct VolumeCase
{
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
  camera->SetPosition(iso[0] + SourceToIsocentre, iso[1], iso[2]);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(
    2 * vtkMath::DegreesFromRadians(std::atan(DetectorSize / 2 / SourceToDetector)));
  camera->SetClippingRange(1.0, 10 * SourceToIsocentre);
  return camera;
}

// Linear upsampling until the voxel count reaches least (the same bounds).
vtkSmartPointer<vtkImageData> Upsample(vtkImageData* volume, double least)
{
  int dims[3];
  volume->GetDimensions(dims);
  const double factor =
    std::cbrt(least / static_cast<double>(volume->GetNumberOfPoints())) * (1 + 1e-3);
  vtkNew<vtkImageInterpolator> linear;
  linear->SetInterpolationModeToLinear();
  vtkNew<vtkImageResize> resize;
  resize->SetInputData(volume);
  resize->SetInterpolator(linear);
  resize->SetOutputDimensions(static_cast<int>(std::ceil(dims[0] * factor)),
    static_cast<int>(std::ceil(dims[1] * factor)), static_cast<int>(std::ceil(dims[2] * factor)));
  resize->Update();
  vtkSmartPointer<vtkImageData> output = resize->GetOutput();
  return output;
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

// plastimatch drr -i exact: its own render time ("Total time: ... secs",
// after loading) and the whole process's, medians of 3, and its error.
struct PeerRun
{
  double RenderSeconds = 0;
  double ProcessSeconds = 0;
  double Error = 1;
  bool Done = false;
};

double ReadTotalTime(const std::string& log)
{
  std::ifstream in(log);
  std::string line;
  double seconds = -1;
  while (std::getline(in, line))
  {
    const std::size_t at = line.find("Total time");
    if (at != std::string::npos)
    {
      const std::size_t number = line.find_first_of("0123456789", at);
      if (number != std::string::npos)
      {
        seconds = std::atof(line.c_str() + number);
      }
    }
  }
  return seconds;
}

PeerRun RunPlastimatch(const std::string& mha, const std::string& output, const double iso[3],
  int size, vtkImageData* reference)
{
  PeerRun peer;
  std::vector<double> render, process;
  const std::string prefix = output + "/plastimatch_" + std::to_string(size) + "_";
  const std::string log = prefix + "log.txt";
  for (int repetition = 0; repetition < 3; ++repetition)
  {
    std::ostringstream command;
    command << "plastimatch drr -I " << mha << " -O " << prefix << " -t pfm -i exact -r \"" << size
            << " " << size << "\" -z \"" << DetectorSize << " " << DetectorSize << "\" --sad "
            << SourceToIsocentre << " --sid " << SourceToDetector << " -o \"" << iso[0] << " "
            << iso[1] << " " << iso[2] << "\" > " << log << " 2>&1";
    const Clock::time_point start = Clock::now();
    const int status = std::system(command.str().c_str());
    process.push_back(Since(start));
    const double seconds = ReadTotalTime(log);
    std::vector<double> values;
    if (status != 0 || seconds < 0 ||
      !mcxbench::ReadPlastimatchPFM(prefix + "0000.pfm", size, values))
    {
      std::cerr << "plastimatch failed (" << command.str() << ")" << std::endl;
      return peer;
    }
    render.push_back(seconds);
    peer.Error = mcxbench::RelativeRMS(values, reference);
  }
  for (const char* suffix : { "0000.pfm", "0000.txt", "log.txt" })
  {
    std::remove((prefix + suffix).c_str());
  }
  peer.RenderSeconds = mcxbench::Median(render);
  peer.ProcessSeconds = mcxbench::Median(process);
  peer.Done = true;
  return peer;
}

// VTK's GPU ray-cast mapper in additive blend mode (software GL under Xvfb
// here): an 8-bit, clamped sum of the opacity along each ray. The opacity TF
// is our TF scaled down until nothing saturates; one least-squares gain then
// maps the grey levels to line integrals. False without a display.
bool RenderWithVTK(vtkImageData* volume, vtkPiecewiseFunction* tf, vtkCamera* camera, int size,
  vtkImageData* reference, double& seconds, double& error)
{
  if (!std::getenv("DISPLAY"))
  {
    return false;
  }
  vtkDataArray* exact =
    reference->GetPointData()->GetArray(vtkMCXTypes::LineIntegralName());
  double scale = 1.0;
  for (int attempt = 0; attempt < 12; ++attempt, scale /= 4)
  {
    vtkNew<vtkPiecewiseFunction> opacity;
    for (int n = 0; n < tf->GetSize(); ++n)
    {
      double node[4];
      tf->GetNodeValue(n, node);
      opacity->AddPoint(node[0], std::min(1.0, node[1] * scale));
    }
    vtkNew<vtkColorTransferFunction> white;
    white->AddRGBPoint(tf->GetRange()[0], 1, 1, 1);
    white->AddRGBPoint(tf->GetRange()[1], 1, 1, 1);
    vtkNew<vtkVolumeProperty> property;
    property->SetScalarOpacity(opacity);
    property->SetColor(white);
    property->SetInterpolationTypeToLinear();
    vtkNew<vtkGPUVolumeRayCastMapper> mapper;
    mapper->SetInputData(volume);
    mapper->SetBlendModeToAdditive();
    vtkNew<vtkVolume> prop;
    prop->SetMapper(mapper);
    prop->SetProperty(property);
    vtkNew<vtkRenderer> renderer;
    renderer->AddVolume(prop);
    renderer->SetActiveCamera(camera);
    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->AddRenderer(renderer);
    window->SetSize(size, size);
    window->Render(); // compiles shaders, uploads the volume
    const Clock::time_point start = Clock::now();
    window->Render();
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->SetInputBufferTypeToRGB();
    grab->ReadFrontBufferOff();
    grab->Update();
    seconds = Since(start);
    vtkDataArray* grey = grab->GetOutput()->GetPointData()->GetScalars();
    if (grey->GetRange(0)[1] >= 255)
    {
      continue; // saturated: scale the opacity down
    }
    double product = 0, squares = 0;
    for (vtkIdType i = 0; i < grey->GetNumberOfTuples(); ++i)
    {
      product += grey->GetComponent(i, 0) * exact->GetTuple1(i);
      squares += grey->GetComponent(i, 0) * grey->GetComponent(i, 0);
    }
    const double gain = squares > 0 ? product / squares : 0.0;
    std::vector<double> values(static_cast<std::size_t>(grey->GetNumberOfTuples()));
    for (vtkIdType i = 0; i < grey->GetNumberOfTuples(); ++i)
    {
      values[static_cast<std::size_t>(i)] = gain * grey->GetComponent(i, 0);
    }
    error = mcxbench::RelativeRMS(values, reference);
    return true;
  }
  return false;
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
}

int main(int argc, char* argv[])
{
  mcxbench::BenchmarkArguments arguments;
  if (!mcxbench::ParseArguments(argc, argv, "BenchmarkPeers", MCXRAY_SHARED_DATA_DIR, arguments))
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
    { "CT body", data + "/ct_body_totalseg.nii.gz", 0, true, true },
    { "CT chest", data + "/ct_chest_cta_totalseg.nii.gz", 0, true, true },
    { quick ? "CT chest upsampled past 8 M voxels" : "CT chest upsampled past 400 M voxels",
      data + "/ct_chest_cta_totalseg.nii.gz", quick ? 8.0e6 : 4.0e8, false, false },
  };

  std::ofstream volumes(output + "/volumes.csv");
  volumes << "volume,dimensions,voxels,index_seconds,peak_resident_megabytes\n";
  std::ofstream peers(output + "/peers.csv");
  peers << "volume,size,tool,method,samples,seconds,error\n";
  std::ofstream targets(output + "/time-to-target.csv");
  targets << "volume,size,target,point_samples,point_seconds,point_error,footprint_samples,"
             "footprint_seconds,footprint_error,plastimatch_exact_seconds,plastimatch_error,"
             "speedup\n";
  std::ofstream edits(output + "/tf-edit.csv");
  edits << "volume,size,cloud,points,first_render_ms,median_ms,error,error_after_edit\n";

  int nonsense = 0; // failed peers, non-finite errors: the run must fail loudly
  for (const VolumeCase& c : cases)
  {
    vtkSmartPointer<vtkImageData> volume = mcxbench::ReadInStoredFrame(c.File, c.Name);
    if (!volume)
    {
      continue;
    }
    std::string error;
    if (c.LeastVoxels > 0)
    {
      volume = Upsample(volume, c.LeastVoxels);
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
        peer = RunPlastimatch(mha, output, camera->GetFocalPoint(), size, reference);
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
      // Each deposit's sweep; the first run that reaches each target.
      Run reached[2][2]; // [deposit][target]
      bool found[2][2] = { { false, false }, { false, false } };
      const int deposits[2] = { vtkMCXTypes::POINT, vtkMCXTypes::FOOTPRINT };
      for (int d = 0; d < 2; ++d)
      {
        const std::array<int, 2>& span = d == 0 ? pointRange : footprintRange;
        Run last;
        for (int m = span[0]; m <= span[1] && !found[d][1]; ++m)
        {
          last = Render(index, tf, camera, size, m, deposits[d], reference);
          peers << Quoted(c.Name) << ',' << size << ",MonteCarloXRay,"
                << (d == 0 ? "hybrid point" : "hybrid footprint") << ',' << last.Samples << ','
                << last.Seconds << ',' << last.Error << '\n';
          nonsense += std::isfinite(last.Error) && last.Seconds > 0 ? 0 : 1;
          for (int t = 0; t < 2; ++t)
          {
            if (!found[d][t] && last.Error <= Targets[t])
            {
              reached[d][t] = last;
              found[d][t] = true;
            }
          }
        }
        for (int t = 0; t < 2; ++t)
        {
          reached[d][t] = found[d][t] ? reached[d][t] : last; // capped: the last run
        }
      }
      if (c.EveryVoxel)
      {
        // The fused DRR of every voxel once: one run, no sample count.
        const Run every = Render(index, tf, camera, size, 0, vtkMCXTypes::FOOTPRINT,
          reference, vtkMCXTypes::EVERY_VOXEL);
        peers << Quoted(c.Name) << ',' << size << ",MonteCarloXRay,every voxel footprint,"
              << every.Samples << ',' << every.Seconds << ',' << every.Error << '\n';
        nonsense += std::isfinite(every.Error) && every.Seconds > 0 ? 0 : 1;
      }
      for (int t = 0; t < 2; ++t)
      {
        targets << Quoted(c.Name) << ',' << size << ',' << Targets[t];
        for (int d = 0; d < 2; ++d)
        {
          const Run& run = reached[d][t];
          targets << ',' << (found[d][t] ? "" : ">") << static_cast<long long>(run.Samples) << ','
                  << (found[d][t] ? "" : ">") << run.Seconds << ',' << run.Error;
        }
        if (peer.Done)
        {
          // Against the faster deposit that reached the target; where none
          // did, an upper bound from the last runs ("<").
          const bool any = found[0][t] || found[1][t];
          double ours = std::numeric_limits<double>::infinity();
          for (int d = 0; d < 2; ++d)
          {
            ours = found[d][t] || !any ? std::min(ours, reached[d][t].Seconds) : ours;
          }
          const double speedup = peer.RenderSeconds / ours;
          nonsense += std::isfinite(speedup) && speedup > 0 ? 0 : 1;
          targets << ',' << peer.RenderSeconds << ',' << peer.Error << ',' << (any ? "" : "<")
                  << speedup << '\n';
        }
        else
        {
          targets << ",,,\n";
        }
      }
      // The interactive path at the smallest size: the footprint count that
      // reached 2 %, every voxel of non-zero weight once (where they are
      // fewer than 2^30 points), and the view-ordered count that reaches 2 %.
      if (size == sizes.front())
      {
        const int m = static_cast<int>(std::lround(std::log2(reached[1][0].Samples + 1)));
        const int viewOrderedM = ViewOrderedExponentForTarget(
          index, tf, camera, size, reference, Targets[0], footprintRange[0], m);
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
  std::cout << "wrote " << output << std::endl;
  if (nonsense > 0)
  {
    std::cerr << nonsense << " runs failed or gave non-finite errors" << std::endl;
    return 1;
  }
  return 0;
}
