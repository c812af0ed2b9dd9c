#include "vtkMCXXRayRepresentation.h"

#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXXRayMapper.h"

#include "vtkAlgorithmOutput.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPVRenderView.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"

vtkStandardNewMacro(vtkMCXXRayRepresentation);

vtkMCXXRayRepresentation::vtkMCXXRayRepresentation()
{
  vtkMath::UninitializeBounds(this->DataBounds);
  // Until the colour map provides one: g = 0, an empty image.
  vtkNew<vtkPiecewiseFunction> zero;
  this->Sampler->SetTransferFunction(zero);
  // The interactive preview's 4 M points; the mapper is the only consumer of
  // the cloud, so a TF edit may rewrite it in place.
  this->Sampler->SetSampleExponent(DefaultSampleExponent);
  this->Sampler->ReusePointsOn();
  this->Sampler->SetDeposit(vtkMCXPointSampler::FOOTPRINT); // far less noise for the same points
  this->Mapper->SetInputConnection(this->Sampler->GetOutputPort());
  this->Volume->SetMapper(this->Mapper);
  this->Volume->SetVisibility(false);
}

vtkMCXXRayRepresentation::~vtkMCXXRayRepresentation() = default;

int vtkMCXXRayRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkMCXXRayRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkMath::UninitializeBounds(this->DataBounds);
  this->DeliveredIndex = nullptr;
  if (inputVector[0]->GetNumberOfInformationObjects() == 1)
  {
    if (vtkImageData* input = vtkImageData::GetData(inputVector[0], 0))
    {
      vtkNew<vtkImageData> volume;
      volume->ShallowCopy(input);
      this->Index->SetInputData(volume);
      // The array the user colours by is the density.
      if (vtkInformation* array = this->GetInputArrayInformation(0))
      {
        if (array->Has(vtkDataObject::FIELD_NAME()))
        {
          this->Index->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
            array->Get(vtkDataObject::FIELD_NAME()));
        }
      }
      this->Index->Update();
      this->DeliveredIndex = vtkSmartPointer<vtkImageData>::New();
      this->DeliveredIndex->ShallowCopy(this->Index->GetOutput());
      input->GetBounds(this->DataBounds);
    }
  }
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

int vtkMCXXRayRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request, inInfo, outInfo))
  {
    return 0;
  }
  if (request == vtkPVView::REQUEST_UPDATE())
  {
    // Only the index travels to the rendering processes: 4 or 8 bytes a voxel.
    vtkPVView::SetPiece(inInfo, this, this->DeliveredIndex);
    if (vtkMath::AreBoundsInitialized(this->DataBounds))
    {
      vtkPVRenderView::SetGeometryBounds(inInfo, this, this->DataBounds);
    }
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    vtkAlgorithmOutput* producer = vtkPVRenderView::GetPieceProducer(inInfo, this);
    this->Sampler->SetInputConnection(producer);
    this->SetVisibility(this->GetVisibility());
  }
  return 1;
}

bool vtkMCXXRayRepresentation::AddToView(vtkView* view)
{
  if (auto* renderView = vtkPVRenderView::SafeDownCast(view))
  {
    renderView->GetRenderer()->AddVolume(this->Volume);
    return this->Superclass::AddToView(view);
  }
  return false;
}

bool vtkMCXXRayRepresentation::RemoveFromView(vtkView* view)
{
  if (auto* renderView = vtkPVRenderView::SafeDownCast(view))
  {
    renderView->GetRenderer()->RemoveVolume(this->Volume);
    return this->Superclass::RemoveFromView(view);
  }
  return false;
}

void vtkMCXXRayRepresentation::SetVisibility(bool visible)
{
  this->Superclass::SetVisibility(visible);
  // Shown only once the view has connected the delivered index.
  this->Volume->SetVisibility(visible && this->Sampler->GetNumberOfInputConnections(0) > 0);
}

void vtkMCXXRayRepresentation::SetScalarOpacityFunction(vtkPiecewiseFunction* function)
{
  if (function)
  {
    this->Sampler->SetTransferFunction(function);
  }
  else
  {
    vtkNew<vtkPiecewiseFunction> zero;
    this->Sampler->SetTransferFunction(zero);
  }
  this->MarkModified();
}

void vtkMCXXRayRepresentation::SetSampleExponent(int exponent)
{
  this->Sampler->SetSampleExponent(exponent);
}

void vtkMCXXRayRepresentation::SetStrategy(int strategy)
{
  this->Sampler->SetStrategy(strategy);
}

void vtkMCXXRayRepresentation::SetKernel(int kernel)
{
  this->Sampler->SetKernel(kernel);
}

void vtkMCXXRayRepresentation::SetDeposit(int deposit)
{
  this->Sampler->SetDeposit(deposit);
}

void vtkMCXXRayRepresentation::SetSeed(vtkTypeInt64 seed)
{
  this->Sampler->SetSeed(seed);
}

void vtkMCXXRayRepresentation::SetFootprintReach(double reach)
{
  this->Mapper->SetFootprintReach(reach);
}

void vtkMCXXRayRepresentation::SetInvertDisplay(bool invert)
{
  this->Mapper->SetInvertDisplay(invert);
}

void vtkMCXXRayRepresentation::SetCompositing(int compositing)
{
  this->Mapper->SetCompositing(compositing);
}

void vtkMCXXRayRepresentation::SetAutomaticWindowLevel(bool automatic)
{
  this->Mapper->SetAutomaticWindowLevel(automatic);
}

void vtkMCXXRayRepresentation::SetColorWindow(double window)
{
  this->Mapper->SetColorWindow(window);
}

void vtkMCXXRayRepresentation::SetColorLevel(double level)
{
  this->Mapper->SetColorLevel(level);
}

void vtkMCXXRayRepresentation::SetProgressiveRefinement(bool progressive)
{
  this->Mapper->SetProgressiveRefinement(progressive);
}

vtkMCXXRayMapper* vtkMCXXRayRepresentation::GetMapper()
{
  return this->Mapper;
}

void vtkMCXXRayRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Index: " << this->Index.GetPointer() << "\n";
  os << indent << "Sampler: " << this->Sampler.GetPointer() << "\n";
  os << indent << "Mapper: " << this->Mapper.GetPointer() << "\n";
  os << indent << "Volume: " << this->Volume.GetPointer() << "\n";
  os << indent << "DeliveredIndex: " << this->DeliveredIndex.GetPointer() << "\n";
  os << indent << "DataBounds: " << this->DataBounds[0] << " " << this->DataBounds[1] << " "
     << this->DataBounds[2] << " " << this->DataBounds[3] << " " << this->DataBounds[4] << " "
     << this->DataBounds[5] << "\n";
}
