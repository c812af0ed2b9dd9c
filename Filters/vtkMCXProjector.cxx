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

#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkMCXProjector);

namespace
{
// Thread-local fixed-point images summed at the end: integer addition makes
// the result independent of the order and the number of threads.
class ImageAccumulator
{
public:
  explicit ImageAccumulator(std::size_t pixels)
    : Pixels(pixels)
  {
  }

  std::vector<mcx::FixedSum>& Local()
  {
    std::vector<mcx::FixedSum>& buffer = this->Buffers.Local();
    if (buffer.empty())
    {
      buffer.assign(this->Pixels, 0);
    }
    return buffer;
  }

  std::vector<mcx::FixedSum> Sum()
  {
    std::vector<mcx::FixedSum> total(this->Pixels, 0);
    for (auto& buffer : this->Buffers)
    {
      for (std::size_t i = 0; i < buffer.size(); ++i)
      {
        total[i] += buffer[i];
      }
    }
    return total;
  }

private:
  std::size_t Pixels;
  vtkSMPThreadLocal<std::vector<mcx::FixedSum>> Buffers;
};

template <typename IdType>
bool ProjectFromIndex(vtkAlgorithm* self, const mcx::IndexView& view, const mcx::TransferTable& table,
  mcx::Strategy strategy, mcx::Kernel kernel, vtkTypeUInt64 seed, unsigned m,
  const mcx::ProjectionGeometry& geometry, ImageAccumulator& accumulator)
{
  mcx::SampleSource<IdType> source = view.MakeSource<IdType>(table);
  source.Method = strategy;
  source.Reconstruction = kernel;
  source.Seed = seed;
  source.Exponent = m;
  double origin[3], matrix[9];
  view.SourceToWorld(origin, matrix);
  const mcx::PixelBinner binner(geometry, origin, matrix);
  return mcx::BatchedFor(self, source.NumberOfSamples(), 0.0, 1.0,
    [&](std::uint64_t b, std::uint64_t e) {
      std::vector<mcx::FixedSum>& image = accumulator.Local();
      auto sink = [&](std::uint64_t, const double p[3]) {
        std::int64_t pixel;
        mcx::FixedSum increment;
        if (binner.Bin(p, pixel, increment))
        {
          image[static_cast<std::size_t>(pixel)] += increment;
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
    std::vector<mcx::FixedSum>& image = accumulator.Local();
    for (std::uint64_t i = b; i < e; ++i)
    {
      const double p[3] = { static_cast<double>(points[3 * i]), static_cast<double>(points[3 * i + 1]),
        static_cast<double>(points[3 * i + 2]) };
      std::int64_t pixel;
      mcx::FixedSum increment;
      if (binner.Bin(p, pixel, increment))
      {
        image[static_cast<std::size_t>(pixel)] += increment;
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
  ImageAccumulator accumulator(pixels);

  std::uint64_t count = 0;
  double weight = 0.0;
  double integral = 0.0;
  bool completed = true;
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
    if (count > 0)
    {
      if (points->GetDataType() == VTK_FLOAT)
      {
        completed = ProjectPoints(this, static_cast<const float*>(points->GetVoidPointer(0)), count,
          geometry, accumulator);
      }
      else if (points->GetDataType() == VTK_DOUBLE)
      {
        completed = ProjectPoints(this, static_cast<const double*>(points->GetVoidPointer(0)), count,
          geometry, accumulator);
      }
      else
      {
        vtkErrorMacro("Points must be float or double, not " << points->GetData()->GetDataTypeAsString() << ".");
        return 0;
      }
    }
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
    const unsigned m = table.IsEmpty() ? 0u : static_cast<unsigned>(this->SampleExponent);
    count = mcx::SampleCount(m);
    weight = count > 0 ? integral / static_cast<double>(count) : 0.0;
    if (count > 0)
    {
      const auto strategy = static_cast<mcx::Strategy>(this->Strategy);
      const auto kernel = static_cast<mcx::Kernel>(this->Kernel);
      completed = view.WideIds
        ? ProjectFromIndex<std::uint64_t>(this, view, table, strategy, kernel, this->Seed, m, geometry, accumulator)
        : ProjectFromIndex<std::uint32_t>(this, view, table, strategy, kernel, this->Seed, m, geometry, accumulator);
    }
  }
  if (!completed)
  {
    output->Initialize();
    return 1;
  }

  vtkDoubleArray* values = this->AllocateLineIntegral(output);
  mcx::FixedSumsToValues(accumulator.Sum(), weight, geometry.PixelArea(), values->GetPointer(0));

  vtkFieldData* fd = output->GetFieldData();
  fd->Initialize();
  mcx::AddFieldValue(fd, "SampleCount", static_cast<long long>(count));
  mcx::AddFieldValue(fd, "SampleWeight", weight);
  mcx::AddFieldValue(fd, "Integral", integral);
  return 1;
}

void vtkMCXProjector::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleExponent: " << this->SampleExponent << "\n";
  os << indent << "Strategy: " << this->Strategy << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
}
