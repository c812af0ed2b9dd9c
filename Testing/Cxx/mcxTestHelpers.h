// Shared helpers for the tests: small synthetic volumes and image metrics.
#ifndef mcxTestHelpers_h
#define mcxTestHelpers_h

#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMCXPointSampler.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

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

/// The sum of an image's line integrals over its pixels (times the pixel
/// area: the mass the image holds).
inline double LineIntegralSum(vtkImageData* image)
{
  vtkDataArray* values = LineIntegral(image);
  double sum = 0;
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    sum += values->GetTuple1(i);
  }
  return sum;
}

/// The sum of the squares of an image's line integrals (the norm of a
/// relative RMS error).
inline double LineIntegralSquares(vtkImageData* image)
{
  vtkDataArray* values = LineIntegral(image);
  double sum = 0;
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    sum += values->GetTuple1(i) * values->GetTuple1(i);
  }
  return sum;
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

/// Display coordinates of a world point in a width x height image of the
/// camera, from VTK's own composite projection matrix (pixel i covers
/// [i, i + 1), as in vtkRenderer::WorldToDisplay); false behind the eye. An
/// independent check of the projectors' camera-to-detector code.
inline bool DisplayCoordinates(
  vtkCamera* camera, int width, int height, const double x[3], double display[2])
{
  vtkMatrix4x4* m =
    camera->GetCompositeProjectionTransformMatrix(static_cast<double>(width) / height, -1, 1);
  const double in[4] = { x[0], x[1], x[2], 1.0 };
  double out[4];
  m->MultiplyPoint(in, out);
  if (!(out[3] > 0))
  {
    return false;
  }
  display[0] = 0.5 * (out[0] / out[3] + 1.0) * width;
  display[1] = 0.5 * (out[1] / out[3] + 1.0) * height;
  return true;
}

/// The factor f = D^2 s / z^3 by which a perspective view scales a sample's
/// count (D the focal distance, z the depth and s the distance of the point
/// from the eye: the Jacobian of the central projection onto the focal
/// plane, times the ray length per depth); in a parallel view the ray length
/// per depth alone, 1 / cos of the rays' angle to the view (1 unless sheared).
inline double PerspectiveWeight(vtkCamera* camera, const double x[3])
{
  if (camera->GetParallelProjection())
  {
    // 1 / cos of the rays' angle to the view direction: a ray is the set of
    // world points VTK's matrix sends to one screen point, here the two at
    // normalized depths -1 and 1.
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(camera->GetCompositeProjectionTransformMatrix(1.0, -1, 1), inverse);
    const double nearPoint[4] = { 0.1, 0.2, -1, 1 }, farPoint[4] = { 0.1, 0.2, 1, 1 };
    double a[4], b[4], ray[3];
    inverse->MultiplyPoint(nearPoint, a);
    inverse->MultiplyPoint(farPoint, b);
    for (int k = 0; k < 3; ++k)
    {
      ray[k] = b[k] / b[3] - a[k] / a[3];
    }
    vtkMath::Normalize(ray);
    return 1.0 / std::fabs(vtkMath::Dot(ray, camera->GetDirectionOfProjection()));
  }
  double eye[3], w[3];
  camera->GetPosition(eye);
  camera->GetDirectionOfProjection(w);
  const double* shear = camera->GetViewShear();
  if (camera->GetUseOffAxisProjection() || shear[0] != 0 || shear[1] != 0)
  {
    // Off the camera's position: the centre of projection is the world
    // point VTK's matrix sends to clip coordinates (0, 0, 1, 0); depth grows
    // along clip w's row.
    vtkMatrix4x4* m = camera->GetCompositeProjectionTransformMatrix(1.0, -1, 1);
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(m, inverse);
    const double centre[4] = { 0, 0, 1, 0 };
    double h[4];
    inverse->MultiplyPoint(centre, h);
    const double norm = std::sqrt(m->GetElement(3, 0) * m->GetElement(3, 0) +
      m->GetElement(3, 1) * m->GetElement(3, 1) + m->GetElement(3, 2) * m->GetElement(3, 2));
    for (int a = 0; a < 3; ++a)
    {
      eye[a] = h[a] / h[3];
      w[a] = m->GetElement(3, a) / norm;
    }
  }
  const double d[3] = { x[0] - eye[0], x[1] - eye[1], x[2] - eye[2] };
  const double z = d[0] * w[0] + d[1] * w[1] + d[2] * w[2];
  const double s = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double focal = camera->GetDistance();
  return focal * focal * s / (z * z * z);
}

/// Second moments of the per-sample weight f over a cloud drawn from the
/// sampling distribution: MeanSquare = E[f^2 1{seen}], and per pixel
/// E[f^2 1{in pixel}], with pixels found by DisplayCoordinates and samples
/// nearer than the camera's near plane unseen. The variance of a pixel
/// estimate of M samples of weight W / M is at most W^2 E[f^2 1{pixel}] /
/// (A^2 M) (A the pixel area): the bound a perspective image is held to.
struct WeightMoments
{
  double MeanSquare = 0;
  std::vector<double> PixelMeanSquare;
};

inline WeightMoments MeasureWeights(vtkPoints* points, vtkCamera* camera, int width, int height)
{
  WeightMoments moments;
  moments.PixelMeanSquare.assign(static_cast<std::size_t>(width) * height, 0.0);
  const double* eye = camera->GetPosition();
  const double* w = camera->GetDirectionOfProjection();
  const double nearPlane = camera->GetClippingRange()[0];
  const double n = static_cast<double>(points->GetNumberOfPoints());
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    const double* x = points->GetPoint(i);
    double display[2];
    const double depth = (x[0] - eye[0]) * w[0] + (x[1] - eye[1]) * w[1] + (x[2] - eye[2]) * w[2];
    if ((!camera->GetParallelProjection() && !(depth >= nearPlane)) ||
      !DisplayCoordinates(camera, width, height, x, display) || !(display[0] >= 0) ||
      !(display[0] < width) || !(display[1] >= 0) || !(display[1] < height))
    {
      continue;
    }
    const double f = PerspectiveWeight(camera, x);
    moments.MeanSquare += f * f / n;
    moments.PixelMeanSquare[static_cast<std::size_t>(display[1]) * width +
      static_cast<std::size_t>(display[0])] += f * f / n;
  }
  return moments;
}

/// MeasureWeights on a plain Monte Carlo cloud of 2^exponent - 1 samples of
/// an index under a TF: the sampling distribution of every strategy.
inline WeightMoments MeasureSampledWeights(vtkAlgorithmOutput* index, vtkPiecewiseFunction* tf,
  vtkCamera* camera, int width, int height, int exponent = 21)
{
  vtkNew<vtkMCXPointSampler> sampler;
  sampler->SetInputConnection(index);
  sampler->SetTransferFunction(tf);
  sampler->SetStrategy(vtkMCXTypes::MONTE_CARLO);
  sampler->SetDeposit(vtkMCXTypes::POINT); // positions with their kernel offsets
  sampler->SetSampleExponent(exponent);
  sampler->SetSeed(11);
  sampler->Update();
  return MeasureWeights(sampler->GetOutput()->GetPoints(), camera, width, height);
}

/// The expected relative RMS error of an image of M samples whose weights
/// have the second moment meanSquare = E[f^2 1{seen}]: the pixel variances
/// W^2 E[f^2 1{pixel}] / (A^2 M) summed over the image (each sample lands in
/// one pixel), over sum I^2 of the reference. Parallel views have f = 1.
inline double ExpectedRelativeRMSOfWeights(
  vtkImageData* reference, double integral, double pixelArea, double samples, double meanSquare)
{
  vtkDataArray* b = LineIntegral(reference);
  const double scale = MaximumAbsolute(b);
  double squares = 0;
  for (vtkIdType i = 0; i < b->GetNumberOfTuples(); ++i)
  {
    squares += (b->GetTuple1(i) / scale) * (b->GetTuple1(i) / scale);
  }
  const double w = integral / scale / pixelArea;
  return std::sqrt(w * w * meanSquare / samples / squares);
}

/// The effective number of independent pixels (sum v)^2 / sum v^2 of pixel
/// variances v: a sum of n squared errors of variances v has a relative
/// standard deviation of sqrt(2 / n), so a relative RMS error, or an
/// estimate of it, has a relative spread of about 1 / sqrt(2 n).
inline double EffectivePixelCount(const std::vector<double>& variances)
{
  double sum = 0, squares = 0;
  for (double v : variances)
  {
    sum += v;
    squares += v * v;
  }
  return squares > 0 ? sum * sum / squares : 0.0;
}

/// Pixel variances proportional to the reference (a parallel view: a pixel
/// count is binomial with mean proportional to I).
inline std::vector<double> ParallelPixelVariances(vtkImageData* reference)
{
  vtkDataArray* b = LineIntegral(reference);
  std::vector<double> variances(static_cast<std::size_t>(b->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < b->GetNumberOfTuples(); ++i)
  {
    variances[static_cast<std::size_t>(i)] = std::max(0.0, b->GetTuple1(i));
  }
  return variances;
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

/// Keeps the first error event of an object (and stops VTK printing it).
struct FirstError
{
  std::string Text;
  vtkNew<vtkCallbackCommand> Command;
  // Observed until this goes out of scope: a later error of the object
  // must not reach a Text that no longer exists.
  vtkWeakPointer<vtkObject> Observed;
  unsigned long Tag = 0;

  explicit FirstError(vtkObject* object)
  {
    this->Command->SetClientData(&this->Text);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long, void* data, void* message)
      {
        std::string& text = *static_cast<std::string*>(data);
        if (text.empty() && message)
        {
          text = static_cast<const char*>(message);
        }
      });
    this->Tag = object->AddObserver(vtkCommand::ErrorEvent, this->Command);
    this->Observed = object;
  }
  ~FirstError()
  {
    if (this->Observed)
    {
      this->Observed->RemoveObserver(this->Tag);
    }
  }
  FirstError(const FirstError&) = delete;
  FirstError& operator=(const FirstError&) = delete;
};

inline double FieldValue(vtkDataObject* data, const char* name)
{
  return data->GetFieldData()->GetArray(name)->GetTuple1(0);
}

} // namespace mcxtest

#endif
