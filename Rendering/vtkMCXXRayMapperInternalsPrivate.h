// The state behind vtkMCXXRayMapper's image, and the stages of a render:
// bring the input up to date (sampling an image input), read the view,
// restart the image when the input or the view changed, refine it within
// the time budget, keep the automatic window's source, and upload what
// changed to the display. The mapper's public methods drive these stages;
// the display itself is vtkMCXXRayDisplay (OpenGL).
#ifndef vtkMCXXRayMapperInternalsPrivate_h
#define vtkMCXXRayMapperInternalsPrivate_h

#include "mcxProgressiveImage.h"
#include "mcxRadiographEffects.h"
#include "vtkMCXPolychromaticChannelsPrivate.h"
#include "vtkMCXSMPExecutor.h"
#include "vtkMCXVolumeSamplingPrivate.h"
#include "vtkMCXXRayDisplayPrivate.h"
#include "vtkMCXXRayMapper.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkCamera;
class vtkOpenGLRenderWindow;
class vtkPoints;
class vtkRenderer;

struct vtkMCXXRayMapper::vtkInternals
{
  using ProgressiveImage = mcx::ProgressiveImage<mcx::SMPExecutor>;
  std::unique_ptr<ProgressiveImage> Image{ new ProgressiveImage };
  bool HasImage = false;

  // The most refined image of another view of the same input, set aside at
  // a restart: a view that comes back to it (a resize and back, as
  // ParaView's screenshot dialog does with its preview) shows it at once
  // and goes on refining it, instead of starting over from a noisy prefix.
  struct Shelf
  {
    std::unique_ptr<ProgressiveImage> Image{ new ProgressiveImage };
    bool Polychromatic = false; // split into the materials' channels
    bool Held = false;
    vtkPolyData* Cloud = nullptr; // compared only, never dereferenced
    vtkMTimeType CloudTime = 0;
    double FootprintReach = 0.0;
    mcx::ProjectionGeometry Geometry;
    double Matrix[16] = { 0 };
    std::vector<float> Depth;
  };
  Shelf Shelved;

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
  vtkMCXXRayDisplay Display;

  vtkMCXVolumeSampling Sampling; // for an image input: its index and sampler

  // The polychromatic mode (a Spectrum set, an image input): the image
  // above is the total density's, the channels follow it point for point
  // and the display shows their effective line integral.
  vtkMCXPolychromaticChannels Channels;
  bool Polychromatic = false;      // this render's input is drawn through the channels
  bool ImagePolychromatic = false; // the image on screen has channels
  std::uint64_t MappedVersion = 0; // the model the uploaded values went through
  // -ln T's error estimate, propagated at the last upload (an overlay asks
  // for it every frame), and the sample count it is for.
  double MappedError = 0.0;
  std::uint64_t MappedErrorCount = 0;
  std::string Refused;             // the last problem reported (once per problem)

  // Whether the mapper's Spectrum asks for the polychromatic mode and the
  // input and settings allow it; reports why not (once) and returns false
  // with `refused` set.
  bool ConfigurePolychromatic(vtkMCXXRayMapper* self, vtkImageData* image, bool& refused);

  // The points' shares of the channels for the cloud of an image input;
  // false, reported, when its points are no voxel centres of the image.
  bool ShareChannels(vtkMCXXRayMapper* self, vtkImageData* image, vtkPolyData* cloud);

  // Reports a problem unless it was the last one reported.
  void Refuse(vtkMCXXRayMapper* self, const std::string& problem);

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

  // Stage 1: brings the input up to date (the cloud of an image input
  // sampled for the view); null (reported) when there is no cloud to draw.
  vtkPolyData* UpdateInput(vtkMCXXRayMapper* self, vtkVolume* volume, const View& view);

  // The cloud of an image input (a volume, or a density index) under the
  // volume property's scalar opacity; null when the volume has no density
  // array to index (reported).
  vtkPolyData* SampleVolume(
    vtkMCXXRayMapper* self, vtkImageData* image, vtkVolume* volume, const View& view);

  // The input's point weights for this render: checked once per array
  // version (a scan of every weight), not on every progressive frame.
  bool UpdateWeights(vtkMCXXRayMapper* self, vtkPolyData* cloud);

  // Stage 2: the view of this render; false when there is nothing to draw
  // (an empty viewport) or the camera is unusable (reported).
  bool ReadView(vtkMCXXRayMapper* self, vtkRenderer* renderer, vtkVolume* volume,
    vtkOpenGLRenderWindow* window, View& view);

  // Stage 3: starts the image over when the input or the view changed;
  // true when it did. A view that the shelved image was made for takes it
  // back instead (false: not a restart).
  bool RestartIfChanged(vtkMCXXRayMapper* self, vtkPolyData* cloud, View& view);

  // Swaps the image on screen, and what it was made from, with the shelf's.
  void SwapWithShelf();

  // The points the automatic window is taken from: the smallest prefix of
  // 2^k - 1 points with at least 4 per pixel (64 per 4 x 4 block), or all
  // (always all of an every-voxel cloud).
  std::uint64_t WindowPrefix(const int size[2]) const;

  // Projects up to the window prefix (the image holds no more yet) and keeps
  // its line integrals as the automatic window's source.
  void KeepWindowSource(vtkPoints* points, const int size[2]);

  // The automatic window of the source under the radiograph effects shown;
  // false when the source is empty.
  bool ChooseWindowFromSource();

  // Stage 5: uploads what changed (new points, other effects, a new
  // context); true when it uploaded. A display change only redraws.
  bool UploadIfChanged(
    vtkOpenGLRenderWindow* window, const mcx::RadiographEffects& effects, const int size[2]);

  // The values on screen before the display's effects: the line integrals,
  // or in the polychromatic mode the effective line integral -ln T.
  void ImageValues(float* values);

  // What one point of weight 1 carries: the integral over the points so far
  // (counted with their weights, PointWeight).
  double SampleWeight() const;

  // The number of points the image should hold after this render: the next
  // Halton prefix at least, then as many levels as the budget (seconds)
  // affords, and at least `floor` points.
  std::uint64_t RefinementTarget(double budget, double floor) const;

  // Projects points up to `target` and updates the measured cost per point.
  void Advance(vtkPoints* points, std::uint64_t target);

  // Converts the sums to line integrals, applies the radiograph physics
  // asked for, and uploads the values as a float texture.
  void Upload(vtkOpenGLRenderWindow* window, int width, int height);
};

#endif
