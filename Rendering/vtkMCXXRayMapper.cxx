#include "vtkMCXXRayMapper.h"
#include "vtkMCXXRayMapperInternalsPrivate.h"

#include "mcxHalton.h"
#include "mcxRadiographEffects.h"
#include "vtkMCXCloudDeposit.h"
#include "vtkMCXDensityIndex.h"

#include "vtkAbstractMapper.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerKey.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXProjectorBase.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <stdexcept>
#include <vector>

vtkStandardNewMacro(vtkMCXXRayMapper);
vtkInformationKeyMacro(vtkMCXXRayMapper, FILM_LAID, Integer);
vtkInformationKeyMacro(vtkMCXXRayMapper, FILM_RESET_INSTALLED, Integer);

namespace
{
// The radiograph physics the mapper's properties ask for.
mcx::RadiographEffects EffectsOf(vtkMCXXRayMapper* self)
{
  return mcx::RadiographEffects::FromProperties(self->GetBeerLambert(),
    self->GetIncidentIntensity(), self->GetPhotonsPerPixel(),
    static_cast<std::uint64_t>(self->GetNoiseSeed()), self->GetNegativeLog());
}

// The sampling settings of an image input.
vtkMCXVolumeSampling::Settings SamplingSettingsOf(vtkMCXXRayMapper* self)
{
  return { self->GetSampleExponent(), self->GetStrategy(), self->GetKernel(), self->GetDeposit(),
    self->GetSeed(), self->GetReorderAngle() };
}

// `output` framed as the image of `g`, with its LineIntegral scalars of
// `pixels` values to fill.
vtkDoubleArray* FrameLineIntegral(
  const mcx::ProjectionGeometry& g, std::size_t pixels, vtkImageData* output)
{
  output->SetExtent(0, g.Size[0] - 1, 0, g.Size[1] - 1, 0, 0);
  output->SetOrigin(g.Origin[0], g.Origin[1], 0.0);
  output->SetSpacing(g.Spacing[0], g.Spacing[1], 1.0);
  vtkNew<vtkDoubleArray> values;
  values->SetName(vtkMCXTypes::LineIntegralName());
  values->SetNumberOfValues(static_cast<vtkIdType>(pixels));
  output->GetPointData()->SetScalars(values);
  return values;
}
}

vtkMCXXRayMapper::vtkMCXXRayMapper()
  : Internals(new vtkInternals)
{
  this->SetMaterials("default");
  this->SetDetector("integrating");
}

vtkMCXXRayMapper::~vtkMCXXRayMapper()
{
  this->SetSpectrum(nullptr);
  this->SetMaterials(nullptr);
  this->SetDetector(nullptr);
  delete this->Internals;
}

int vtkMCXXRayMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

void vtkMCXXRayMapper::SetInputData(vtkImageData* volume)
{
  this->SetInputDataInternal(0, volume);
}

void vtkMCXXRayMapper::SetInputData(vtkPolyData* cloud)
{
  this->SetInputDataInternal(0, cloud);
}

vtkDataArray* vtkMCXXRayMapper::SelectDensityArray(vtkImageData* image, std::string& problem)
{
  int cellFlag = 0;
  vtkDataArray* density = vtkArrayDownCast<vtkDataArray>(vtkAbstractMapper::GetAbstractScalars(
    image, this->ScalarMode, this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag));
  if (!density)
  {
    problem = this->ScalarMode == VTK_SCALAR_MODE_DEFAULT
      ? "it has no point scalars (select a one-component point array)"
      : "the selected array is not among its point data";
  }
  else if (cellFlag != 0)
  {
    problem = "the selected array is cell data; the X-ray needs densities at the points";
    density = nullptr;
  }
  else if (density->GetNumberOfComponents() != 1)
  {
    problem = "the selected array has " + std::to_string(density->GetNumberOfComponents()) +
      " components; select a one-component density array";
    density = nullptr;
  }
  else if ((!density->GetName() || !*density->GetName()) &&
    density != image->GetPointData()->GetScalars())
  {
    problem = "the selected array has no name; name it or make it the active scalars";
    density = nullptr;
  }
  return density;
}

vtkTypeInt64 vtkMCXXRayMapper::GetNumberOfInputPoints()
{
  return this->Internals->HasImage ? static_cast<vtkTypeInt64>(this->Internals->NumberOfPoints) : 0;
}

vtkTypeInt64 vtkMCXXRayMapper::GetNumberOfAccumulatedSamples()
{
  return this->Internals->HasImage ? static_cast<vtkTypeInt64>(this->Internals->Image->Count()) : 0;
}

bool vtkMCXXRayMapper::IsRefinementComplete()
{
  return this->Internals->HasImage &&
    this->Internals->Image->Count() >= this->Internals->NumberOfPoints;
}

double vtkMCXXRayMapper::GetEstimatedRelativeError()
{
  const vtkInternals& in = *this->Internals;
  if (in.HasImage && in.ImagePolychromatic)
  {
    if (in.MappedErrorCount == in.Image->Count() && in.MappedVersion == in.Channels.ModelVersion())
    {
      return in.MappedError; // what the image on screen was uploaded with
    }
    std::vector<double> effective;
    double error = std::nan("");
    in.Channels.EffectiveValues(*in.Image, in.SampleWeight(), effective, &error);
    return error;
  }
  // Every voxel once: nothing to estimate, unless nothing was drawn (0).
  return in.HasImage && !(in.EveryVoxel && in.Image->Count() > 0)
    ? in.Image->EstimateRelativeError()
    : std::nan("");
}

bool vtkMCXXRayMapper::GetLastRenderUsedControlImage()
{
  return this->Internals->HasImage && this->Internals->Image->IsControlled();
}

void vtkMCXXRayMapper::GetLineIntegralImage(vtkImageData* output)
{
  output->Initialize();
  vtkInternals& in = *this->Internals;
  if (!in.HasImage)
  {
    return;
  }
  vtkDoubleArray* values =
    FrameLineIntegral(in.Image->GetGeometry(), in.Image->NumberOfPixels(), output);
  const std::uint64_t count = in.Image->Count();
  if (in.ImagePolychromatic)
  {
    std::vector<double> effective;
    in.Channels.EffectiveValues(*in.Image, in.SampleWeight(), effective);
    std::copy(effective.begin(), effective.end(), values->GetPointer(0));
  }
  else
  {
    in.Image->ToValues(in.SampleWeight(), values->GetPointer(0));
  }
  mcx::AddFieldValue(
    output->GetFieldData(), vtkMCXTypes::SampleCountName(), static_cast<long long>(count));
  mcx::AddFieldValue(output->GetFieldData(), vtkMCXTypes::EstimatedRelativeErrorName(),
    this->GetEstimatedRelativeError());
}

int vtkMCXXRayMapper::GetNumberOfChannels()
{
  const vtkInternals& in = *this->Internals;
  return in.HasImage && in.ImagePolychromatic ? in.Channels.Size() : 0;
}

void vtkMCXXRayMapper::GetChannelImage(int m, vtkImageData* output)
{
  output->Initialize();
  vtkInternals& in = *this->Internals;
  if (m < 0 || m >= this->GetNumberOfChannels())
  {
    return;
  }
  vtkDoubleArray* values =
    FrameLineIntegral(in.Image->GetGeometry(), in.Image->NumberOfPixels(), output);
  in.Image->ChannelToValues(m, in.SampleWeight(), values->GetPointer(0));
  mcx::AddFieldValue(output->GetFieldData(), vtkMCXTypes::SampleCountName(),
    static_cast<long long>(in.Image->Count()));
  mcx::AddFieldValue(output->GetFieldData(), vtkMCXTypes::EstimatedRelativeErrorName(),
    in.Image->ChannelRelativeError(m));
}

void vtkMCXXRayMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  // An allocation can fail under an address-space limit however the budget
  // was checked: an error, and the next render starts over.
  try
  {
    this->RenderImage(renderer, volume);
  }
  catch (const std::bad_alloc&)
  {
    this->Internals->HasImage = false;
    vtkErrorMacro("Out of memory rendering the X-ray image.");
  }
  catch (const std::length_error& error)
  {
    this->Internals->HasImage = false;
    vtkErrorMacro("Cannot render the X-ray image: " << error.what() << ".");
  }
}

void vtkMCXXRayMapper::RenderImage(vtkRenderer* renderer, vtkVolume* volume)
{
  const auto start = std::chrono::steady_clock::now();
  vtkInternals& in = *this->Internals;
  vtkOpenGLRenderWindow* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    vtkErrorMacro("vtkMCXXRayMapper needs an OpenGL render window.");
    return;
  }
  vtkInternals::View view;
  if (!in.ReadView(this, renderer, volume, window, view))
  {
    return;
  }
  vtkPolyData* cloud = in.UpdateInput(this, volume, view);
  if (!cloud)
  {
    return;
  }
  const bool needWindowSource = this->AutomaticWindowLevel && !in.WindowSourceKept;
  if (needWindowSource && in.HasImage && in.Image->Count() > in.WindowPrefix(view.Size))
  {
    in.HasImage = false; // the window's prefix has passed: project again from its start
  }
  const bool restart = in.RestartIfChanged(this, cloud, view);
  if (restart)
  {
    ++this->NumberOfRestarts;
  }
  bool sourceMade = false; // this render projected the automatic window's prefix
  if (this->AutomaticWindowLevel && !in.WindowSourceKept)
  {
    in.KeepWindowSource(cloud->GetPoints(), view.Size);
    sourceMade = true;
  }
  const double floor =
    static_cast<double>(mcx::SampleCount(static_cast<unsigned>(this->InitialSampleExponent)));
  std::uint64_t target = in.NumberOfPoints;
  if (this->ProgressiveRefinement)
  {
    // A render that made the window's prefix shows it (at least 4 points a
    // pixel); later renders add what the time budget affords.
    target = sourceMade && static_cast<double>(in.Image->Count()) >= floor
      ? in.Image->Count()
      : in.RefinementTarget(this->RenderTimeBudget(volume), floor);
  }
  if (target > in.Image->Count())
  {
    in.Advance(cloud->GetPoints(), target); // stage 4: refine within the time budget
    if (!restart)
    {
      ++this->NumberOfRefinements;
    }
  }
  if (in.UploadIfChanged(window, EffectsOf(this), view.Size))
  {
    ++this->NumberOfUploads;
  }
  this->DisplayedWindow = this->AutomaticWindowLevel ? in.AutomaticWindow : this->ColorWindow;
  this->DisplayedLevel = this->AutomaticWindowLevel ? in.AutomaticLevel : this->ColorLevel;
  const double lowest = this->DisplayedLevel - 0.5 * this->DisplayedWindow;
  const double inverseWindow =
    this->DisplayedWindow > 0 ? 1.0 / this->DisplayedWindow : std::numeric_limits<float>::max();
  const bool film = this->Compositing == FILM && this->TakeFilm(renderer, volume);
  vtkMCXXRayDisplay::Blending blending;
  blending.Invert = this->InvertDisplay;
  blending.Film = film;
  blending.OverGeometry = this->LastRenderUsedDepth;
  blending.CompositedByDepth = this->CompositedByDepth;
  if (!in.Display.Draw(window, lowest, inverseWindow, blending))
  {
    vtkErrorMacro("The X-ray display shader failed to compile.");
    return;
  }
  ++this->NumberOfDraws;
  this->TimeToDraw =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double* vtkMCXXRayMapper::GetBounds()
{
  vtkMath::UninitializeBounds(this->Bounds);
  if (this->GetNumberOfInputConnections(0) < 1)
  {
    return this->Bounds;
  }
  this->Update();
  vtkDataObject* input = this->GetInputDataObject(0, 0);
  double corners[24];
  if (this->SupportCorners(input, corners))
  {
    for (int c = 0; c < 8; ++c)
    {
      for (int a = 0; a < 3; ++a)
      {
        const double x = corners[3 * c + a];
        this->Bounds[2 * a] = c == 0 ? x : std::min(this->Bounds[2 * a], x);
        this->Bounds[2 * a + 1] = c == 0 ? x : std::max(this->Bounds[2 * a + 1], x);
      }
    }
  }
  else if (auto* data = vtkDataSet::SafeDownCast(input))
  {
    if (data->GetNumberOfPoints() > 0)
    {
      data->GetBounds(this->Bounds);
    }
  }
  return this->Bounds;
}

bool vtkMCXXRayMapper::SupportCorners(vtkDataObject* input, double corners[24])
{
  auto* image = vtkImageData::SafeDownCast(input);
  if (!image)
  {
    return mcx::CloudSupportCorners(input, corners);
  }
  // An image's support is the sampler's, known before any point is drawn.
  return this->ConnectImageInput(image, false) && this->Internals->Sampling.SupportCorners(corners);
}

bool vtkMCXXRayMapper::ConnectImageInput(vtkImageData* image, bool report)
{
  vtkDataArray* density = nullptr;
  if (!vtkMCXVolumeSampling::IsDensityIndex(image))
  {
    std::string problem;
    density = this->SelectDensityArray(image, problem);
    if (!density)
    {
      if (report)
      {
        vtkErrorMacro("Cannot draw this volume as an X-ray: " << problem << ".");
      }
      return false;
    }
  }
  vtkMCXVolumeSampling& sampling = this->Internals->Sampling;
  sampling.Connect(this->GetInputConnection(0, 0), image, density);
  sampling.Configure(SamplingSettingsOf(this));
  return true;
}

void vtkMCXXRayMapper::UpdateDensityIndex()
{
  if (this->GetNumberOfInputConnections(0) < 1)
  {
    return;
  }
  this->Update();
  auto* image = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  if (image && !vtkMCXVolumeSampling::IsDensityIndex(image) && this->ConnectImageInput(image, true))
  {
    this->Internals->Sampling.GetIndex()->Update();
  }
}

vtkMCXDensityIndex* vtkMCXXRayMapper::GetDensityIndex()
{
  return this->Internals->Sampling.GetIndex();
}

vtkMCXPointSampler* vtkMCXXRayMapper::GetPointSampler()
{
  return this->Internals->Sampling.GetSampler();
}

bool vtkMCXXRayMapper::TakeFilm(vtkRenderer* renderer, vtkVolume* volume)
{
  vtkInformation* info = renderer->GetInformation();
  if (!info->Has(FILM_RESET_INSTALLED()))
  {
    // Each render of the renderer starts without film; the callback keeps
    // no pointer to this mapper.
    vtkNew<vtkCallbackCommand> reset;
    reset->SetCallback([](vtkObject* caller, unsigned long, void*, void*)
      { static_cast<vtkRenderer*>(caller)->GetInformation()->Set(FILM_LAID(), 0); });
    renderer->AddObserver(vtkCommand::StartEvent, reset);
    info->Set(FILM_RESET_INSTALLED(), 1);
  }
  if (info->Has(FILM_LAID()) && info->Get(FILM_LAID()) != 0)
  {
    return false; // another X-ray laid it this render: add to it
  }
  // Translucent props draw no depth: film would cover them.
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (prop != volume && prop->GetVisibility() && !prop->IsA("vtkVolume") &&
      prop->HasTranslucentPolygonalGeometry())
    {
      return false;
    }
  }
  info->Set(FILM_LAID(), 1);
  return true;
}

double vtkMCXXRayMapper::RenderTimeBudget(vtkVolume* volume) const
{
  const double allocated = volume->GetAllocatedRenderTime();
  return this->MaximumRenderTime > 0 && !(allocated < this->MaximumRenderTime)
    ? this->MaximumRenderTime
    : allocated;
}

void vtkMCXXRayMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& in = *this->Internals;
  in.Display.ReleaseGraphicsResources(window);
  in.UploadedCount = std::numeric_limits<std::uint64_t>::max();
}

void vtkMCXXRayMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleExponent: " << this->SampleExponent << "\n";
  os << indent << "Strategy: " << vtkMCXTypes::StrategyCommandName(this->Strategy) << "\n";
  os << indent << "Kernel: " << vtkMCXTypes::KernelCommandName(this->Kernel) << "\n";
  os << indent << "Deposit: " << vtkMCXTypes::DepositCommandName(this->Deposit) << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "ReorderAngle: " << this->ReorderAngle << "\n";
  os << indent << "ColorWindow: " << this->ColorWindow << "\n";
  os << indent << "ColorLevel: " << this->ColorLevel << "\n";
  os << indent << "AutomaticWindowLevel: " << this->AutomaticWindowLevel << "\n";
  os << indent << "DisplayedWindow: " << this->DisplayedWindow << "\n";
  os << indent << "DisplayedLevel: " << this->DisplayedLevel << "\n";
  os << indent << "InvertDisplay: " << this->InvertDisplay << "\n";
  os << indent << "Compositing: " << (this->Compositing == FILM ? "FILM" : "ADDITIVE") << "\n";
  os << indent << "CompositedByDepth: " << this->CompositedByDepth << "\n";
  os << indent << "BeerLambert: " << this->BeerLambert << "\n";
  os << indent << "IncidentIntensity: " << this->IncidentIntensity << "\n";
  os << indent << "PhotonsPerPixel: " << this->PhotonsPerPixel << "\n";
  os << indent << "NoiseSeed: " << this->NoiseSeed << "\n";
  os << indent << "NegativeLog: " << this->NegativeLog << "\n";
  os << indent << "ProgressiveRefinement: " << this->ProgressiveRefinement << "\n";
  os << indent << "InitialSampleExponent: " << this->InitialSampleExponent << "\n";
  os << indent << "MaximumRenderTime: " << this->MaximumRenderTime << "\n";
  os << indent << "FootprintReach: " << this->FootprintReach << "\n";
  os << indent << "Spectrum: " << (this->Spectrum ? this->Spectrum : "(none)") << "\n";
  os << indent << "Materials: " << (this->Materials ? this->Materials : "(none)") << "\n";
  os << indent << "Detector: " << (this->Detector ? this->Detector : "(none)") << "\n";
  os << indent << "NumberOfChannels: " << this->GetNumberOfChannels() << "\n";
  os << indent << "NumberOfAccumulatedSamples: " << this->GetNumberOfAccumulatedSamples() << "\n";
  os << indent << "NumberOfRestarts: " << this->NumberOfRestarts << "\n";
  os << indent << "NumberOfRefinements: " << this->NumberOfRefinements << "\n";
  os << indent << "NumberOfUploads: " << this->NumberOfUploads << "\n";
  os << indent << "NumberOfDraws: " << this->NumberOfDraws << "\n";
  os << indent << "LastRenderUsedDepth: " << this->LastRenderUsedDepth << "\n";
  os << indent << "LastRenderUsedControlImage: " << this->GetLastRenderUsedControlImage() << "\n";
}
