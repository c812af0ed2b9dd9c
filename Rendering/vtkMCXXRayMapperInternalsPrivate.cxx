#include "vtkMCXXRayMapperInternalsPrivate.h"

#include "mcxAutomaticWindow.h"

#include "mcxHalton.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMCXCameraGeometry.h"
#include "vtkMCXCloudDeposit.h"
#include "vtkMCXIndexView.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace
{
// Whether any other visible prop in the renderer draws opaque 3D geometry
// that can hide part of the volume (an actor without geometry, as
// ParaView's views hold, draws nothing).
bool HasOccluders(vtkRenderer* renderer, vtkVolume* self)
{
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (prop != self && prop->GetVisibility() && prop->IsA("vtkProp3D") &&
      !prop->IsA("vtkVolume") && prop->HasOpaqueGeometry())
    {
      const double* bounds = prop->GetBounds();
      if (bounds && vtkMath::AreBoundsInitialized(bounds))
      {
        return true;
      }
    }
  }
  return false;
}

// Whether no pixel's depth limit (a distance along the view from the eye)
// hides any of the cloud's samples: every limit lies beyond the farthest
// corner of the sampler's support (SupportCorners, world coordinates: for
// a cloud drawn without a prop matrix): opaque props behind the volume
// need the depth test but hide nothing.
bool HidesNothing(
  const std::vector<double>& limits, vtkPolyData* cloud, const mcx::ProjectionGeometry& g)
{
  if (limits.empty())
  {
    return true;
  }
  double depths[2];
  return mcx::CloudSupportDepths(cloud, g, depths) &&
    std::all_of(
      limits.begin(), limits.end(), [&depths](double limit) { return limit > depths[1]; });
}

// Window 0 .. the automatic window (mcxAutomaticWindow.h), level at its
// middle; false (window unchanged) when the image is empty.
bool ChooseAutomaticWindow(
  const std::vector<float>& values, int width, int height, double& window, double& level)
{
  double chosen = 0;
  if (!mcx::AutomaticWindow(
        [&values](std::size_t p) { return static_cast<double>(values[p]); }, width, height, chosen))
  {
    return false;
  }
  window = chosen;
  level = 0.5 * chosen;
  return true;
}

// Eye distance (along the view direction) of a depth-buffer value; +inf for
// the far plane, where nothing was drawn.
double DepthToDistance(float depth, bool perspective, double nearPlane, double farPlane)
{
  if (!(depth < 1.0f))
  {
    return std::numeric_limits<double>::infinity();
  }
  if (perspective)
  {
    const double ndc = 2.0 * depth - 1.0;
    return 2.0 * nearPlane * farPlane / (farPlane + nearPlane - ndc * (farPlane - nearPlane));
  }
  return nearPlane + depth * (farPlane - nearPlane);
}
}

vtkPolyData* vtkMCXXRayMapper::vtkInternals::UpdateInput(
  vtkMCXXRayMapper* self, vtkVolume* volume, const View& view)
{
  int outputPort = 0;
  vtkAlgorithm* producer =
    self->GetNumberOfInputConnections(0) > 0 ? self->GetInputAlgorithm(0, 0, outputPort) : nullptr;
  if (!producer)
  {
    vtkErrorWithObjectMacro(
      self, "No input: connect a volume (vtkImageData) or a vtkMCXPointSampler.");
    return nullptr;
  }
  producer->Update(outputPort);
  vtkDataObject* input = self->GetInputDataObject(0, 0);
  vtkPolyData* cloud = vtkPolyData::SafeDownCast(input);
  this->Polychromatic = false;
  if (!self->GetSpectrum() || !*self->GetSpectrum())
  {
    this->Refused.clear(); // monochromatic: a later refusal is said again
  }
  if (auto* image = vtkImageData::SafeDownCast(input))
  {
    bool refused = false;
    this->Polychromatic = this->ConfigurePolychromatic(self, image, refused);
    if (refused)
    {
      return nullptr;
    }
    cloud = this->SampleVolume(self, image, volume, view);
    if (!cloud || !cloud->GetFieldData()->GetArray(vtkMCXTypes::IntegralName()))
    {
      return nullptr; // the index or the sampler said why
    }
    if (this->Polychromatic && !this->ShareChannels(self, image, cloud))
    {
      return nullptr;
    }
  }
  else if (self->GetSpectrum() && *self->GetSpectrum())
  {
    this->Refuse(self,
      "Cannot draw a polychromatic X-ray of a point cloud: a Spectrum needs the volume in HU as "
      "input (its voxels' materials).");
    return nullptr;
  }
  vtkDataArray* integral =
    cloud ? cloud->GetFieldData()->GetArray(vtkMCXTypes::IntegralName()) : nullptr;
  if (!integral || integral->GetNumberOfTuples() < 1)
  {
    vtkErrorWithObjectMacro(
      self, "The input carries no Integral in its field data (make it with vtkMCXPointSampler).");
    return nullptr;
  }
  vtkPoints* points = cloud->GetPoints();
  if (!mcx::CheckPointType(self, points))
  {
    return nullptr;
  }
  return this->UpdateWeights(self, cloud) ? cloud : nullptr;
}

vtkPolyData* vtkMCXXRayMapper::vtkInternals::SampleVolume(
  vtkMCXXRayMapper* self, vtkImageData* image, vtkVolume* volume, const View& view)
{
  if (!self->ConnectImageInput(image, true))
  {
    return nullptr;
  }
  // Polychromatic: the materials' total density, whatever the property's TF.
  vtkPiecewiseFunction* tf =
    this->Polychromatic ? this->Channels.Density() : volume->GetProperty()->GetScalarOpacity();
  return this->Sampling.Sample(tf, view.Camera, view.Size);
}

bool vtkMCXXRayMapper::vtkInternals::ConfigurePolychromatic(
  vtkMCXXRayMapper* self, vtkImageData* image, bool& refused)
{
  refused = false;
  const char* spectrum = self->GetSpectrum();
  if (!spectrum || !*spectrum)
  {
    return false;
  }
  std::string problem;
  if (self->GetDeposit() != vtkMCXTypes::FOOTPRINT ||
    self->GetStrategy() == vtkMCXTypes::EVERY_VOXEL)
  {
    problem = "a Spectrum needs the footprint deposit and a sampling strategy other than every "
              "voxel (its points are voxel centres, each with its voxel's materials)";
  }
  else if (!vtkMCXVolumeSampling::IsDensityIndex(image) &&
    !self->SelectDensityArray(image, problem))
  {
    problem = "the volume " + problem;
  }
  else
  {
    problem = this->Channels.Configure(spectrum, self->GetDetector() ? self->GetDetector() : "",
      self->GetMaterials() ? self->GetMaterials() : "");
  }
  if (!problem.empty())
  {
    this->Refuse(self, "Cannot draw a polychromatic X-ray: " + problem + ".");
    refused = true;
    return false;
  }
  this->Refused.clear();
  return true;
}

bool vtkMCXXRayMapper::vtkInternals::ShareChannels(
  vtkMCXXRayMapper* self, vtkImageData* image, vtkPolyData* cloud)
{
  std::string problem;
  vtkDataArray* values = vtkMCXVolumeSampling::IsDensityIndex(image)
    ? this->Channels.IndexValues(image)
    : self->SelectDensityArray(image, problem);
  problem =
    values ? this->Channels.UpdateShares(cloud, image, values) : "the density index cannot be read";
  if (!problem.empty())
  {
    this->Refuse(self, "Cannot draw a polychromatic X-ray: " + problem + ".");
    return false;
  }
  return true;
}

void vtkMCXXRayMapper::vtkInternals::Refuse(vtkMCXXRayMapper* self, const std::string& problem)
{
  if (problem != this->Refused)
  {
    vtkErrorWithObjectMacro(self, << problem);
    this->Refused = problem;
  }
}

bool vtkMCXXRayMapper::vtkInternals::UpdateWeights(vtkMCXXRayMapper* self, vtkPolyData* cloud)
{
  vtkDataArray* weights = cloud->GetPointData()->GetArray(vtkMCXTypes::PointWeightName());
  if (weights && weights == this->CheckedWeights &&
    weights->GetMTime() == this->CheckedWeightsTime &&
    weights->GetNumberOfTuples() == cloud->GetNumberOfPoints())
  {
    this->Weights = weights;
    return true;
  }
  bool valid = true;
  this->Weights = mcx::CloudPointWeights(self, cloud, valid);
  this->CheckedWeights = this->Weights;
  this->CheckedWeightsTime = this->Weights ? this->Weights->GetMTime() : 0;
  return valid;
}

bool vtkMCXXRayMapper::vtkInternals::ReadView(vtkMCXXRayMapper* self, vtkRenderer* renderer,
  vtkVolume* volume, vtkOpenGLRenderWindow* window, View& view)
{
  int x0 = 0, y0 = 0;
  renderer->GetTiledSizeAndOrigin(&view.Size[0], &view.Size[1], &x0, &y0);
  if (view.Size[0] < 1 || view.Size[1] < 1)
  {
    return false;
  }
  view.Camera = renderer->GetActiveCamera();
  // The renderer's tiled aspect ratio, as VTK's camera uses it: a tile of
  // a large screenshot (window centre and tiled viewport) is that part of
  // the large image.
  std::string problem = mcx::GeometryFromCamera(
    view.Camera, view.Size, 0.0, renderer->GetTiledAspectRatio(), view.Geometry);
  if (problem.empty())
  {
    problem = view.Geometry.Validate();
  }
  if (!problem.empty())
  {
    vtkErrorWithObjectMacro(self, "Cannot render this view: " << problem << ".");
    return false;
  }
  vtkMatrix4x4::DeepCopy(view.Matrix, volume->GetMatrix());
  // Depth work only when something opaque can hide part of the volume.
  self->LastRenderUsedDepth = HasOccluders(renderer, volume);
  if (self->LastRenderUsedDepth)
  {
    view.Depth = vtkMCXXRayDisplay::ReadDepth(window, x0, y0, view.Size[0], view.Size[1]);
  }
  return true;
}

bool vtkMCXXRayMapper::vtkInternals::RestartIfChanged(
  vtkMCXXRayMapper* self, vtkPolyData* cloud, View& view)
{
  const double reach = self->GetFootprintReach();
  // Polychromatic: a mode switch, or channels that no longer follow the
  // image (other materials), draw again.
  const bool newInput = cloud != this->Cloud || cloud->GetMTime() != this->CloudTime ||
    this->Polychromatic != this->ImagePolychromatic ||
    (this->Polychromatic && this->Image->Channels() != this->Channels.Size());
  if (this->HasImage && !newInput && mcx::SameGeometry(view.Geometry, this->Geometry) &&
    std::equal(view.Matrix, view.Matrix + 16, this->Matrix) && view.Depth == this->Depth &&
    reach == this->FootprintReach)
  {
    return false;
  }
  const Shelf& shelf = this->Shelved;
  // Not while the automatic window needs its source (the first points):
  // a restored image may hold more.
  const bool sourceStays =
    !self->GetAutomaticWindowLevel() || (this->WindowSourceKept && !this->AutomaticWindowPending);
  // A polychromatic image comes back with its channels (the materials,
  // part of the cloud's weights, are the cloud's time).
  const bool shelfFits = this->HasImage && sourceStays && shelf.Held &&
    shelf.Polychromatic == this->Polychromatic && cloud == shelf.Cloud &&
    cloud->GetMTime() == shelf.CloudTime && reach == shelf.FootprintReach &&
    mcx::SameGeometry(view.Geometry, shelf.Geometry) &&
    std::equal(view.Matrix, view.Matrix + 16, shelf.Matrix) && view.Depth == shelf.Depth;
  // The image on screen is set aside when it holds more points than the
  // shelf's (interactive frames do not push a refined image out).
  const bool onScreenKept = this->HasImage && !newInput;
  const bool shelve =
    onScreenKept && (shelfFits || !shelf.Held || this->Image->Count() > shelf.Image->Count());
  if (shelfFits || shelve)
  {
    this->SwapWithShelf();
    this->Shelved.Held = shelve;
  }
  else if (newInput)
  {
    this->Shelved.Held = false; // another input's image
  }
  const double* m = view.Matrix;
  const bool restart = !shelfFits;
  if (restart)
  {
    vtkCamera* camera = view.Camera;
    std::vector<double> limits(view.Depth.size());
    const double* range = camera->GetClippingRange();
    for (std::size_t p = 0; p < view.Depth.size(); ++p)
    {
      limits[p] = DepthToDistance(view.Depth[p], view.Geometry.Perspective, range[0], range[1]);
    }
    const bool hidesNothing = HidesNothing(limits, cloud, view.Geometry);
    const double origin[3] = { m[3], m[7], m[11] };
    const double linear[9] = { m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10] };
    const mcx::DepositSettings settings =
      mcx::CloudDepositSettings(cloud, view.Geometry, origin, linear, reach);
    this->ImagePolychromatic = this->Polychromatic;
    this->Image->Reset(view.Geometry, origin, linear, std::move(limits), settings);
    // Polychromatic: every deposit split into the materials' channels.
    this->Image->SetChannels(this->Polychromatic ? this->Channels.Size() : 0);
    this->Cloud = cloud;
    this->CloudTime = cloud->GetMTime();
    this->FootprintReach = reach;
    this->Geometry = view.Geometry;
    std::copy(m, m + 16, this->Matrix);
    this->Depth = std::move(view.Depth);
    // A view-ordered cloud's control image holds for its own frame (no prop
    // matrix) with every sample visible.
    static const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    if (hidesNothing && std::equal(m, m + 16, identity))
    {
      double variance = 0.0;
      std::vector<double> control = mcx::CloudControlImage(cloud, view.Geometry, variance);
      if (!control.empty())
      {
        this->Image->SetControl(std::move(control),
          cloud->GetFieldData()->GetArray(vtkMCXTypes::IntegralName())->GetTuple1(0), variance);
      }
    }
  }
  this->HasImage = true;
  vtkPoints* points = cloud->GetPoints();
  this->NumberOfPoints = points ? static_cast<std::uint64_t>(points->GetNumberOfPoints()) : 0;
  this->EveryVoxel = mcx::IsEveryVoxelCloud(cloud);
  const double integral =
    cloud->GetFieldData()->GetArray(vtkMCXTypes::IntegralName())->GetTuple1(0);
  this->ScaledIntegral = integral * std::fabs(vtkMatrix4x4::Determinant(m));
  this->UploadedCount = std::numeric_limits<std::uint64_t>::max();
  this->MappedErrorCount = std::numeric_limits<std::uint64_t>::max(); // another image
  this->AutomaticWindowPending = this->AutomaticWindowPending || newInput;
  // A new input needs a new source; so does a new view while the last
  // source showed nothing (the camera had not reached the volume yet).
  this->WindowSourceKept = this->WindowSourceKept && !newInput && !this->AutomaticWindowPending;
  return restart;
}

void vtkMCXXRayMapper::vtkInternals::SwapWithShelf()
{
  Shelf& shelf = this->Shelved;
  std::swap(this->Image, shelf.Image);
  std::swap(this->ImagePolychromatic, shelf.Polychromatic);
  std::swap(this->Cloud, shelf.Cloud);
  std::swap(this->CloudTime, shelf.CloudTime);
  std::swap(this->FootprintReach, shelf.FootprintReach);
  std::swap(this->Geometry, shelf.Geometry);
  std::swap_ranges(this->Matrix, this->Matrix + 16, shelf.Matrix);
  std::swap(this->Depth, shelf.Depth);
}

std::uint64_t vtkMCXXRayMapper::vtkInternals::WindowPrefix(const int size[2]) const
{
  if (this->EveryVoxel)
  {
    // Its prefixes are runs of neighbours, brighter where a run lands:
    // their top percentile would set too wide a window. The whole cloud
    // costs one pass over its voxels, as a TF edit does.
    return this->NumberOfPoints;
  }
  const double wanted = 4.0 * size[0] * size[1];
  std::uint64_t prefix = 1;
  while (static_cast<double>(prefix) < wanted && prefix < this->NumberOfPoints)
  {
    prefix = 2 * prefix + 1;
  }
  return std::min(prefix, this->NumberOfPoints);
}

void vtkMCXXRayMapper::vtkInternals::KeepWindowSource(vtkPoints* points, const int size[2])
{
  const std::uint64_t prefix = this->WindowPrefix(size);
  if (this->Image->Count() < prefix)
  {
    this->Advance(points, prefix);
  }
  this->WindowSource.resize(this->Image->NumberOfPixels());
  if (this->Polychromatic)
  {
    this->Channels.KeepWindowSource(*this->Image, this->SampleWeight());
  }
  else
  {
    this->Image->ToValues(this->SampleWeight(), this->WindowSource.data());
  }
  this->WindowSourceSize[0] = size[0];
  this->WindowSourceSize[1] = size[1];
  this->WindowSourceKept = true;
}

bool vtkMCXXRayMapper::vtkInternals::ChooseWindowFromSource()
{
  std::vector<float> values = this->WindowSource;
  if (this->ImagePolychromatic)
  {
    // The kept channels under the current model: a spectrum change chooses
    // its window from the same points.
    std::vector<double> effective;
    this->Channels.WindowSourceValues(effective);
    std::copy(effective.begin(), effective.end(), values.begin());
  }
  if (this->Effects.Any())
  {
    float* v = values.data();
    this->Effects.ApplyToImage(
      mcx::SMPExecutor(), static_cast<std::int64_t>(values.size()),
      [v](std::int64_t p) { return static_cast<double>(v[p]); }, v);
  }
  return ChooseAutomaticWindow(values, this->WindowSourceSize[0], this->WindowSourceSize[1],
    this->AutomaticWindow, this->AutomaticLevel);
}

bool vtkMCXXRayMapper::vtkInternals::UploadIfChanged(
  vtkOpenGLRenderWindow* window, const mcx::RadiographEffects& effects, const int size[2])
{
  const bool newModel =
    this->ImagePolychromatic && this->Channels.ModelVersion() != this->MappedVersion;
  const bool newEffects = effects != this->Effects;
  if (newEffects || newModel)
  {
    this->Effects = effects;
    this->AutomaticWindowPending = true; // other quantity, other scale
  }
  if (!newEffects && !newModel && this->Image->Count() == this->UploadedCount &&
    this->Display.HasImageIn(window))
  {
    return false;
  }
  this->Upload(window, size[0], size[1]);
  return true;
}

double vtkMCXXRayMapper::vtkInternals::SampleWeight() const
{
  const double carried = this->Image->CountedWeight();
  return carried > 0 ? this->ScaledIntegral / carried : 0.0;
}

std::uint64_t vtkMCXXRayMapper::vtkInternals::RefinementTarget(double budget, double floor) const
{
  const std::uint64_t current = this->Image->Count();
  const double affordable = budget > 0 && std::isfinite(budget)
    ? static_cast<double>(current) + budget / this->SecondsPerSample
    : std::numeric_limits<double>::infinity();
  std::uint64_t prefix = 2 * current + 1;
  while (prefix < this->NumberOfPoints &&
    (static_cast<double>(2 * prefix + 1) <= affordable || static_cast<double>(prefix) < floor))
  {
    prefix = 2 * prefix + 1;
  }
  return std::min(prefix, this->NumberOfPoints);
}

void vtkMCXXRayMapper::vtkInternals::Advance(vtkPoints* points, std::uint64_t target)
{
  const std::uint64_t current = this->Image->Count();
  const auto start = std::chrono::steady_clock::now();
  // Polychromatic: each point's deposit split by its shares, in the same pass.
  const mcx::PointShares* shares = this->ImagePolychromatic ? this->Channels.Shares() : nullptr;
  mcx::WithPointWeights(this->Weights,
    [&](const auto* weights)
    {
      if (points->GetDataType() == VTK_FLOAT)
      {
        this->Image->Advance(mcx::SMPExecutor(),
          static_cast<const float*>(points->GetVoidPointer(0)), target, weights, shares);
      }
      else
      {
        this->Image->Advance(mcx::SMPExecutor(),
          static_cast<const double*>(points->GetVoidPointer(0)), target, weights, shares);
      }
    });
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::uint64_t added = target - current;
  if (added >= 4096 && seconds > 0)
  {
    this->SecondsPerSample = 0.5 * (this->SecondsPerSample + seconds / static_cast<double>(added));
  }
}

void vtkMCXXRayMapper::vtkInternals::Upload(vtkOpenGLRenderWindow* window, int width, int height)
{
  this->Values.resize(this->Image->NumberOfPixels());
  this->ImageValues(this->Values.data());
  if (this->Effects.Any())
  {
    float* values = this->Values.data();
    this->Effects.ApplyToImage(
      mcx::SMPExecutor(), static_cast<std::int64_t>(this->Values.size()),
      [values](std::int64_t p) { return static_cast<double>(values[p]); }, values);
  }
  if (this->AutomaticWindowPending && this->WindowSourceKept && this->ChooseWindowFromSource())
  {
    this->AutomaticWindowPending = false;
  }
  this->Display.Upload(window, width, height, this->Values.data());
  this->UploadedCount = this->Image->Count();
}

void vtkMCXXRayMapper::vtkInternals::ImageValues(float* values)
{
  if (!this->ImagePolychromatic)
  {
    this->Image->ToValues(this->SampleWeight(), values);
    return;
  }
  std::vector<double> effective;
  this->Channels.EffectiveValues(*this->Image, this->SampleWeight(), effective, &this->MappedError);
  std::copy(effective.begin(), effective.end(), values);
  this->MappedVersion = this->Channels.ModelVersion();
  this->MappedErrorCount = this->Image->Count();
}
