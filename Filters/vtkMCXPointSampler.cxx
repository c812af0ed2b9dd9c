// The filter: its settings, its pipeline requests, and the dispatch to its
// strategies. HYBRID, MONTE_CARLO and QUASI_MONTE_CARLO are drawn here;
// EVERY_VOXEL (vtkMCXEveryVoxelSamplingPrivate) and VIEW_ORDERED
// (vtkMCXViewOrderedSamplingPrivate) live in files of their own, each with
// its cache; what all clouds share is in vtkMCXSampledCloudPrivate.
#include "vtkMCXPointSampler.h"

#include "mcxSampleGenerator.h"
#include "vtkMCXBatchedForPrivate.h"
#include "vtkMCXEveryVoxelSamplingPrivate.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXMemoryCheck.h"
#include "vtkMCXSampledCloudPrivate.h"
#include "vtkMCXViewOrderedSamplingPrivate.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cstdint>
#include <new>
#include <stdexcept>
#include <string>

vtkStandardNewMacro(vtkMCXPointSampler);

vtkCxxSetObjectMacro(vtkMCXPointSampler, TransferFunction, vtkPiecewiseFunction);
vtkInformationKeyRestrictedMacro(vtkMCXPointSampler, SUPPORT_CORNERS, DoubleVector, 24);

namespace
{
template <typename IdType, typename Real>
bool GeneratePoints(vtkAlgorithm* self, const mcx::IndexView& view, const mcx::TransferTable& table,
  mcx::Strategy strategy, mcx::Kernel kernel, vtkTypeUInt64 seed, unsigned m, bool centres,
  Real* points)
{
  mcx::SampleSource<IdType> source = view.MakeSource<IdType>(table);
  source.Centres = centres;
  source.Method = strategy;
  source.Reconstruction = kernel;
  source.Seed = seed;
  source.Exponent = m;
  double origin[3], matrix[9];
  view.SourceToWorld(origin, matrix);
  auto store = [&](std::uint64_t k, const double p[3])
  { mcx::StoreInWorld(origin, matrix, p, points + 3 * k); };
  return mcx::BatchedFor(
    self, source.NumberOfStorageItems(), 0.05, 1.0,
    [&](std::uint64_t b, std::uint64_t e) { source.GenerateForStorage(b, e, store); }, 1);
}

// GeneratePoints for the index's id type and the points' precision.
template <typename IdType>
bool GenerateAnyPoints(vtkAlgorithm* self, const mcx::IndexView& view,
  const mcx::TransferTable& table, mcx::Strategy strategy, mcx::Kernel kernel, vtkTypeUInt64 seed,
  unsigned m, bool centres, bool isDouble, void* raw)
{
  return isDouble ? GeneratePoints<IdType>(self, view, table, strategy, kernel, seed, m, centres,
                      static_cast<double*>(raw))
                  : GeneratePoints<IdType>(self, view, table, strategy, kernel, seed, m, centres,
                      static_cast<float*>(raw));
}
}

vtkMCXPointSampler::vtkMCXPointSampler()
  : EveryVoxel(new vtkMCXEveryVoxelSampling)
  , ViewOrdered(new vtkMCXViewOrderedSampling)
{
  this->SetProgressText("X-Ray Point Sampler"); // what progress bars show (ParaView's label)
}

vtkMCXPointSampler::~vtkMCXPointSampler()
{
  this->SetTransferFunction(nullptr);
}

void vtkMCXPointSampler::SetNumberOfSamples(vtkTypeInt64 n)
{
  this->SetSampleExponent(static_cast<int>(mcx::ExponentForSampleCount(n)));
}

void vtkMCXPointSampler::SetReusePoints(bool reuse)
{
  if (!reuse)
  {
    this->KeptPoints = nullptr; // not an output change: no Modified()
    this->EveryVoxel->Forget();
  }
  if (reuse != this->ReusePoints)
  {
    this->ReusePoints = reuse;
    this->Modified();
  }
}

void vtkMCXPointSampler::SetOrderingView(vtkCamera* camera, int width, int height)
{
  // Called from Python and ParaView: no exception may leave it (it would end
  // the interpreter).
  try
  {
    if (this->ViewOrdered->SetView(this, camera, width, height))
    {
      this->Modified();
    }
  }
  catch (const std::exception& error)
  {
    vtkErrorMacro("Cannot order by a view of " << width << " x " << height
                                               << " pixels: " << error.what() << ".");
  }
}

bool vtkMCXPointSampler::HasOrderingView() const
{
  return this->ViewOrdered->HasView();
}

vtkTypeInt64 vtkMCXPointSampler::GetNumberOfSamples()
{
  return static_cast<vtkTypeInt64>(mcx::SampleCount(static_cast<unsigned>(this->SampleExponent)));
}

vtkMTimeType vtkMCXPointSampler::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->TransferFunction)
  {
    t = std::max(t, this->TransferFunction->GetMTime());
  }
  return t;
}

int vtkMCXPointSampler::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkMCXPointSampler::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  double corners[24];
  const double radius = mcx::KernelRadius(static_cast<mcx::Kernel>(this->Kernel));
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (mcx::SupportCornersFromInformation(inputVector[0]->GetInformationObject(0), radius, corners))
  {
    outInfo->Set(SUPPORT_CORNERS(), corners, 24);
  }
  else
  {
    outInfo->Remove(SUPPORT_CORNERS());
  }
  return 1;
}

int vtkMCXPointSampler::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  return 1;
}

int vtkMCXPointSampler::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  // An allocation the budget allowed can still fail (an address-space limit,
  // ulimit -v): an error and an empty cloud, never an exception through the
  // executive into Python or ParaView.
  try
  {
    return this->RequestCloud(input, output);
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro("Out of memory sampling " << this->GetNumberOfSamples() << " points.");
  }
  catch (const std::length_error& error)
  {
    vtkErrorMacro(
      "Cannot sample " << this->GetNumberOfSamples() << " points: " << error.what() << ".");
  }
  this->KeptPoints = nullptr;
  this->ViewOrdered->ForgetOrder();
  output->Initialize();
  return 0;
}

int vtkMCXPointSampler::RequestCloud(vtkImageData* input, vtkPolyData* output)
{
  if (this->Strategy == vtkMCXTypes::EVERY_VOXEL)
  {
    this->KeptPoints = nullptr;
    this->ViewOrdered->ForgetOrder();
    return this->EveryVoxel->RequestData(this, input, output);
  }
  this->EveryVoxel->Forget();
  if (this->Strategy == vtkMCXTypes::VIEW_ORDERED)
  {
    return this->RequestViewOrdered(input, output);
  }
  this->ViewOrdered->ForgetOrder();
  return this->RequestSampled(input, output);
}

int vtkMCXPointSampler::RequestSampled(vtkImageData* input, vtkPolyData* output)
{
  // A sampled cloud's points count once each (an output the executive did
  // not empty may still hold an every-voxel cloud's weights).
  output->GetPointData()->RemoveArray(vtkMCXTypes::PointWeightName());
  mcx::IndexView view;
  mcx::TransferTable table;
  double integral = 0.0;
  if (!mcx::PrepareSampling(this, "sample", input, this->TransferFunction, view, table, integral))
  {
    this->KeptPoints = nullptr;
    output->Initialize(); // no stale cloud of an earlier request
    return 0;
  }

  const unsigned m = table.IsEmpty() ? 0u : static_cast<unsigned>(this->SampleExponent);
  const vtkIdType count = static_cast<vtkIdType>(mcx::SampleCount(m));
  const int pointType = this->OutputPointsPrecision == DOUBLE_PRECISION ? VTK_DOUBLE : VTK_FLOAT;
  vtkSmartPointer<vtkPoints> points = this->CloudPoints(output, pointType, count);
  if (!points)
  {
    output->Initialize();
    return 0;
  }

  bool completed = true;
  if (count > 0)
  {
    const auto strategy = static_cast<mcx::Strategy>(this->Strategy);
    const auto kernel = static_cast<mcx::Kernel>(this->Kernel);
    const bool centres = this->Deposit == vtkMCXTypes::FOOTPRINT;
    void* raw = points->GetVoidPointer(0);
    const bool isDouble = this->OutputPointsPrecision == DOUBLE_PRECISION;
    completed = view.WideIds ? GenerateAnyPoints<std::uint64_t>(this, view, table, strategy, kernel,
                                 this->Seed, m, centres, isDouble, raw)
                             : GenerateAnyPoints<std::uint32_t>(this, view, table, strategy, kernel,
                                 this->Seed, m, centres, isDouble, raw);
  }
  if (!completed)
  {
    output->Initialize();
    return 1;
  }

  output->SetPoints(points);
  if (this->ReusePoints)
  {
    this->KeptPoints = points;
  }
  mcx::WriteCloudFields(this, view, integral, count, static_cast<int>(m), output->GetFieldData());
  return 1;
}

int vtkMCXPointSampler::RequestViewOrdered(vtkImageData* input, vtkPolyData* output)
{
  mcx::IndexView view;
  mcx::TransferTable table;
  double integral = 0.0;
  if (!mcx::PrepareSampling(
        this, "sample in view order", input, this->TransferFunction, view, table, integral))
  {
    this->KeptPoints = nullptr;
    output->Initialize(); // no stale cloud of an earlier request
    return 0;
  }
  vtkMCXViewOrderedSampling::Cloud cloud;
  const auto outcome = this->ViewOrdered->Sample(
    this, view, integral,
    [this, output](int type, vtkIdType count) { return this->CloudPoints(output, type, count); },
    cloud);
  if (outcome != vtkMCXViewOrderedSampling::Outcome::Made)
  {
    output->Initialize();
    return outcome == vtkMCXViewOrderedSampling::Outcome::Failed ? 0 : 1; // an error, or aborted
  }
  output->SetPoints(cloud.Points);
  output->GetPointData()->AddArray(cloud.Weights);
  if (this->ReusePoints)
  {
    this->KeptPoints = cloud.Points;
  }
  mcx::WriteCloudFields(this, view, integral, cloud.Points->GetNumberOfPoints(),
    static_cast<int>(cloud.Exponent), output->GetFieldData());
  vtkMCXViewOrderedSampling::WriteControl(cloud, output->GetFieldData());
  return 1;
}

vtkSmartPointer<vtkPoints> vtkMCXPointSampler::CloudPoints(
  vtkPolyData* output, int type, vtkIdType count)
{
  vtkSmartPointer<vtkPoints> points = this->ReusablePoints(output, type, count);
  this->KeptPoints = nullptr; // an old cloud is not held while a new one is allocated
  if (points)
  {
    points->Modified();
    return points;
  }
  if (!mcx::CheckMemory(this, 3.0 * (type == VTK_DOUBLE ? 8 : 4) * static_cast<double>(count),
        "A cloud of " + std::to_string(count) + " points"))
  {
    return nullptr;
  }
  points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataType(type);
  points->SetNumberOfPoints(count);
  if (points->GetNumberOfPoints() != count)
  {
    vtkErrorMacro("Cannot allocate a cloud of " << count << " points.");
    return nullptr;
  }
  return points;
}

vtkPoints* vtkMCXPointSampler::ReusablePoints(vtkPolyData* output, int type, vtkIdType count) const
{
  vtkPoints* kept = this->KeptPoints;
  if (!this->ReusePoints || !kept || kept->GetDataType() != type ||
    kept->GetNumberOfPoints() != count || !kept->GetData())
  {
    return nullptr;
  }
  // The executive usually empties the output before RequestData; when it
  // has not, the output's reference is the old cloud's own.
  const int holders = 1 + (output->GetPoints() == kept ? 1 : 0);
  return kept->GetReferenceCount() == holders && kept->GetData()->GetReferenceCount() == 1
    ? kept
    : nullptr;
}

void vtkMCXPointSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TransferFunction: " << this->TransferFunction << "\n";
  os << indent << "SampleExponent: " << this->SampleExponent << "\n";
  os << indent << "Strategy: " << this->Strategy << "\n";
  os << indent << "Kernel: " << this->Kernel << "\n";
  os << indent << "Deposit: " << this->Deposit << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "ReusePoints: " << this->ReusePoints << "\n";
  os << indent << "KeptPoints: " << (this->KeptPoints ? this->KeptPoints->GetNumberOfPoints() : 0)
     << " points\n";
  os << indent << "KeptVoxels: " << this->EveryVoxel->KeptPointCount() << " points\n";
  os << indent << "OutputPointsPrecision: " << this->OutputPointsPrecision << "\n";
  os << indent << "NumberOfOrderingBins: " << this->NumberOfOrderingBins << "\n";
  os << indent << "ControlVariate: " << (this->ControlVariate ? "On" : "Off") << "\n";
  os << indent << "ControlVoxelsPerPoint: " << this->ControlVoxelsPerPoint << "\n";
  os << indent << "ReorderAngle: " << this->ReorderAngle << "\n";
  this->ViewOrdered->PrintSelf(os, indent);
}
