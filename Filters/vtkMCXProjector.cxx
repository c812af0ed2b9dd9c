#include "vtkMCXProjector.h"

#include "mcxAccumulator.h"
#include "mcxBatchedFor.h"
#include "mcxIndexView.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkMCXProjector);

// Smallest pilot run of the target-accuracy controls: 2^16 - 1 samples.
static constexpr int PilotSampleExponent = 16;

namespace
{
// Thread-local fixed-point images summed at the end: integer addition makes
// the result independent of the order and the number of threads. Each holds
// two images, interleaved: all samples, and the samples of the first half
// (output index below Half), for the error estimate.
class ImageAccumulator
{
public:
  ImageAccumulator(std::size_t pixels, std::uint64_t half)
    : Pixels(pixels)
    , Half(half)
  {
  }

  mcx::FixedSum* Local()
  {
    std::vector<mcx::FixedSum>& buffer = this->Buffers.Local();
    if (buffer.empty())
    {
      buffer.assign(2 * this->Pixels, 0);
    }
    return buffer.data();
  }

  // The two sums of a pixel are neighbours, so both live in one cache line.
  void Add(mcx::FixedSum* image, std::uint64_t k, std::int64_t pixel, mcx::FixedSum increment) const
  {
    mcx::FixedSum* sums = image + 2 * pixel;
    sums[0] += increment;
    sums[1] += k < this->Half ? increment : 0;
  }

  /// Sums of all threads: all samples in [0, pixels), first half after.
  std::vector<mcx::FixedSum> Sum()
  {
    std::vector<mcx::FixedSum> total(2 * this->Pixels, 0);
    for (auto& buffer : this->Buffers)
    {
      for (std::size_t p = 0; p < this->Pixels; ++p)
      {
        total[p] += buffer[2 * p];
        total[this->Pixels + p] += buffer[2 * p + 1];
      }
    }
    return total;
  }

private:
  std::size_t Pixels;
  std::uint64_t Half;
  vtkSMPThreadLocal<std::vector<mcx::FixedSum>> Buffers;
};

template <typename IdType>
bool ProjectFromIndex(vtkAlgorithm* self, const mcx::IndexView& view, const mcx::TransferTable& table,
  mcx::Strategy strategy, mcx::Kernel kernel, vtkTypeUInt64 seed, unsigned m,
  const mcx::ProjectionGeometry& geometry, ImageAccumulator& accumulator, double progressBegin,
  double progressEnd)
{
  mcx::SampleSource<IdType> source = view.MakeSource<IdType>(table);
  source.Method = strategy;
  source.Reconstruction = kernel;
  source.Seed = seed;
  source.Exponent = m;
  double origin[3], matrix[9];
  view.SourceToWorld(origin, matrix);
  const mcx::PixelBinner binner(geometry, origin, matrix);
  return mcx::BatchedFor(self, source.NumberOfSamples(), progressBegin, progressEnd,
    [&](std::uint64_t b, std::uint64_t e) {
      mcx::FixedSum* image = accumulator.Local();
      auto sink = [&](std::uint64_t k, const double p[3]) {
        std::int64_t pixel;
        mcx::FixedSum increment;
        if (binner.Bin(p, pixel, increment))
        {
          accumulator.Add(image, k, pixel, increment);
        }
      };
      source.Generate(b, e, sink);
    });
}

template <typename Real>
bool ProjectPoints(vtkAlgorithm* self, const Real* points, std::uint64_t count,
  const mcx::ProjectionGeometry& geometry, ImageAccumulator& accumulator)
{
  const double origin[3] = { 0, 0, 0 };
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const mcx::PixelBinner binner(geometry, origin, identity);
  return mcx::BatchedFor(self, count, 0.0, 1.0, [&](std::uint64_t b, std::uint64_t e) {
    mcx::FixedSum* image = accumulator.Local();
    for (std::uint64_t i = b; i < e; ++i)
    {
      const double p[3] = { static_cast<double>(points[3 * i]), static_cast<double>(points[3 * i + 1]),
        static_cast<double>(points[3 * i + 2]) };
      std::int64_t pixel;
      mcx::FixedSum increment;
      if (binner.Bin(p, pixel, increment))
      {
        accumulator.Add(image, i, pixel, increment);
      }
    }
  });
}

double FieldValue(vtkFieldData* fd, const char* name, double fallback)
{
  vtkDataArray* array = fd ? fd->GetArray(name) : nullptr;
  return array && array->GetNumberOfTuples() > 0 ? array->GetTuple1(0) : fallback;
}
}

vtkMCXProjector::vtkMCXProjector() = default;

void vtkMCXProjector::SetNumberOfSamples(vtkTypeInt64 n)
{
  this->SetSampleExponent(static_cast<int>(mcx::ExponentForSampleCount(n)));
}

vtkTypeInt64 vtkMCXProjector::GetNumberOfSamples()
{
  return static_cast<vtkTypeInt64>(mcx::SampleCount(static_cast<unsigned>(this->SampleExponent)));
}

int vtkMCXProjector::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkMCXProjector::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  const mcx::ProjectionGeometry& geometry = this->GetGeometry();
  const std::size_t pixels = static_cast<std::size_t>(geometry.Size[0]) * geometry.Size[1];

  std::uint64_t count = 0;
  double weight = 0.0;
  double integral = 0.0;
  bool completed = true;
  std::vector<mcx::FixedSum> sums(2 * pixels, 0);
  if (auto* cloud = vtkPolyData::SafeDownCast(input))
  {
    vtkFieldData* fd = cloud->GetFieldData();
    if (!fd || !fd->GetArray("SampleWeight"))
    {
      vtkErrorMacro("The point cloud carries no SampleWeight (make it with vtkMCXPointSampler).");
      return 0;
    }
    weight = FieldValue(fd, "SampleWeight", 0.0);
    integral = FieldValue(fd, "Integral", 0.0);
    vtkPoints* points = cloud->GetPoints();
    count = points ? static_cast<std::uint64_t>(points->GetNumberOfPoints()) : 0;
    if (points && points->GetDataType() != VTK_FLOAT && points->GetDataType() != VTK_DOUBLE)
    {
      vtkErrorMacro("Points must be float or double, not " << points->GetData()->GetDataTypeAsString() << ".");
      return 0;
    }
    ImageAccumulator accumulator(pixels, mcx::FirstHalfSize(count));
    if (count > 0)
    {
      completed = points->GetDataType() == VTK_FLOAT
        ? ProjectPoints(this, static_cast<const float*>(points->GetVoidPointer(0)), count, geometry, accumulator)
        : ProjectPoints(this, static_cast<const double*>(points->GetVoidPointer(0)), count, geometry, accumulator);
    }
    sums = accumulator.Sum();
  }
  else
  {
    mcx::IndexView view;
    mcx::TransferTable table;
    if (!mcx::PrepareSampling(
          this, "project", vtkImageData::SafeDownCast(input), this->TransferFunction, view, table, integral))
    {
      return 0;
    }
    const auto strategy = static_cast<mcx::Strategy>(this->Strategy);
    const auto kernel = static_cast<mcx::Kernel>(this->Kernel);
    auto project = [&](unsigned m, double progressBegin, double progressEnd) {
      ImageAccumulator accumulator(pixels, mcx::FirstHalfSize(mcx::SampleCount(m)));
      if (m > 0)
      {
        completed = view.WideIds
          ? ProjectFromIndex<std::uint64_t>(this, view, table, strategy, kernel, this->Seed, m, geometry,
              accumulator, progressBegin, progressEnd)
          : ProjectFromIndex<std::uint32_t>(this, view, table, strategy, kernel, this->Seed, m, geometry,
              accumulator, progressBegin, progressEnd);
      }
      sums = accumulator.Sum();
    };
    unsigned m = table.IsEmpty() ? 0u : static_cast<unsigned>(this->SampleExponent);
    const bool targeted = this->TargetRelativeError > 0 || this->TargetQuantizationLevels > 0;
    if (m > 0 && targeted)
    {
      // A pilot run (about 4 samples per pixel) measures the image; the
      // sample count is then scaled to meet the target and re-checked on the
      // larger run, within [pilot, MaximumSampleExponent].
      const unsigned cap = static_cast<unsigned>(this->MaximumSampleExponent);
      m = std::min(cap, std::max(static_cast<unsigned>(PilotSampleExponent),
                          mcx::ExponentForSampleCount(static_cast<long long>(4 * pixels))));
      project(m, 0.0, 0.05);
      const double passEnd[] = { 0.8, 0.95, 1.0 };
      for (int pass = 0; pass < 3 && completed; ++pass)
      {
        const std::uint64_t current = mcx::SampleCount(m);
        double needed = 0.0;
        if (this->TargetRelativeError > 0)
        {
          const double error = mcx::EstimateRelativeError(sums, current);
          const double ratio = error / this->TargetRelativeError;
          needed = std::max(needed, static_cast<double>(current) * ratio * ratio);
        }
        if (this->TargetQuantizationLevels > 0)
        {
          needed = std::max(needed, mcx::QuantizationSampleCount(sums, this->TargetQuantizationLevels));
        }
        const unsigned next = std::min(cap, mcx::ExponentForSampleCount(static_cast<long long>(std::min(needed, 9.0e18))));
        if (next <= m)
        {
          break;
        }
        m = next;
        project(m, pass == 0 ? 0.05 : passEnd[pass - 1], passEnd[pass]);
      }
    }
    else
    {
      project(m, 0.0, 1.0);
    }
    count = mcx::SampleCount(m);
    weight = count > 0 ? integral / static_cast<double>(count) : 0.0;
  }
  if (!completed)
  {
    output->Initialize();
    return 1;
  }

  vtkDoubleArray* values = this->AllocateLineIntegral(output);
  mcx::FixedSumsToValues(sums.data(), pixels, weight, geometry.PixelArea(), values->GetPointer(0));

  vtkFieldData* fd = output->GetFieldData();
  fd->Initialize();
  mcx::AddFieldValue(fd, "SampleCount", static_cast<long long>(count));
  mcx::AddFieldValue(fd, "SampleWeight", weight);
  mcx::AddFieldValue(fd, "Integral", integral);
  mcx::AddFieldValue(fd, "EstimatedRelativeError", mcx::EstimateRelativeError(sums, count));
  return 1;
}

void vtkMCXProjector::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleExponent: " << this->SampleExponent << "\n";
  os << indent << "Strategy: " << this->Strategy << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "TargetRelativeError: " << this->TargetRelativeError << "\n";
  os << indent << "TargetQuantizationLevels: " << this->TargetQuantizationLevels << "\n";
  os << indent << "MaximumSampleExponent: " << this->MaximumSampleExponent << "\n";
}
