#include "vtkMCXXRayMapper.h"

#include "mcxHalton.h"
#include "mcxProgressiveImage.h"
#include "mcxRadiographEffects.h"
#include "vtkMCXCameraGeometryPrivate.h"
#include "vtkMCXCloudDepositPrivate.h"
#include "vtkMCXIndexViewPrivate.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXRadiograph.h"
#include "vtkMCXSMPExecutorPrivate.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerKey.h"
#include "vtkMCXProjectorBase.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtk_glew.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

vtkStandardNewMacro(vtkMCXXRayMapper);
vtkInformationKeyMacro(vtkMCXXRayMapper, FILM_LAID, Integer);
vtkInformationKeyMacro(vtkMCXXRayMapper, FILM_RESET_INSTALLED, Integer);

namespace
{
// Maps a line integral to a grey value g (window and level), and composites
// it as emitted light or, inverted, as a transmission factor.
const char* DisplayShaderDeclarations = R"(
uniform sampler2D lineIntegrals;
uniform float lowest;
uniform float inverseWindow;
uniform int invert;
uniform float imageDepth;
)";
const char* DisplayShaderBody = R"(
  float g = clamp((texture(lineIntegrals, texCoord).r - lowest) * inverseWindow, 0.0, 1.0);
  if (invert == 1)
  {
    g = 1.0 - g;
  }
  gl_FragData[0] = vec4(g, g, g, 1.0);
  gl_FragDepth = imageDepth; // at the far plane: depth tests tell film from geometry in front
)";

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

// Window 0 .. the 99.5th percentile of the positive means of 4 x 4 pixel
// blocks: the blocks average out most of a coarse image's noise, which would
// otherwise push a high percentile up. False (window unchanged) when the
// image is empty.
bool ChooseAutomaticWindow(
  const std::vector<float>& values, int width, int height, double& window, double& level)
{
  std::vector<double> blocks;
  for (int by = 0; by < height; by += 4)
  {
    for (int bx = 0; bx < width; bx += 4)
    {
      double sum = 0;
      int n = 0;
      for (int y = by; y < std::min(height, by + 4); ++y)
      {
        for (int x = bx; x < std::min(width, bx + 4); ++x, ++n)
        {
          sum += values[static_cast<std::size_t>(y) * width + x];
        }
      }
      if (sum > 0)
      {
        blocks.push_back(sum / n);
      }
    }
  }
  if (blocks.empty())
  {
    return false;
  }
  auto rank =
    blocks.begin() + static_cast<std::ptrdiff_t>(0.995 * static_cast<double>(blocks.size() - 1));
  std::nth_element(blocks.begin(), rank, blocks.end());
  window = *rank;
  level = 0.5 * *rank;
  return true;
}

// The radiograph physics the mapper's properties ask for.
mcx::RadiographEffects EffectsOf(vtkMCXXRayMapper* self)
{
  return mcx::RadiographEffects::FromProperties(self->GetBeerLambert(),
    self->GetIncidentIntensity(), self->GetPhotonsPerPixel(),
    static_cast<std::uint64_t>(self->GetNoiseSeed()), self->GetNegativeLog());
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
// The depth buffer of the viewport as drawn so far (the opaque geometry).
std::vector<float> ReadDepth(vtkOpenGLRenderWindow* window, int x0, int y0, int width, int height)
{
  std::vector<float> depth(static_cast<std::size_t>(width) * height);
  vtkOpenGLState* state = window->GetState();
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  if (samples > 0)
  {
    // The render window knows how to resolve its multisampled buffer.
    vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
    window->GetZbufferData(x0, y0, x0 + width - 1, y0 + height - 1, depth.data());
    return depth;
  }
  GLint drawFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
  state->PushReadFramebufferBinding();
  state->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<unsigned int>(drawFramebuffer));
  state->vtkglPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x0, y0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  state->PopReadFramebufferBinding();
  return depth;
}
}

struct vtkMCXXRayMapper::vtkInternals
{
  mcx::ProgressiveImage<mcx::SMPExecutor> Image;
  bool HasImage = false;

  // What the image on screen was made from.
  vtkPolyData* Cloud = nullptr;    // compared only, never dereferenced
  vtkDataArray* Weights = nullptr; // the input's checked PointWeight (null: none), set each render
  vtkDataArray* CheckedWeights = nullptr; // compared only, never dereferenced
  vtkMTimeType CheckedWeightsTime = 0;
  vtkMTimeType CloudTime = 0;
  double FootprintReach = 0.0; // of the image on screen
  mcx::ProjectionGeometry Geometry;
  double Matrix[16] = { 0 };
  std::vector<float> Depth;
  double ScaledIntegral = 0.0; // the cloud's integral times |det| of the prop matrix
  std::uint64_t NumberOfPoints = 0;
  bool EveryVoxel = false; // the input is an every-voxel cloud: no error estimate
  bool AutomaticWindowPending = true;
  double AutomaticWindow = 1.0;
  double AutomaticLevel = 0.5;
  // The automatic window's source: the line integrals of the first
  // WindowPrefix points of the current input, whatever the sample count and
  // the time budget (so the window is a property of the image, not of the
  // noise of however many points the first render happened to afford).
  std::vector<float> WindowSource;
  int WindowSourceSize[2] = { 0, 0 };
  bool WindowSourceKept = false;

  double SecondsPerSample = 1e-8; // measured, for the progressive budget

  std::vector<float> Values;
  std::uint64_t UploadedCount = 0;
  mcx::RadiographEffects Effects; // what the uploaded values went through
  vtkSmartPointer<vtkTextureObject> Texture;
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;

  // What a render sees: the camera's geometry for the viewport, the prop's
  // matrix and, when opaque props can hide samples, the depth buffer.
  struct View
  {
    vtkCamera* Camera = nullptr;
    mcx::ProjectionGeometry Geometry;
    int Size[2] = { 0, 0 };
    double Matrix[16] = { 0 };
    std::vector<float> Depth;
  };

  // Stage 1: brings the input up to date; null (reported) when it is not a
  // sampler's cloud.
  vtkPolyData* UpdateInput(vtkMCXXRayMapper* self)
  {
    int outputPort = 0;
    vtkAlgorithm* producer = self->GetNumberOfInputConnections(0) > 0
      ? self->GetInputAlgorithm(0, 0, outputPort)
      : nullptr;
    if (!producer)
    {
      vtkErrorWithObjectMacro(self, "No input: connect a vtkMCXPointSampler.");
      return nullptr;
    }
    producer->Update(outputPort);
    vtkPolyData* cloud = vtkPolyData::SafeDownCast(self->GetInputDataObject(0, 0));
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

  // The input's point weights for this render: checked once per array
  // version (a scan of every weight), not on every progressive frame.
  bool UpdateWeights(vtkMCXXRayMapper* self, vtkPolyData* cloud)
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

  // Stage 2: the view of this render; false when there is nothing to draw
  // (an empty viewport) or the camera is unusable (reported).
  bool ReadView(vtkMCXXRayMapper* self, vtkRenderer* renderer, vtkVolume* volume,
    vtkOpenGLRenderWindow* window, View& view)
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
      view.Depth = ReadDepth(window, x0, y0, view.Size[0], view.Size[1]);
    }
    return true;
  }

  // Stage 3: starts the image over when the input or the view changed;
  // true when it did.
  bool RestartIfChanged(vtkMCXXRayMapper* self, vtkPolyData* cloud, View& view)
  {
    const bool newInput = cloud != this->Cloud || cloud->GetMTime() != this->CloudTime;
    if (this->HasImage && !newInput && mcx::SameGeometry(view.Geometry, this->Geometry) &&
      std::equal(view.Matrix, view.Matrix + 16, this->Matrix) && view.Depth == this->Depth &&
      self->GetFootprintReach() == this->FootprintReach)
    {
      return false;
    }
    vtkCamera* camera = view.Camera;
    std::vector<double> limits(view.Depth.size());
    const double* range = camera->GetClippingRange();
    for (std::size_t p = 0; p < view.Depth.size(); ++p)
    {
      limits[p] = DepthToDistance(view.Depth[p], view.Geometry.Perspective, range[0], range[1]);
    }
    const bool hidesNothing = HidesNothing(limits, cloud, view.Geometry);
    const double* m = view.Matrix;
    const double origin[3] = { m[3], m[7], m[11] };
    const double linear[9] = { m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10] };
    this->Image.Reset(view.Geometry, origin, linear, std::move(limits),
      mcx::CloudDepositSettings(cloud, view.Geometry, origin, linear, self->GetFootprintReach()));
    this->HasImage = true;
    this->Cloud = cloud;
    this->CloudTime = cloud->GetMTime();
    this->FootprintReach = self->GetFootprintReach();
    this->Geometry = view.Geometry;
    std::copy(m, m + 16, this->Matrix);
    this->Depth = std::move(view.Depth);
    vtkPoints* points = cloud->GetPoints();
    this->NumberOfPoints = points ? static_cast<std::uint64_t>(points->GetNumberOfPoints()) : 0;
    this->EveryVoxel = mcx::IsEveryVoxelCloud(cloud);
    const double integral =
      cloud->GetFieldData()->GetArray(vtkMCXTypes::IntegralName())->GetTuple1(0);
    this->ScaledIntegral = integral * std::fabs(vtkMatrix4x4::Determinant(m));
    // A view-ordered cloud's control image holds for its own frame (no prop
    // matrix) with every sample visible.
    static const double identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
    if (hidesNothing && std::equal(m, m + 16, identity))
    {
      std::vector<double> control = mcx::CloudControlImage(cloud, view.Geometry);
      if (!control.empty())
      {
        this->Image.SetControl(std::move(control), integral);
      }
    }
    this->UploadedCount = std::numeric_limits<std::uint64_t>::max();
    this->AutomaticWindowPending = this->AutomaticWindowPending || newInput;
    // A new input needs a new source; so does a new view while the last
    // source showed nothing (the camera had not reached the volume yet).
    this->WindowSourceKept = this->WindowSourceKept && !newInput && !this->AutomaticWindowPending;
    return true;
  }

  // The points the automatic window is taken from: the smallest prefix of
  // 2^k - 1 points with at least 4 per pixel (64 per 4 x 4 block), or all
  // (always all of an every-voxel cloud).
  std::uint64_t WindowPrefix(const int size[2]) const
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

  // Projects up to the window prefix (the image holds no more yet) and keeps
  // its line integrals as the automatic window's source.
  void KeepWindowSource(vtkPoints* points, const int size[2])
  {
    const std::uint64_t prefix = this->WindowPrefix(size);
    if (this->Image.Count() < prefix)
    {
      this->Advance(points, prefix);
    }
    this->WindowSource.resize(this->Image.NumberOfPixels());
    this->Image.ToValues(this->SampleWeight(), this->WindowSource.data());
    this->WindowSourceSize[0] = size[0];
    this->WindowSourceSize[1] = size[1];
    this->WindowSourceKept = true;
  }

  // The automatic window of the source under the radiograph effects shown;
  // false when the source is empty.
  bool ChooseWindowFromSource()
  {
    std::vector<float> values = this->WindowSource;
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

  // Stage 5: uploads what changed (new points, other effects, a new
  // context); true when it uploaded. A display change only redraws.
  bool UploadIfChanged(
    vtkOpenGLRenderWindow* window, const mcx::RadiographEffects& effects, const int size[2])
  {
    const bool newEffects = effects != this->Effects;
    if (newEffects)
    {
      this->Effects = effects;
      this->AutomaticWindowPending = true; // other quantity, other scale
    }
    if (!newEffects && this->Image.Count() == this->UploadedCount && this->Texture &&
      this->Texture->GetContext() == window)
    {
      return false;
    }
    this->Upload(window, size[0], size[1]);
    return true;
  }

  // What one point of weight 1 carries: the integral over the points so far
  // (counted with their weights, PointWeight).
  double SampleWeight() const
  {
    const double carried = this->Image.CountedWeight();
    return carried > 0 ? this->ScaledIntegral / carried : 0.0;
  }

  // The number of points the image should hold after this render: the next
  // Halton prefix at least, then as many levels as the budget (seconds)
  // affords, and at least `floor` points.
  std::uint64_t RefinementTarget(double budget, double floor) const
  {
    const std::uint64_t current = this->Image.Count();
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

  // Projects points up to `target` and updates the measured cost per point.
  void Advance(vtkPoints* points, std::uint64_t target)
  {
    const std::uint64_t current = this->Image.Count();
    const auto start = std::chrono::steady_clock::now();
    mcx::WithPointWeights(this->Weights,
      [&](const auto* weights)
      {
        if (points->GetDataType() == VTK_FLOAT)
        {
          this->Image.Advance(mcx::SMPExecutor(),
            static_cast<const float*>(points->GetVoidPointer(0)), target, weights);
        }
        else
        {
          this->Image.Advance(mcx::SMPExecutor(),
            static_cast<const double*>(points->GetVoidPointer(0)), target, weights);
        }
      });
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::uint64_t added = target - current;
    if (added >= 4096 && seconds > 0)
    {
      this->SecondsPerSample =
        0.5 * (this->SecondsPerSample + seconds / static_cast<double>(added));
    }
  }

  // Converts the sums to line integrals, applies the radiograph physics
  // asked for, and uploads the values as a float texture.
  void Upload(vtkOpenGLRenderWindow* window, int width, int height)
  {
    this->Values.resize(this->Image.NumberOfPixels());
    this->Image.ToValues(this->SampleWeight(), this->Values.data());
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
    if (!this->Texture || this->Texture->GetContext() != window)
    {
      this->Texture = vtkSmartPointer<vtkTextureObject>::New();
      this->Texture->SetContext(window);
      this->Texture->SetMinificationFilter(vtkTextureObject::Nearest);
      this->Texture->SetMagnificationFilter(vtkTextureObject::Nearest);
      this->Texture->SetWrapS(vtkTextureObject::ClampToEdge);
      this->Texture->SetWrapT(vtkTextureObject::ClampToEdge);
    }
    this->Texture->Create2DFromRaw(static_cast<unsigned int>(width),
      static_cast<unsigned int>(height), 1, VTK_FLOAT, this->Values.data());
    this->UploadedCount = this->Image.Count();
  }

  // Draws the texture over the viewport through the display shader; false
  // if the shader cannot be built. As film, the grey replaces the background
  // where nothing opaque was drawn (the quad lies at the far plane and passes
  // the depth test only there) and blends over the geometry elsewhere
  // (when there is some); additive, it blends everywhere. For a depth
  // compositor the image writes a depth just in front of the far plane where
  // nothing opaque was drawn (a first pass there, additive ones too), so
  // that the compositor keeps it against other processes' empty pixels.
  bool Draw(vtkOpenGLRenderWindow* window, double lowest, double inverseWindow, bool invert,
    bool film, bool overGeometry, bool compositedByDepth)
  {
    if (!this->Quad)
    {
      std::string fragment = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
      vtkShaderProgram::Substitute(fragment, "//VTK::FSQ::Decl", DisplayShaderDeclarations);
      vtkShaderProgram::Substitute(fragment, "//VTK::FSQ::Impl", DisplayShaderBody);
      this->Quad.reset(new vtkOpenGLQuadHelper(window,
        vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader().c_str(), fragment.c_str(), ""));
    }
    else
    {
      window->GetShaderCache()->ReadyShaderProgram(this->Quad->Program);
    }
    if (!this->Quad->Program)
    {
      return false;
    }
    vtkOpenGLState* state = window->GetState();
    vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
    vtkOpenGLState::ScopedglDepthMask depthMask(state);
    vtkOpenGLState::ScopedglDepthFunc depthFunction(state);
    vtkOpenGLState::ScopedglBlendFuncSeparate blendFunction(state);
    state->vtkglDepthMask(GL_FALSE);
    this->Texture->Activate();
    this->Quad->Program->SetUniformi("lineIntegrals", this->Texture->GetTextureUnit());
    this->Quad->Program->SetUniformf("lowest", static_cast<float>(lowest));
    this->Quad->Program->SetUniformf("inverseWindow", static_cast<float>(inverseWindow));
    this->Quad->Program->SetUniformi("invert", invert ? 1 : 0);
    // 2^-20 in front of the far plane: distinct from it in a 24-bit depth buffer.
    this->Quad->Program->SetUniformf("imageDepth", compositedByDepth ? 1.0f - 0x1p-20f : 1.0f);
    auto blendAdditively = [state, invert]()
    {
      state->vtkglEnable(GL_BLEND);
      if (invert)
      {
        state->vtkglBlendFuncSeparate(GL_ZERO, GL_SRC_COLOR, GL_ZERO, GL_ONE); // dst * (1 - g)
      }
      else
      {
        state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE); // dst + g
      }
    };
    const bool whereEmptyFirst = film || compositedByDepth;
    if (whereEmptyFirst)
    {
      state->vtkglEnable(GL_DEPTH_TEST); // where the depth buffer is empty
      state->vtkglDepthFunc(GL_LEQUAL);
      state->vtkglDepthMask(compositedByDepth ? GL_TRUE : GL_FALSE);
      if (film)
      {
        state->vtkglDisable(GL_BLEND);
      }
      else
      {
        blendAdditively();
      }
      this->Quad->Render();
      state->vtkglDepthMask(GL_FALSE);
    }
    if (!whereEmptyFirst || overGeometry)
    {
      if (whereEmptyFirst)
      {
        state->vtkglDepthFunc(GL_GREATER); // the geometry's pixels
      }
      else
      {
        state->vtkglDisable(GL_DEPTH_TEST);
      }
      blendAdditively();
      this->Quad->Render();
    }
    this->Texture->Deactivate();
    return true;
  }
};

vtkMCXXRayMapper::vtkMCXXRayMapper()
  : Internals(new vtkInternals)
{
}

vtkMCXXRayMapper::~vtkMCXXRayMapper()
{
  delete this->Internals;
}

int vtkMCXXRayMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

vtkTypeInt64 vtkMCXXRayMapper::GetNumberOfAccumulatedSamples()
{
  return this->Internals->HasImage ? static_cast<vtkTypeInt64>(this->Internals->Image.Count()) : 0;
}

bool vtkMCXXRayMapper::IsRefinementComplete()
{
  return this->Internals->HasImage &&
    this->Internals->Image.Count() >= this->Internals->NumberOfPoints;
}

double vtkMCXXRayMapper::GetEstimatedRelativeError()
{
  const vtkInternals& in = *this->Internals;
  // Every voxel once: nothing to estimate, unless nothing was drawn (0).
  return in.HasImage && !(in.EveryVoxel && in.Image.Count() > 0) ? in.Image.EstimateRelativeError()
                                                                 : std::nan("");
}

bool vtkMCXXRayMapper::GetLastRenderUsedControlImage()
{
  return this->Internals->HasImage && this->Internals->Image.IsControlled();
}

void vtkMCXXRayMapper::GetLineIntegralImage(vtkImageData* output)
{
  output->Initialize();
  vtkInternals& in = *this->Internals;
  if (!in.HasImage)
  {
    return;
  }
  const mcx::ProjectionGeometry& g = in.Image.GetGeometry();
  output->SetExtent(0, g.Size[0] - 1, 0, g.Size[1] - 1, 0, 0);
  output->SetOrigin(g.Origin[0], g.Origin[1], 0.0);
  output->SetSpacing(g.Spacing[0], g.Spacing[1], 1.0);
  vtkNew<vtkDoubleArray> values;
  values->SetName(vtkMCXTypes::LineIntegralName());
  values->SetNumberOfValues(static_cast<vtkIdType>(in.Image.NumberOfPixels()));
  const std::uint64_t count = in.Image.Count();
  in.Image.ToValues(in.SampleWeight(), values->GetPointer(0));
  output->GetPointData()->SetScalars(values);
  mcx::AddFieldValue(
    output->GetFieldData(), vtkMCXTypes::SampleCountName(), static_cast<long long>(count));
  mcx::AddFieldValue(output->GetFieldData(), vtkMCXTypes::EstimatedRelativeErrorName(),
    this->GetEstimatedRelativeError());
}

void vtkMCXXRayMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  const auto start = std::chrono::steady_clock::now();
  vtkInternals& in = *this->Internals;
  vtkOpenGLRenderWindow* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    vtkErrorMacro("vtkMCXXRayMapper needs an OpenGL render window.");
    return;
  }
  vtkPolyData* cloud = in.UpdateInput(this);
  vtkInternals::View view;
  if (!cloud || !in.ReadView(this, renderer, volume, window, view))
  {
    return;
  }
  const bool needWindowSource = this->AutomaticWindowLevel && !in.WindowSourceKept;
  if (needWindowSource && in.HasImage && in.Image.Count() > in.WindowPrefix(view.Size))
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
    target = sourceMade && static_cast<double>(in.Image.Count()) >= floor
      ? in.Image.Count()
      : in.RefinementTarget(this->RenderTimeBudget(volume), floor);
  }
  if (target > in.Image.Count())
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
  if (!in.Draw(window, lowest, inverseWindow, this->InvertDisplay, film, this->LastRenderUsedDepth,
        this->CompositedByDepth))
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
  vtkPolyData* cloud = vtkPolyData::SafeDownCast(this->GetInputDataObject(0, 0));
  double corners[24];
  if (mcx::CloudSupportCorners(cloud, corners))
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
  else if (cloud && cloud->GetNumberOfPoints() > 0)
  {
    cloud->GetBounds(this->Bounds);
  }
  return this->Bounds;
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
  if (in.Texture)
  {
    in.Texture->ReleaseGraphicsResources(window);
    in.Texture = nullptr;
  }
  if (in.Quad)
  {
    in.Quad->ReleaseGraphicsResources(window);
    in.Quad.reset();
  }
  in.UploadedCount = std::numeric_limits<std::uint64_t>::max();
}

void vtkMCXXRayMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
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
  os << indent << "NumberOfAccumulatedSamples: " << this->GetNumberOfAccumulatedSamples() << "\n";
  os << indent << "NumberOfRestarts: " << this->NumberOfRestarts << "\n";
  os << indent << "NumberOfRefinements: " << this->NumberOfRefinements << "\n";
  os << indent << "NumberOfUploads: " << this->NumberOfUploads << "\n";
  os << indent << "NumberOfDraws: " << this->NumberOfDraws << "\n";
  os << indent << "LastRenderUsedDepth: " << this->LastRenderUsedDepth << "\n";
  os << indent << "LastRenderUsedControlImage: " << this->GetLastRenderUsedControlImage() << "\n";
}
