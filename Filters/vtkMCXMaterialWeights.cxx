#include "vtkMCXMaterialWeights.h"

#include "mcxFixedPoint.h"
#include "mcxMaterialDecomposition.h"
#include "mcxPointWeights.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXMaterialFractions.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXSMPExecutor.h"
#include "vtkMCXTypes.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

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
  vtkNew<vtkDoubleArray> weights;
  weights->SetName(vtkMCXTypes::PointWeightName());
  weights->SetNumberOfValues(count);
  double* w = weights->GetPointer(0);
  const vtkIdType outside =
    mcx::FillMaterialFractions(*set, cloud, volume, scalars, { this->Channel }, { w });
  if (outside >= 0)
  {
    vtkErrorMacro("Point " << outside
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
