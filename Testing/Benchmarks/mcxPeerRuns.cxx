#include "mcxPeerRuns.h"

#include "mcxAccuracyMeasures.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

namespace mcxbench
{
namespace
{
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

}

PeerRun RunPlastimatch(const std::string& mha, const std::string& output, const double iso[3],
  int size, const ConeBeam& beam, vtkImageData* reference)
{
  PeerRun peer;
  std::vector<double> render, process;
  const std::string prefix = output + "/plastimatch_" + std::to_string(size) + "_";
  const std::string log = prefix + "log.txt";
  for (int repetition = 0; repetition < 3; ++repetition)
  {
    std::ostringstream command;
    command << "plastimatch drr -I " << mha << " -O " << prefix << " -t pfm -i exact -r \"" << size
            << " " << size << "\" -z \"" << beam.DetectorSize << " " << beam.DetectorSize
            << "\" --sad " << beam.SourceToIsocentre << " --sid " << beam.SourceToDetector
            << " -o \"" << iso[0] << " " << iso[1] << " " << iso[2] << "\" > " << log << " 2>&1";
    const Clock::time_point start = Clock::now();
    const int status = std::system(command.str().c_str());
    process.push_back(Since(start));
    const double seconds = ReadTotalTime(log);
    std::vector<double> values;
    if (status != 0 || seconds < 0 || !ReadPlastimatchPFM(prefix + "0000.pfm", size, values))
    {
      std::cerr << "plastimatch failed (" << command.str() << ")" << std::endl;
      return peer;
    }
    render.push_back(seconds);
    peer.Error = RelativeRMS(values, reference);
  }
  for (const char* suffix : { "0000.pfm", "0000.txt", "log.txt" })
  {
    std::remove((prefix + suffix).c_str());
  }
  peer.RenderSeconds = Median(render);
  peer.ProcessSeconds = Median(process);
  peer.Done = true;
  return peer;
}

bool RenderWithVTK(vtkImageData* volume, vtkPiecewiseFunction* tf, vtkCamera* camera, int size,
  vtkImageData* reference, double& seconds, double& error)
{
  if (!std::getenv("DISPLAY"))
  {
    return false;
  }
  vtkDataArray* exact = reference->GetPointData()->GetArray(vtkMCXTypes::LineIntegralName());
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
    error = RelativeRMS(values, reference);
    return true;
  }
  return false;
}

}
