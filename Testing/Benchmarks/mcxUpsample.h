// The large volumes of the benchmarks: a real CT resized linearly until it
// holds at least a given number of voxels (the same bounds), as
// BenchmarkPeers and BenchmarkKernels make their 400 M-voxel CT.
#ifndef mcxUpsample_h
#define mcxUpsample_h

#include "vtkImageData.h"
#include "vtkImageInterpolator.h"
#include "vtkImageResize.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <cmath>

namespace mcxbench
{
inline vtkSmartPointer<vtkImageData> Upsample(vtkImageData* volume, double least)
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
}

#endif
