#include "vtkMCXVolumeSamplingPrivate.h"

#include "vtkAlgorithmOutput.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

vtkMCXVolumeSampling::vtkMCXVolumeSampling()
{
  // The mapper renders the volume it holds: no other process takes part.
  this->Index->SetController(nullptr);
  // The mapper is the cloud's only consumer: a TF edit refills it in place.
  this->Sampler->ReusePointsOn();
}

vtkMCXVolumeSampling::~vtkMCXVolumeSampling() = default;

bool vtkMCXVolumeSampling::IsDensityIndex(vtkDataObject* data)
{
  vtkFieldData* fd = data ? data->GetFieldData() : nullptr;
  return fd && fd->GetArray(vtkMCXTypes::SortedVoxelIdsName()) &&
    fd->GetArray(vtkMCXTypes::LevelValuesName()) && fd->GetArray(vtkMCXTypes::LevelOffsetsName());
}

void vtkMCXVolumeSampling::Connect(
  vtkAlgorithmOutput* input, vtkImageData* image, vtkDataArray* density)
{
  vtkAlgorithmOutput* indexed = input;
  if (!IsDensityIndex(image))
  {
    if (this->Index->GetNumberOfInputConnections(0) != 1 ||
      this->Index->GetInputConnection(0, 0) != input)
    {
      this->Index->SetInputConnection(input);
    }
    // By name, else (an unnamed array is the active scalars) as the scalars.
    if (density->GetName() && *density->GetName())
    {
      this->Index->SetInputArrayToProcess(
        0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, density->GetName());
    }
    else
    {
      this->Index->SetInputArrayToProcess(
        0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
    }
    indexed = this->Index->GetOutputPort();
  }
  if (this->Sampler->GetNumberOfInputConnections(0) != 1 ||
    this->Sampler->GetInputConnection(0, 0) != indexed)
  {
    this->Sampler->SetInputConnection(indexed);
  }
}

void vtkMCXVolumeSampling::Configure(const Settings& settings)
{
  this->Sampler->SetSampleExponent(settings.SampleExponent);
  this->Sampler->SetStrategy(settings.Strategy);
  this->Sampler->SetKernel(settings.Kernel);
  this->Sampler->SetDeposit(settings.Deposit);
  this->Sampler->SetSeed(settings.Seed);
  this->Sampler->SetReorderAngle(settings.ReorderAngle);
}

vtkPolyData* vtkMCXVolumeSampling::Sample(
  vtkPiecewiseFunction* tf, vtkCamera* camera, const int size[2])
{
  this->Sampler->SetTransferFunction(tf);
  // The sampler's time folds in its TF's: an edit, or a setting, since the
  // last sort sorts for the view as it is now.
  if (this->Sampler->GetStrategy() == vtkMCXTypes::VIEW_ORDERED && camera &&
    this->Sampler->GetMTime() > this->SortedAt)
  {
    this->Sampler->SetOrderingView(camera, size[0], size[1]);
    this->SortedAt = this->Sampler->GetMTime();
  }
  this->Sampler->Update();
  return this->Sampler->GetOutput();
}

bool vtkMCXVolumeSampling::SupportCorners(double corners[24])
{
  this->Sampler->UpdateInformation();
  vtkInformation* info = this->Sampler->GetOutputInformation(0);
  if (!info || !info->Has(vtkMCXPointSampler::SUPPORT_CORNERS()))
  {
    return false;
  }
  info->Get(vtkMCXPointSampler::SUPPORT_CORNERS(), corners);
  return true;
}
