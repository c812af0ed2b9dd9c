#include "vtkMCXMaterialWeights.h"

#include "mcxFixedPoint.h"
#include "mcxMaterialDecomposition.h"
#include "mcxPointWeights.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXSMPExecutor.h"
#include "vtkMCXTypes.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <vector>

vtkStandardNewMacro(vtkMCXMaterialWeights);

vtkMCXMaterialWeights::vtkMCXMaterialWeights()
{
  this->SetNumberOfInputPorts(2);
  this->SetMaterials("default");
}

vtkMCXMaterialWeights::~vtkMCXMaterialWeights()
{
  this->SetMaterials(nullptr);
}

int vtkMCXMaterialWeights::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkPolyData" : "vtkImageData");
  return 1;
}

const mcx::MaterialSet* vtkMCXMaterialWeights::Set()
{
  const std::string text = this->Materials ? this->Materials : "";
  if (!this->Parsed || text != this->ParsedText)
  {
    this->Parsed.reset();
    try
    {
      this->Parsed.reset(new mcx::MaterialSet(mcx::MaterialsFromText(text)));
      this->ParsedText = text;
    }
    catch (const std::exception& error)
    {
      vtkErrorMacro(<< error.what());
      return nullptr;
    }
  }
  return this->Parsed.get();
}

bool vtkMCXMaterialWeights::FillDensityFunction(vtkPiecewiseFunction* density)
{
  const mcx::MaterialSet* set = this->Set();
  if (!set || !density)
  {
    return false;
  }
  density->RemoveAllPoints();
  for (std::size_t i = 0; i < set->Density.HU.size(); ++i)
  {
    density->AddPoint(set->Density.HU[i], set->Density.Value[i]);
  }
  return true;
}

bool vtkMCXMaterialWeights::FillFractionFunction(int m, vtkPiecewiseFunction* fraction)
{
  const mcx::MaterialSet* set = this->Set();
  if (!set || !fraction || m < 0 || m >= static_cast<int>(set->Size()))
  {
    return false;
  }
  const mcx::HUCurve& curve = set->Materials[static_cast<std::size_t>(m)].Fraction;
  fraction->RemoveAllPoints();
  fraction->ClampingOn(); // constant beyond the ends, as the curve
  for (std::size_t i = 0; i < curve.HU.size(); ++i)
  {
    fraction->AddPoint(curve.HU[i], curve.Value[i]);
  }
  return true;
}

const char* vtkMCXMaterialWeights::GetMaterialName(int m)
{
  const mcx::MaterialSet* set = this->Set();
  return set && m >= 0 && m < static_cast<int>(set->Size()) ? set->Materials[m].Name.c_str()
                                                            : nullptr;
}

int vtkMCXMaterialWeights::GetNumberOfMaterials()
{
  const mcx::MaterialSet* set = this->Set();
  return set ? static_cast<int>(set->Size()) : 0;
}

int vtkMCXMaterialWeights::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // The projector frames the image by the cloud's support before any point.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (inInfo->Has(vtkMCXPointSampler::SUPPORT_CORNERS()))
  {
    outInfo->CopyEntry(inInfo, vtkMCXPointSampler::SUPPORT_CORNERS());
  }
  return 1;
}

int vtkMCXMaterialWeights::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* cloud = vtkPolyData::GetData(inputVector[0]);
  vtkImageData* volume = vtkImageData::GetData(inputVector[1]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  const mcx::MaterialSet* set = this->Set();
  if (!cloud || !volume || !set)
  {
    if (set)
    {
      vtkErrorMacro("Needs a cloud on input 0 and its volume on input 1.");
    }
    return 0;
  }
  if (this->Channel >= static_cast<int>(set->Size()))
  {
    vtkErrorMacro("Channel " << this->Channel << " of " << set->Size() << " materials.");
    return 0;
  }
  vtkDataArray* scalars = volume->GetPointData()->GetScalars();
  vtkFieldData* fd = cloud->GetFieldData();
  vtkDataArray* integralArray = fd ? fd->GetArray(vtkMCXTypes::IntegralName()) : nullptr;
  if (!scalars || !integralArray || cloud->GetPointData()->GetArray(vtkMCXTypes::PointWeightName()))
  {
    vtkErrorMacro("Needs an unweighted cloud of vtkMCXPointSampler and a volume with scalars.");
    return 0;
  }
  const vtkIdType count = cloud->GetNumberOfPoints();
  int dims[3];
  volume->GetDimensions(dims);
  vtkNew<vtkDoubleArray> weights;
  weights->SetName(vtkMCXTypes::PointWeightName());
  weights->SetNumberOfValues(count);
  double* w = weights->GetPointer(0);
  // The world-to-voxel map once, then every point in parallel: a point's
  // weight depends on it alone, so any split of the work gives the same.
  vtkMatrix4x4* toIndex = volume->GetPhysicalToIndexMatrix();
  double m[12];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m[4 * r + c] = toIndex->GetElement(r, c);
    }
  }
  vtkDataArray* points = cloud->GetPoints() ? cloud->GetPoints()->GetData() : nullptr;
  std::atomic<vtkIdType> outside(-1);
  const int channel = this->Channel;
  mcx::SMPExecutor().For(0, count, 4096,
    [&](std::int64_t begin, std::int64_t end)
    {
      std::vector<double> fractions(set->Size());
      for (std::int64_t i = begin; i < end; ++i)
      {
        double x[3];
        points->GetTuple(i, x);
        int index[3];
        bool centre = true;
        for (int a = 0; a < 3; ++a)
        {
          const double ijk =
            m[4 * a] * x[0] + m[4 * a + 1] * x[1] + m[4 * a + 2] * x[2] + m[4 * a + 3];
          index[a] = static_cast<int>(std::lround(ijk));
          // Voxel centres only: a point between voxels has no material of its own.
          centre =
            centre && std::abs(ijk - index[a]) <= 1e-3 && index[a] >= 0 && index[a] < dims[a];
        }
        if (!centre)
        {
          // The first such point, whichever thread finds it: the message is the same on every run.
          vtkIdType seen = outside.load();
          while ((seen < 0 || i < seen) && !outside.compare_exchange_weak(seen, i))
          {
          }
          w[i] = 0.0;
          continue;
        }
        if (channel < 0)
        {
          w[i] = 1.0;
          continue;
        }
        const vtkIdType voxel =
          index[0] + dims[0] * (index[1] + static_cast<vtkIdType>(dims[1]) * index[2]);
        set->FixedFractionsAt(scalars->GetComponent(voxel, 0), fractions.data());
        w[i] = fractions[channel];
      }
    });
  if (outside >= 0)
  {
    vtkErrorMacro("Point " << outside.load()
                           << " is not at a voxel centre of the volume: sample it with the "
                              "footprint deposit (vtkMCXPointSampler's default).");
    return 0;
  }
  const mcx::FixedSum sum =
    mcx::PointWeightSum(mcx::SMPExecutor(), w, 0, static_cast<std::uint64_t>(count));
  const double weightSum = mcx::ToDouble(sum) / mcx::FixedOne;
  output->ShallowCopy(cloud);
  vtkNew<vtkFieldData> fields;
  fields->DeepCopy(fd);
  fields->RemoveArray(vtkMCXTypes::IntegralName());
  const double integral = integralArray->GetComponent(0, 0);
  mcx::AddFieldValue(fields, vtkMCXTypes::IntegralName(),
    count > 0 ? integral * weightSum / static_cast<double>(count) : 0.0);
  output->SetFieldData(fields);
  output->GetPointData()->AddArray(weights);
  return 1;
}

void vtkMCXMaterialWeights::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Materials: " << (this->Materials ? this->Materials : "(none)") << "\n";
  os << indent << "Channel: " << this->Channel << "\n";
  os << indent << "Parsed: " << (this->Parsed ? "yes" : "no") << "\n";
  os << indent << "ParsedText: " << this->ParsedText << "\n";
}
