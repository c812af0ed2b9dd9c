// Shared helpers for the tests: small synthetic volumes and image metrics.
#ifndef mcxTestHelpers_h
#define mcxTestHelpers_h

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

namespace mcxtest
{

/// An nx x ny x nz volume of the given VTK type, value(i, j, k) per voxel.
inline vtkSmartPointer<vtkImageData> MakeVolume(int type, const int dims[3],
  const std::function<double(int, int, int)>& value, const double spacing[3] = nullptr,
  const double origin[3] = nullptr)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims[0], dims[1], dims[2]);
  if (spacing)
  {
    image->SetSpacing(spacing[0], spacing[1], spacing[2]);
  }
  if (origin)
  {
    image->SetOrigin(origin[0], origin[1], origin[2]);
  }
  image->AllocateScalars(type, 1);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  scalars->SetName("density");
  vtkIdType id = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        scalars->SetComponent(id++, 0, value(i, j, k));
      }
    }
  }
  return image;
}

/// A smooth blob with a denser core: a volume with structure at several scales.
inline double Phantom(int i, int j, int k, const int dims[3])
{
  const double x = (i + 0.5) / dims[0] - 0.5, y = (j + 0.5) / dims[1] - 0.5,
               z = (k + 0.5) / dims[2] - 0.5;
  const double r2 = x * x + y * y + z * z;
  double v = r2 < 0.16 ? 100.0 : 0.0;
  if ((x - 0.1) * (x - 0.1) + y * y + (z + 0.05) * (z + 0.05) < 0.01)
  {
    v = 400.0;
  }
  return v + ((i * 7 + j * 3 + k * 5) % 11);
}

inline vtkDataArray* LineIntegral(vtkImageData* image)
{
  return image->GetPointData()->GetArray("LineIntegral");
}

/// Largest |value| of an image (a scale that keeps sums of squares finite).
inline double MaximumAbsolute(vtkDataArray* values)
{
  double largest = 0;
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    largest = std::max(largest, std::fabs(values->GetTuple1(i)));
  }
  return largest > 0 ? largest : 1.0;
}

/// sqrt(sum (a - b)^2 / sum b^2) over two images' LineIntegral arrays.
inline double RelativeRMS(vtkImageData* estimate, vtkImageData* reference)
{
  vtkDataArray* a = LineIntegral(estimate);
  vtkDataArray* b = LineIntegral(reference);
  const double scale = MaximumAbsolute(b);
  double difference = 0, norm = 0;
  for (vtkIdType i = 0; i < b->GetNumberOfTuples(); ++i)
  {
    const double d = a->GetTuple1(i) / scale - b->GetTuple1(i) / scale;
    difference += d * d;
    norm += (b->GetTuple1(i) / scale) * (b->GetTuple1(i) / scale);
  }
  return std::sqrt(difference / norm);
}

/// Expected relative RMS error of a parallel-view Monte Carlo image of M
/// samples: each pixel count is binomial with p = I A / Integral, so
/// E[sum (I_hat - I)^2] = sum I (Integral / (A M)) (1 - p) <= Integral sum I / (A M).
/// For perspective views fMax bounds the per-sample weight factor.
inline double ExpectedRelativeRMS(
  vtkImageData* reference, double integral, double pixelArea, double samples, double fMax = 1.0)
{
  vtkDataArray* b = LineIntegral(reference);
  const double scale = MaximumAbsolute(b);
  double sum = 0, squares = 0;
  for (vtkIdType i = 0; i < b->GetNumberOfTuples(); ++i)
  {
    sum += b->GetTuple1(i) / scale;
    squares += (b->GetTuple1(i) / scale) * (b->GetTuple1(i) / scale);
  }
  return std::sqrt(fMax * (integral / scale) * sum / (pixelArea * samples * squares));
}

/// Counts the executions of an algorithm (its StartEvents).
struct ExecutionCounter
{
  int Count = 0;
  vtkNew<vtkCallbackCommand> Command;

  explicit ExecutionCounter(vtkAlgorithm* algorithm)
  {
    this->Command->SetClientData(&this->Count);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long, void* data, void*) { ++*static_cast<int*>(data); });
    algorithm->AddObserver(vtkCommand::StartEvent, this->Command);
  }
};

inline double FieldValue(vtkDataObject* data, const char* name)
{
  return data->GetFieldData()->GetArray(name)->GetTuple1(0);
}

} // namespace mcxtest

#endif
