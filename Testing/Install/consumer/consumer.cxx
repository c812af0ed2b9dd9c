// A DRR of a synthetic volume through the installed MonteCarloXRay package:
// index -> point sampler -> projector, with a vtkCamera.
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkMCXDensityIndex.h>
#include <vtkMCXPointSampler.h>
#include <vtkMCXProjector.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>

#include <cmath>
#include <iostream>

int main()
{
  // A 32^3 CT-like volume in HU: air around a water sphere.
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(32, 32, 32);
  volume->SetSpacing(2.0, 2.0, 2.0);
  volume->AllocateScalars(VTK_SHORT, 1);
  auto* hu = static_cast<short*>(volume->GetScalarPointer());
  for (int k = 0; k < 32; ++k)
    for (int j = 0; j < 32; ++j)
      for (int i = 0; i < 32; ++i)
        *hu++ = (i - 16) * (i - 16) + (j - 16) * (j - 16) + (k - 16) * (k - 16) < 100 ? 0 : -1000;

  vtkNew<vtkMCXDensityIndex> index; // once per volume
  index->SetInputData(volume);

  vtkNew<vtkPiecewiseFunction> tf; // HU -> attenuation-like weight
  tf->AddPoint(-1000, 0.0);
  tf->AddPoint(0, 1.0);

  vtkNew<vtkMCXPointSampler> sampler; // re-runs on every TF change, O(M)
  sampler->SetInputConnection(index->GetOutputPort());
  sampler->SetTransferFunction(tf);
  sampler->SetNumberOfSamples(1 << 20);

  vtkNew<vtkCamera> camera;
  camera->SetFocalPoint(31, 31, 31);
  camera->SetPosition(31, -400, 31);
  camera->SetViewUp(0, 0, 1);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(40);

  vtkNew<vtkMCXProjector> projector; // re-runs on every camera change
  projector->SetInputConnection(sampler->GetOutputPort());
  projector->SetCamera(camera);
  projector->SetImageSize(128, 128);
  projector->Update();

  vtkImageData* image = projector->GetOutput();
  vtkDataArray* values = image->GetPointData()->GetArray("LineIntegral");
  double sum = 0;
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    sum += values->GetTuple1(i);
  }
  const double integral = image->GetFieldData()->GetArray("Integral")->GetTuple1(0);
  const double area = image->GetSpacing()[0] * image->GetSpacing()[1];
  std::cout << "peak line integral " << values->GetRange()[1] << " mm, total " << sum * area
            << " mm^3 of " << integral << " mm^3" << std::endl;
  // The image holds every sample; the sphere's diameter is about 40 mm.
  const bool ok = std::fabs(sum * area - integral) < 1e-9 * integral &&
    values->GetRange()[1] > 30 && values->GetRange()[1] < 50;
  return ok ? 0 : 1;
}
