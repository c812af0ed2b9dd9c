#include "vtkMCXReferenceProjector.h"

#include "mcxProjectionGeometry.h"
#include "mcxRayIntegrator.h"
#include "vtkMCXBatchedForPrivate.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXMemoryCheck.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjectorBaseInternals.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include <atomic>
#include <cmath>
#include <limits>
#include <new>
#include <vector>

vtkStandardNewMacro(vtkMCXReferenceProjector);

namespace
{
// g at every voxel, from the index: the TF value of the voxel's level.
// Returns false if an id lies outside the volume (a corrupt index).
template <typename IdType>
bool ScatterLevelWeights(
  const mcx::IndexView& view, const std::vector<double>& weights, std::vector<double>& g)
{
  const IdType* ids = view.IdPointer<IdType>();
  const std::uint64_t voxels = g.size();
  std::atomic<bool> valid(true);
  vtkSMPTools::For(0, view.NumberOfLevels,
    [&](vtkIdType l0, vtkIdType l1)
    {
      for (vtkIdType l = l0; l < l1; ++l)
      {
        const double w = weights[static_cast<std::size_t>(l)];
        const double value = (w > 0 && std::isfinite(w)) ? w : 0.0;
        for (std::int64_t i = view.LevelOffsets[l]; i < view.LevelOffsets[l + 1]; ++i)
        {
          const std::uint64_t id = static_cast<std::uint64_t>(ids[i]);
          if (id >= voxels)
          {
            valid = false;
            return;
          }
          g[id] = value;
        }
      }
    });
  return valid;
}

// Rays in voxel coordinates for points of the detector plane.
class RayFactory
{
public:
  RayFactory(const mcx::ProjectionGeometry& g, const mcx::IndexView& view)
    : Geometry(g)
  {
    double matrix[9];
    view.SourceToWorld(this->SourceOrigin, matrix);
    vtkMath::Invert3x3(
      reinterpret_cast<const double(*)[3]>(matrix), reinterpret_cast<double(*)[3]>(this->Inverse));
  }

  // Ray through plane point (a, b): start p0, direction d (per unit world length), t range.
  void Make(double a, double b, double p0[3], double d[3], double& tmin, double& tmax) const
  {
    const mcx::ProjectionGeometry& g = this->Geometry;
    double start[3], direction[3];
    if (g.Perspective)
    {
      for (int r = 0; r < 3; ++r)
      {
        start[r] = g.Eye[r];
        direction[r] = a * g.U[r] + b * g.V[r] + g.FocalDistance * g.W[r];
      }
      vtkMath::Normalize(direction);
      tmin = g.NearDistance / vtkMath::Dot(direction, g.W);
      tmax = std::numeric_limits<double>::infinity();
    }
    else
    {
      for (int r = 0; r < 3; ++r)
      {
        start[r] = a * g.U[r] + b * g.V[r];
        direction[r] = g.W[r] + g.Obliquity[0] * g.U[r] + g.Obliquity[1] * g.V[r];
      }
      vtkMath::Normalize(direction);
      tmin = -std::numeric_limits<double>::infinity();
      tmax = std::numeric_limits<double>::infinity();
    }
    const double relative[3] = { start[0] - this->SourceOrigin[0], start[1] - this->SourceOrigin[1],
      start[2] - this->SourceOrigin[2] };
    for (int r = 0; r < 3; ++r)
    {
      p0[r] = this->Inverse[3 * r] * relative[0] + this->Inverse[3 * r + 1] * relative[1] +
        this->Inverse[3 * r + 2] * relative[2];
      d[r] = this->Inverse[3 * r] * direction[0] + this->Inverse[3 * r + 1] * direction[1] +
        this->Inverse[3 * r + 2] * direction[2];
    }
  }

private:
  const mcx::ProjectionGeometry& Geometry;
  double SourceOrigin[3];
  double Inverse[9];
};
}

vtkMCXReferenceProjector::vtkMCXReferenceProjector()
{
  this->SetProgressText("X-Ray Reference Projector"); // what progress bars show
}

int vtkMCXReferenceProjector::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkMCXReferenceProjector::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!this->FrameOnInputData(
        vtkImageData::GetData(inputVector[0]), inputVector[0]->GetInformationObject(0)))
  {
    output->Initialize();
    return 0;
  }
  mcx::IndexView view;
  mcx::TransferTable table;
  double integral = 0.0;
  if (!mcx::PrepareSampling(this, "project", vtkImageData::GetData(inputVector[0]),
        this->TransferFunction, view, table, integral))
  {
    output->Initialize();
    return 0;
  }

  // g at every voxel and two images (this subdivision's and the last).
  const double voxels =
    static_cast<double>(view.Dimensions[0]) * view.Dimensions[1] * view.Dimensions[2];
  const mcx::ProjectionGeometry& geometry = this->Internals->Geometry;
  if (!mcx::CheckMemory(this, 8.0 * voxels + 16.0 * geometry.Size[0] * geometry.Size[1],
        "The exact projection of " + std::to_string(static_cast<long long>(voxels)) + " voxels"))
  {
    output->Initialize();
    return 0;
  }
  std::vector<double> g;
  try
  {
    g.assign(static_cast<std::size_t>(voxels), 0.0);
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro("Out of memory: the exact projection needs 8 bytes per voxel.");
    output->Initialize();
    return 0;
  }
  const std::vector<double> weights = view.EvaluateTransferFunction(this->TransferFunction);
  const bool validIds = view.WideIds ? ScatterLevelWeights<std::uint64_t>(view, weights, g)
                                     : ScatterLevelWeights<std::uint32_t>(view, weights, g);
  if (!validIds)
  {
    vtkErrorMacro("Cannot project: the index holds voxel ids outside the volume.");
    output->Initialize();
    return 0;
  }
  const mcx::Kernel kernel = static_cast<mcx::Kernel>(this->Kernel);
  const mcx::RayIntegrator integrator(g.data(), view.Dimensions, kernel);
  const RayFactory rays(geometry, view);
  const int width = geometry.Size[0];
  const int height = geometry.Size[1];
  const std::size_t pixels = static_cast<std::size_t>(width) * height;

  // Steps S = 1, 3, 9, ...: the sub-ray centres of one step contain the last's.
  int steps = 1;
  for (int s = 3; s <= this->MaximumSubdivision; s *= 3)
  {
    ++steps;
  }
  std::vector<double> previous, current(pixels, 0.0);
  double change = std::numeric_limits<double>::infinity();
  int subdivision = 1;
  for (int step = 0, s = 1; step < steps; ++step, s *= 3)
  {
    previous.swap(current);
    current.assign(pixels, 0.0);
    subdivision = s;
    const double progressBegin = static_cast<double>(step) / steps;
    const bool completed = mcx::BatchedFor(this, static_cast<std::uint64_t>(height), progressBegin,
      progressBegin + 1.0 / steps,
      [&](std::uint64_t j0, std::uint64_t j1)
      {
        for (std::uint64_t j = j0; j < j1; ++j)
        {
          for (int i = 0; i < width; ++i)
          {
            double sum = 0.0;
            for (int sj = 0; sj < s; ++sj)
            {
              const double b = geometry.Origin[1] +
                (static_cast<double>(j) + (sj + 0.5) / s - 0.5) * geometry.Spacing[1];
              for (int si = 0; si < s; ++si)
              {
                const double a =
                  geometry.Origin[0] + (i + (si + 0.5) / s - 0.5) * geometry.Spacing[0];
                double p0[3], d[3], tmin, tmax;
                rays.Make(a, b, p0, d, tmin, tmax);
                sum += integrator.Integrate(p0, d, tmin, tmax);
              }
            }
            current[j * width + i] = sum / (static_cast<double>(s) * s);
          }
        }
      });
    if (!completed)
    {
      output->Initialize();
      return 1;
    }
    if (step > 0)
    {
      double difference = 0.0, norm = 0.0;
      for (std::size_t p = 0; p < pixels; ++p)
      {
        difference += (current[p] - previous[p]) * (current[p] - previous[p]);
        norm += current[p] * current[p];
      }
      // An empty image has not converged: rays between them may still meet
      // a volume thinner than a pixel (it stays empty where the view misses).
      change = norm > 0 ? std::sqrt(difference / norm) : 0.0;
      if (change <= this->RelativeTolerance && norm > 0)
      {
        break;
      }
    }
  }
  if (steps > 1 && change > this->RelativeTolerance)
  {
    vtkWarningMacro(<< "the exact projection stopped at " << subdivision << "^2 rays per pixel "
                    << "(MaximumSubdivision) with an estimated relative error of " << change
                    << ", above its RelativeTolerance of " << this->RelativeTolerance
                    << " (voxels much thinner than a pixel?)");
  }

  vtkDoubleArray* values = this->AllocateLineIntegral(output);
  std::copy(current.begin(), current.end(), values->GetPointer(0));
  vtkFieldData* fd = output->GetFieldData();
  mcx::AddFieldValue(fd, vtkMCXTypes::EstimatedRelativeErrorName(), change);
  mcx::AddFieldValue(fd, "RaysPerPixelAxis", static_cast<long long>(subdivision));
  mcx::AddFieldValue(fd, vtkMCXTypes::IntegralName(), integral);
  return 1;
}

void vtkMCXReferenceProjector::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RelativeTolerance: " << this->RelativeTolerance << "\n";
  os << indent << "MaximumSubdivision: " << this->MaximumSubdivision << "\n";
}
