#include "mcxAccuracyMeasures.h"

#include "mcxVolumeReader.h"

#include "vtkMCXReferenceProjector.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>

#include <sys/resource.h>

namespace mcxbench
{

double Since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double Median(std::vector<double> values)
{
  if (values.empty())
  {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

double FieldValue(vtkDataObject* data, const char* name)
{
  return data->GetFieldData()->GetArray(name)->GetTuple1(0);
}

std::vector<double> Values(vtkImageData* image)
{
  vtkDataArray* a = image->GetPointData()->GetArray(vtkMCXTypes::LineIntegralName());
  std::vector<double> values(static_cast<std::size_t>(a->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    values[static_cast<std::size_t>(i)] = a->GetTuple1(i);
  }
  return values;
}

double RelativeRMS(const std::vector<double>& estimate, vtkImageData* reference)
{
  vtkDataArray* b = reference->GetPointData()->GetArray(vtkMCXTypes::LineIntegralName());
  double difference = 0, norm = 0;
  for (vtkIdType i = 0; i < b->GetNumberOfTuples(); ++i)
  {
    const double d = estimate[static_cast<std::size_t>(i)] - b->GetTuple1(i);
    difference += d * d;
    norm += b->GetTuple1(i) * b->GetTuple1(i);
  }
  return std::sqrt(difference / norm);
}

vtkSmartPointer<vtkImageData> Reference(vtkAlgorithm* index, vtkPiecewiseFunction* tf,
  vtkCamera* camera, int size, double tolerance, int maximumSubdivision, double& seconds)
{
  vtkNew<vtkMCXReferenceProjector> reference;
  reference->SetInputConnection(index->GetOutputPort());
  reference->SetTransferFunction(tf);
  reference->SetCamera(camera);
  reference->SetImageSize(size, size);
  reference->SetRelativeTolerance(tolerance);
  reference->SetMaximumSubdivision(maximumSubdivision);
  const Clock::time_point start = Clock::now();
  reference->Update();
  seconds = Since(start);
  return reference->GetOutput();
}

vtkSmartPointer<vtkMCXProjector> MakeProjector(vtkAlgorithm* index, vtkPiecewiseFunction* tf,
  vtkCamera* camera, int size, int exponent, int strategy, int deposit)
{
  auto projector = vtkSmartPointer<vtkMCXProjector>::New();
  projector->SetDeposit(deposit);
  projector->SetInputConnection(index->GetOutputPort());
  projector->SetTransferFunction(tf);
  projector->SetCamera(camera);
  projector->SetImageSize(size, size);
  projector->SetSampleExponent(exponent);
  projector->SetStrategy(strategy);
  return projector;
}

bool ReadPlastimatchPFM(const std::string& path, int size, std::vector<double>& values)
{
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int width = 0, height = 0;
  double scale = 0;
  in >> magic >> width >> height >> scale;
  in.get();
  if (!in || magic != "Pf" || width != size || height != size)
  {
    return false;
  }
  std::vector<float> raw(static_cast<std::size_t>(width) * height);
  in.read(
    reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(raw.size() * sizeof(float)));
  if (!in)
  {
    return false;
  }
  values.resize(raw.size());
  for (int r = 0; r < height; ++r)
  {
    for (int c = 0; c < width; ++c)
    {
      values[static_cast<std::size_t>(height - 1 - r) * width + c] =
        raw[static_cast<std::size_t>(r) * width + c];
    }
  }
  return true;
}

bool ParseArguments(int argc, char* argv[], const char* program, const std::string& sharedData,
  BenchmarkArguments& arguments)
{
  arguments.Data = sharedData;
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--quick") == 0)
      arguments.Quick = true;
    else if (std::strcmp(argv[i], "--output") == 0 && i + 1 < argc)
      arguments.Output = argv[++i];
    else if (std::strcmp(argv[i], "--data") == 0 && i + 1 < argc)
      arguments.Data = argv[++i];
    else
    {
      std::cerr << "usage: " << program << " [--quick] [--output DIR] [--data DIR]" << std::endl;
      return false;
    }
  }
  vtksys::SystemTools::MakeDirectory(arguments.Output);
  return true;
}

vtkSmartPointer<vtkImageData> ReadInStoredFrame(const std::string& path, const std::string& name)
{
  std::string error;
  vtkSmartPointer<vtkImageData> volume = mcxio::ReadVolume(path, error);
  if (!volume)
  {
    std::cerr << "skipping " << name << ": " << error << std::endl;
    return nullptr;
  }
  volume->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, 1);
  return volume;
}

long PeakResidentMegabytes()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024;
}

}
