// The bundled CT head as a point cloud drawn by vtkMCXXRayMapper in an
// off-screen window: the scene of the render tests and the mapper benchmark.
#ifndef mcxHeadScene_h
#define mcxHeadScene_h

#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXXRayMapper.h"

#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkXMLImageDataReader.h"

namespace mcxtest
{

struct HeadScene
{
  vtkNew<vtkXMLImageDataReader> Reader;
  vtkNew<vtkMCXDensityIndex> Index;
  vtkNew<vtkPiecewiseFunction> TransferFunction;
  vtkNew<vtkMCXPointSampler> Sampler;
  vtkNew<vtkMCXXRayMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;

  /// 2^exponent - 1 points, a width x height window, a perspective camera
  /// looking along +y at the head's centre (parallel scale 90 mm).
  HeadScene(int exponent, int width, int height)
  {
    this->Reader->SetFileName(MCXRAY_TEST_DATA_DIR "/ct_head_headsq.vti");
    this->Index->SetInputConnection(this->Reader->GetOutputPort());
    this->TransferFunction->AddPoint(400, 0);
    this->TransferFunction->AddPoint(3926, 1);
    this->Sampler->SetInputConnection(this->Index->GetOutputPort());
    this->Sampler->ReusePointsOn(); // the mapper is the cloud's only consumer
    this->Sampler->SetTransferFunction(this->TransferFunction);
    this->Sampler->SetSampleExponent(exponent);
    this->Sampler->SetSeed(7);
    this->Sampler->SetDeposit(vtkMCXTypes::POINT); // the tests' baselines; footprint tests set it
    this->Mapper->SetInputConnection(this->Sampler->GetOutputPort());
    this->Volume->SetMapper(this->Mapper);
    this->Renderer->AddVolume(this->Volume);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(width, height);
    this->Window->AddRenderer(this->Renderer);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->SetFocalPoint(102, 102, 70);
    camera->SetPosition(102, -500, 70);
    camera->SetViewUp(0, 0, 1);
    camera->SetParallelScale(90);
    this->Renderer->ResetCameraClippingRange();
  }
};

} // namespace mcxtest

#endif
