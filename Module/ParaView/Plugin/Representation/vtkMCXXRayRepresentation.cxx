#include "vtkMCXXRayRepresentation.h"

#include "vtkMCXAggregateIndex.h"
#include "vtkMCXAgreeingExecutive.h"
#include "vtkMCXAttenuationModePrivate.h"
#include "vtkMCXCostPrivate.h"
#include "vtkMCXDensityArrayPrivate.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXDistributed.h"
#include "vtkMCXXRayMapper.h"
#include "vtkMCXXRayRepresentationExecutive.h"

#include "vtkAlgorithmOutput.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPVRenderView.h"
#include "vtkPVSession.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProcessModule.h"
#include "vtkRenderer.h"
#include "vtkSMSession.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTrivialProducer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkMCXXRayRepresentation);

namespace
{
// The processes of the data server, the same number on every process of the
// session (the client asks the server; a server process counts its peers).
int DataServerProcesses()
{
  vtkProcessModule* pm = vtkProcessModule::GetProcessModule();
  if (!pm)
  {
    return 1;
  }
  if (auto* session = vtkSMSession::SafeDownCast(pm->GetActiveSession()))
  {
    return session->GetNumberOfProcesses(vtkPVSession::DATA_SERVER);
  }
  return pm->GetNumberOfLocalPartitions();
}

// A parallel data server: each process indexes its z-slab and the index is
// gathered onto the first process, which renders (see the class comment).
bool IsParallelServer()
{
  return DataServerProcesses() > 1;
}

// ParaView asks for streaming passes on the data server only, so a client
// that renders the X-ray itself (a small one from a remote server) gets no
// pass after its still render.
bool ServesData()
{
  vtkProcessModule* pm = vtkProcessModule::GetProcessModule();
  auto* session = pm ? vtkPVSession::SafeDownCast(pm->GetActiveSession()) : nullptr;
  return !session || session->HasProcessRole(vtkPVSession::DATA_SERVER);
}

}

vtkMCXXRayRepresentation::vtkMCXXRayRepresentation()
{
  // vtkPVDataRepresentation's constructor set its executive while this
  // class's CreateDefaultExecutive could not yet be called.
  vtkExecutive* executive = this->CreateDefaultExecutive();
  this->SetExecutive(executive);
  executive->Delete();
  vtkMath::UninitializeBounds(this->DataBounds);
  // Until the colour map provides one: the default ramp, once the index is known.
  this->Volume->GetProperty()->SetScalarOpacity(this->DefaultRamp);
  this->Index->SetInputConnection(this->Slab->GetOutputPort());
  this->Aggregate->SetInputConnection(this->Index->GetOutputPort());
  // The mapper samples the delivered index under the property's TF (and
  // sorts a view-ordered cloud for the view on a TF edit).
  this->Volume->SetMapper(this->Mapper);
  this->Volume->SetVisibility(false);
}

vtkMCXXRayRepresentation::~vtkMCXXRayRepresentation() = default;

vtkExecutive* vtkMCXXRayRepresentation::CreateDefaultExecutive()
{
  return vtkMCXXRayRepresentationExecutive::New();
}

int vtkMCXXRayRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkMCXXRayRepresentation::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestUpdateExtent(request, inputVector, outputVector))
  {
    return 0;
  }
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  vtkInformation* inInfo = inputVector[0]->GetNumberOfInformationObjects() == 1
    ? inputVector[0]->GetInformationObject(0)
    : nullptr;
  if (!mcx::IsDistributed(controller) || !inInfo ||
    !inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    return 1;
  }
  // This process's z-slab, whole slices that no other process holds (ParaView
  // asks for piece r of N, whose point extents share their boundary slices).
  // An empty slab (more processes than slices) asks for one slice, the
  // least a reader delivers; the index then crops it to nothing.
  int whole[6], slab[6];
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  mcx::ZSlabExtent(
    whole, controller->GetLocalProcessId(), controller->GetNumberOfProcesses(), slab);
  if (slab[5] < slab[4])
  {
    slab[5] = slab[4] = whole[4];
  }
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), slab, 6);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  return 1;
}

int vtkMCXXRayRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkMath::UninitializeBounds(this->DataBounds);
  this->DeliveredIndex = nullptr;
  if (inputVector[0]->GetNumberOfInformationObjects() == 1)
  {
    vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
    std::string problem;
    vtkDataArray* density = nullptr;
    vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
    const bool distributed = mcx::IsDistributed(vtkMultiProcessController::GetGlobalController());
    if (!input && !distributed)
    {
      return this->Superclass::RequestData(request, inputVector, outputVector); // nothing to show
    }
    if (vtkMCXAgreeingExecutive::UpstreamFailed(request) || !input ||
      (distributed && (mcx::NothingRead(input, inInfo) || mcx::NothingDescribed(inInfo))))
    {
      problem =
        "the volume's piece could not be read (see the reader's error in that process's output)";
    }
    else
    {
      // The array the user colours by is the density (or, before one is
      // chosen, the one ParaView's Volume representation would show).
      vtkInformation* chosen = this->GetInputArrayInformation(0);
      const char* coloured = chosen && chosen->Has(vtkDataObject::FIELD_NAME())
        ? chosen->Get(vtkDataObject::FIELD_NAME())
        : nullptr;
      const int association = chosen && chosen->Has(vtkDataObject::FIELD_ASSOCIATION())
        ? chosen->Get(vtkDataObject::FIELD_ASSOCIATION())
        : vtkDataObject::FIELD_ASSOCIATION_POINTS;
      density = mcx::ChooseDensityArray(input, coloured, association, problem);
    }
    // On a parallel server every process indexes its slab together: one
    // that cannot fails all of them (none waits for it).
    problem = mcx::FirstErrorOfAll(vtkMultiProcessController::GetGlobalController(), problem);
    if (!problem.empty())
    {
      vtkErrorMacro("Monte Carlo X-Ray: " << problem << ".");
      return this->Superclass::RequestData(request, inputVector, outputVector);
    }
    // The whole extent travels with this process's part, so that the
    // index and the aggregate know which slab is this process's.
    int whole[6];
    if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    {
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    }
    else
    {
      input->GetExtent(whole);
    }
    vtkNew<vtkImageData> volume;
    volume->ShallowCopy(input);
    this->Slab->SetOutput(volume);
    this->Slab->SetWholeExtent(whole);
    if (density->GetName())
    {
      this->Index->SetInputArrayToProcess(
        0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, density->GetName());
    }
    else // the active scalars, unnamed
    {
      this->Index->SetInputArrayToProcess(
        0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
    }
    this->Aggregate->Update();
    // The volume is hidden and the mapper leaves the view's piece until the
    // new index is delivered (REQUEST_RENDER shows and connects them again):
    // the view empties the piece in between, and asks the visible props'
    // bounds first, which would sample that.
    this->Mapper->RemoveAllInputConnections(0);
    this->Volume->SetVisibility(false);
    this->DeliveredIndex = vtkSmartPointer<vtkImageData>::New();
    this->DeliveredIndex->ShallowCopy(this->Aggregate->GetOutput());
    // The whole volume's bounds, the same on every process.
    vtkNew<vtkImageData> wholeVolume;
    wholeVolume->CopyStructure(input);
    wholeVolume->SetExtent(whole);
    wholeVolume->GetBounds(this->DataBounds);
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
    // The size that decides on interactive (LOD) renders is that of the
    // cloud the renders draw, so that a large point count makes camera
    // motion use the interactive budget.
    // An every-voxel cloud holds at most each voxel once, with its weight.
    const double cloudKiB = this->Mapper->GetStrategy() == vtkMCXTypes::EVERY_VOXEL
      ? (this->DeliveredIndex ? 16.0 * this->DeliveredIndex->GetNumberOfPoints() / 1024.0 : 0.0)
      : 12.0 * std::ldexp(1.0, this->Mapper->GetSampleExponent()) / 1024.0;
    const double indexKiB =
      this->DeliveredIndex ? this->DeliveredIndex->GetActualMemorySize() : 0.0;
    const bool parallel = IsParallelServer();
    if (!parallel || this->ServerRenders())
    {
      vtkPVView::SetPiece(inInfo, this,
        this->DeliveredIndex ? this->DeliveredIndex.GetPointer() : this->NoIndex.GetPointer(),
        static_cast<unsigned long>(std::min(std::max(cloudKiB, indexKiB), 4.0e9)));
    }
    if (parallel && this->ServerRenders())
    {
      // The whole index is on the first process, which draws the whole
      // image; the others draw nothing of it, and IceT's compositing keeps
      // the first's pixels (see vtkMCXXRayMapper::SetCompositedByDepth).
      // The server renders (as for ParaView's Volume representation): the
      // index stays where it is and the client gets the picture.
      vtkPVRenderView::SetRequiresDistributedRendering(inInfo, this, true);
    }
    else if (parallel)
    {
      // A parallel server that cannot render (no OpenGL on its processes):
      // nothing is delivered (ParaView 5.11 cannot move this index to the
      // client from several processes), and the view says why instead of
      // drawing.
      if (!this->ToldServerCannotRender)
      {
        vtkWarningMacro("Monte Carlo X-Ray: this parallel server cannot render (no OpenGL on its "
                        "processes), so the X-ray is not drawn; start pvserver with a display or "
                        "offscreen rendering, or use one server process.");
        this->ToldServerCannotRender = true;
      }
    }
    // With streaming on, ParaView asks after each render whether there is
    // more to show (REQUEST_STREAMING_UPDATE) and renders again if so.
    vtkPVRenderView::SetStreamable(inInfo, this, true);
    if (vtkMath::AreBoundsInitialized(this->DataBounds))
    {
      vtkPVRenderView::SetGeometryBounds(inInfo, this, this->DataBounds);
    }
  }
  else if (request == vtkPVView::REQUEST_UPDATE_LOD())
  {
    if (IsParallelServer() && this->ServerRenders())
    {
      vtkPVRenderView::SetRequiresDistributedRenderingLOD(inInfo, this, true);
    }
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    // An empty delivery (no density array: reported on the data server)
    // draws nothing and asks nothing of the mapper.
    vtkAlgorithmOutput* producer = vtkPVRenderView::GetPieceProducer(inInfo, this);
    vtkDataObject* piece = producer && producer->GetProducer()
      ? producer->GetProducer()->GetOutputDataObject(producer->GetIndex())
      : nullptr;
    vtkImageData* index = vtkImageData::SafeDownCast(piece);
    if (index && index->GetNumberOfPoints() > 0)
    {
      if (this->Mapper->GetNumberOfInputConnections(0) != 1 ||
        this->Mapper->GetInputConnection(0, 0) != producer)
      {
        this->Mapper->SetInputConnection(producer);
      }
      this->UseDefaultRampUnlessColoured(index);
      this->UseSampledFunction(index);
    }
    else
    {
      this->Mapper->RemoveAllInputConnections(0);
    }
    // While the camera moves (an interactive, LOD render), each frame
    // projects only what fits the interactive budget; the still render that
    // ends the interaction draws every point.
    // With streaming on, a still render too spends at most the still budget,
    // and the streaming passes that follow it add the rest.
    const bool interactive =
      inInfo->Has(vtkPVRenderView::USE_LOD()) && inInfo->Get(vtkPVRenderView::USE_LOD()) != 0;
    this->Mapper->SetCompositedByDepth(IsParallelServer() && this->ServerRenders());
    const bool streaming = vtkPVView::GetEnableStreaming() && ServesData();
    this->Mapper->SetMaximumRenderTime(interactive ? this->InteractiveRenderTime
        : streaming                                ? this->StillRenderTime
                                                   : 0.0);
    this->SetVisibility(this->GetVisibility());
  }
  else if (request == vtkPVRenderView::REQUEST_STREAMING_UPDATE())
  {
    // More to show while points remain: a token piece makes the view render
    // again (the points are already here; the render adds the next prefix).
    // A pass after which nothing was projected (the first process does not
    // render, or cannot) ends the passes: the mapper's count of projecting
    // renders tells, whatever the point counts of earlier sequences were.
    const vtkTypeInt64 progress =
      this->Mapper->GetNumberOfRestarts() + this->Mapper->GetNumberOfRefinements();
    int more = this->Volume->GetVisibility() && !this->Mapper->IsRefinementComplete() &&
        progress != this->StreamedProgress
      ? 1
      : 0;
    this->StreamedProgress = progress;
    // On a parallel server only the first process draws, so it decides for
    // all. ParaView delivers a pass's pieces on every server process (the
    // keys are gathered from all of them); one without the token would
    // deliver nothing and warn "Attempted to ShallowCopy from null".
    vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
    if (mcx::IsDistributed(controller))
    {
      controller->Broadcast(&more, 1, 0);
    }
    if (more)
    {
      vtkPVRenderView::SetNextStreamedPiece(inInfo, this, this->MorePointsToken);
    }
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

bool vtkMCXXRayRepresentation::ServerRenders()
{
  // The same answer on every process: ParaView tells them all when the
  // server cannot render.
  auto* view = vtkPVRenderView::SafeDownCast(this->GetView());
  return view && view->GetRemoteRenderingAvailable();
}

void vtkMCXXRayRepresentation::SetVisibility(bool visible)
{
  this->Superclass::SetVisibility(visible);
  // Shown only once the view has connected the delivered index.
  this->Volume->SetVisibility(visible && this->Mapper->GetNumberOfInputConnections(0) > 0);
}

void vtkMCXXRayRepresentation::SetScalarOpacityFunction(vtkPiecewiseFunction* function)
{
  if (function != this->OpacityFunction)
  {
    this->ToldNotAttenuation = false; // a new TF is told again
  }
  this->OpacityFunction = function;
  this->Volume->GetProperty()->SetScalarOpacity(
    function ? function : this->DefaultRamp.GetPointer());
  this->MarkModified();
}

void vtkMCXXRayRepresentation::UseDefaultRampUnlessColoured(vtkImageData* index)
{
  if (this->OpacityFunction)
  {
    return;
  }
  // The index's density levels, lowest and highest.
  vtkDataArray* levels = index->GetFieldData()->GetArray(vtkMCXTypes::LevelValuesName());
  if (!levels || levels->GetNumberOfTuples() < 1)
  {
    return;
  }
  // 0 at the lowest density (-200 for CT in HU), 1 at the highest; a
  // constant volume gets 1.
  const double high = levels->GetTuple1(levels->GetNumberOfTuples() - 1);
  const double low = std::min(DefaultRampStart(levels->GetTuple1(0), high), high - 1.0);
  double range[2];
  this->DefaultRamp->GetRange(range);
  if (this->DefaultRamp->GetSize() != 2 || range[0] != low || range[1] != high)
  {
    this->DefaultRamp->RemoveAllPoints();
    this->DefaultRamp->AddPoint(low, 0.0);
    this->DefaultRamp->AddPoint(high, 1.0);
  }
  this->Volume->GetProperty()->SetScalarOpacity(this->DefaultRamp);
}

void vtkMCXXRayRepresentation::UseSampledFunction(vtkImageData* index)
{
  vtkPiecewiseFunction* weight =
    this->OpacityFunction ? this->OpacityFunction.GetPointer() : this->DefaultRamp.GetPointer();
  double range[2];
  if (this->Attenuation != HU_TO_MU || !mcx::IndexDensityRange(index, range))
  {
    this->Volume->GetProperty()->SetScalarOpacity(weight);
    // Radiograph physics of a TF that is not an attenuation per world unit:
    // line integrals of a 0-1 weight through a body are about 100.
    const double largest = mcx::LargestValue(weight);
    // (A polychromatic X-ray samples the materials' density, not the TF.)
    const char* spectrum = this->Mapper->GetSpectrum();
    if ((this->Mapper->GetBeerLambert() || this->Mapper->GetPhotonsPerPixel() > 0) &&
      largest > mcx::LargestAttenuation && !this->ToldNotAttenuation && !(spectrum && *spectrum))
    {
      vtkWarningMacro(<< mcx::NotAttenuationWarning(largest));
      this->ToldNotAttenuation = true;
    }
    return;
  }
  // mu(HU) x the weight, made again when the weight, mu of water or the
  // densities change (the editor's TF is never modified).
  const vtkMTimeType time = weight->GetMTime();
  if (weight != this->WeightedAttenuationOf || time != this->WeightedAttenuationTime ||
    this->WaterAttenuation != this->WeightedAttenuationWater ||
    range[0] != this->WeightedAttenuationRange[0] ||
    range[1] != this->WeightedAttenuationRange[1] || this->WeightedAttenuation->GetSize() == 0)
  {
    this->WeightedAttenuation->DeepCopy(
      mcx::WeightedAttenuation(weight, this->WaterAttenuation, range));
    this->WeightedAttenuationOf = weight;
    this->WeightedAttenuationTime = time;
    this->WeightedAttenuationWater = this->WaterAttenuation;
    this->WeightedAttenuationRange[0] = range[0];
    this->WeightedAttenuationRange[1] = range[1];
  }
  this->Volume->GetProperty()->SetScalarOpacity(this->WeightedAttenuation);
}

void vtkMCXXRayRepresentation::SetAttenuation(int mode)
{
  mode = std::min(std::max(mode, static_cast<int>(WEIGHT_ONLY)), static_cast<int>(HU_TO_MU));
  if (mode != this->Attenuation)
  {
    this->Attenuation = mode;
    this->ToldNotAttenuation = false;
    this->Modified();
  }
}

// Turning Beer-Lambert or noise on enters the combination the warning is about.
void vtkMCXXRayRepresentation::SetBeerLambert(bool on)
{
  this->ToldNotAttenuation &= !(on && !this->Mapper->GetBeerLambert());
  this->Mapper->SetBeerLambert(on);
}

void vtkMCXXRayRepresentation::SetPhotonsPerPixel(double photons)
{
  this->ToldNotAttenuation &= !(photons > 0 && !(this->Mapper->GetPhotonsPerPixel() > 0));
  this->Mapper->SetPhotonsPerPixel(photons);
}

void vtkMCXXRayRepresentation::SetNegativeLog(bool on)
{
  this->Mapper->SetNegativeLog(on);
}

void vtkMCXXRayRepresentation::SetSpectrum(const char* spectrum)
{
  this->Mapper->SetSpectrum(spectrum);
}

void vtkMCXXRayRepresentation::SetMaterials(const char* materials)
{
  this->Mapper->SetMaterials(materials);
}

void vtkMCXXRayRepresentation::SetDetector(const char* detector)
{
  this->Mapper->SetDetector(detector);
}

void vtkMCXXRayRepresentation::SetSampleExponent(int exponent)
{
  // The mapper stores the cloud: at most 2^MaximumPointCloudExponent - 1
  // points. Said before the render that would take the time and memory.
  const int stored = std::min(std::max(exponent, 0), vtkMCXTypes::MaximumPointCloudExponent);
  if (stored == this->Mapper->GetSampleExponent())
  {
    return;
  }
  const std::string cost = mcx::StoredCloudCost(stored);
  if (stored != exponent)
  {
    vtkWarningMacro("X-Ray Sample Exponent " << exponent << " is outside 0-"
                                             << vtkMCXTypes::MaximumPointCloudExponent << "; using "
                                             << stored << (cost.empty() ? "." : ": ") << cost);
  }
  else if (!cost.empty())
  {
    vtkWarningMacro("X-Ray Sample Exponent " << stored << ": " << cost);
  }
  this->Mapper->SetSampleExponent(stored);
}

void vtkMCXXRayRepresentation::SetStrategy(int strategy)
{
  this->Mapper->SetStrategy(strategy);
}

void vtkMCXXRayRepresentation::SetKernel(int kernel)
{
  this->Mapper->SetKernel(kernel);
}

void vtkMCXXRayRepresentation::SetDeposit(int deposit)
{
  this->Mapper->SetDeposit(deposit);
}

void vtkMCXXRayRepresentation::SetSeed(vtkTypeInt64 seed)
{
  this->Mapper->SetSeed(seed);
}

void vtkMCXXRayRepresentation::SetReorderAngle(double degrees)
{
  this->Mapper->SetReorderAngle(degrees);
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
  if (!automatic && this->Mapper->GetAutomaticWindowLevel())
  {
    // The manual window starts where the automatic one is.
    this->Mapper->SetColorWindow(this->Mapper->GetDisplayedWindow());
    this->Mapper->SetColorLevel(this->Mapper->GetDisplayedLevel());
  }
  this->Mapper->SetAutomaticWindowLevel(automatic);
}

double vtkMCXXRayRepresentation::GetDisplayedWindow()
{
  return this->Mapper->GetDisplayedWindow();
}

double vtkMCXXRayRepresentation::GetDisplayedLevel()
{
  return this->Mapper->GetDisplayedLevel();
}

void vtkMCXXRayRepresentation::SetColorWindow(double window)
{
  this->Mapper->SetColorWindow(window);
}

void vtkMCXXRayRepresentation::SetColorLevel(double level)
{
  this->Mapper->SetColorLevel(level);
}

void vtkMCXXRayRepresentation::SetInteractiveRenderTime(double seconds)
{
  seconds = std::min(std::max(seconds, 0.001), 10.0); // the XML's range
  if (this->InteractiveRenderTime != seconds)
  {
    this->InteractiveRenderTime = seconds;
    this->Modified();
  }
}

void vtkMCXXRayRepresentation::SetStillRenderTime(double seconds)
{
  seconds = std::min(std::max(seconds, 0.001), 1000.0); // the XML's range
  if (this->StillRenderTime != seconds)
  {
    this->StillRenderTime = seconds;
    this->Modified();
  }
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
  os << indent << "Slab: " << this->Slab.GetPointer() << "\n";
  os << indent << "Index: " << this->Index.GetPointer() << "\n";
  os << indent << "Aggregate: " << this->Aggregate.GetPointer() << "\n";
  os << indent << "Mapper: " << this->Mapper.GetPointer() << "\n";
  os << indent << "Volume: " << this->Volume.GetPointer() << "\n";
  os << indent << "DeliveredIndex: " << this->DeliveredIndex.GetPointer() << "\n";
  os << indent << "NoIndex: " << this->NoIndex.GetPointer() << "\n";
  os << indent << "OpacityFunction: " << this->OpacityFunction.GetPointer() << "\n";
  os << indent << "DefaultRamp: " << this->DefaultRamp.GetPointer() << "\n";
  os << indent << "InteractiveRenderTime: " << this->InteractiveRenderTime << "\n";
  os << indent << "StillRenderTime: " << this->StillRenderTime << "\n";
  os << indent << "MorePointsToken: " << this->MorePointsToken.GetPointer() << "\n";
  os << indent << "StreamedProgress: " << this->StreamedProgress << "\n";
  os << indent << "ToldServerCannotRender: " << this->ToldServerCannotRender << "\n";
  os << indent << "Attenuation: " << this->Attenuation << "\n";
  os << indent << "WaterAttenuation: " << this->WaterAttenuation << "\n";
  os << indent << "WeightedAttenuation: " << this->WeightedAttenuation.GetPointer() << "\n";
  os << indent << "WeightedAttenuationOf: " << this->WeightedAttenuationOf << "\n";
  os << indent << "WeightedAttenuationTime: " << this->WeightedAttenuationTime << "\n";
  os << indent << "WeightedAttenuationWater: " << this->WeightedAttenuationWater << "\n";
  os << indent << "WeightedAttenuationRange: " << this->WeightedAttenuationRange[0] << " "
     << this->WeightedAttenuationRange[1] << "\n";
  os << indent << "ToldNotAttenuation: " << this->ToldNotAttenuation << "\n";
  os << indent << "DataBounds: " << this->DataBounds[0] << " " << this->DataBounds[1] << " "
     << this->DataBounds[2] << " " << this->DataBounds[3] << " " << this->DataBounds[4] << " "
     << this->DataBounds[5] << "\n";
}
