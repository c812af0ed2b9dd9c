// The X-ray mapper in a real render window (Xvfb + Mesa here): its image
// equals the off-line projector's for the same camera and points, it refines
// by prefixes without restarting, it recomputes only what a change calls for,
// it culls samples behind opaque geometry only when there is some, and its
// pictures match the baselines.
#include "mcxHeadScene.h"
#include "mcxTestHelpers.h"
#include "vtkMCXFirstErrorObserver.h"
#include "vtkMCXProjector.h"
#include "vtkMCXRadiograph.h"
#include "vtkMCXXRayMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCullerCollection.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{
// The bundled CT head (204 x 204 x 140 mm), with the checks the tests share.
struct Scene : mcxtest::HeadScene
{
  explicit Scene(int exponent = 18, int width = 160, int height = 128)
    : HeadScene(exponent, width, height)
  {
  }

  // The off-line projector's image of the first n points for the renderer's
  // camera, at the window's size or another.
  vtkSmartPointer<vtkImageData> Offline(vtkIdType n = -1, const int* size = nullptr)
  {
    this->Sampler->Update();
    vtkPolyData* cloud = this->Sampler->GetOutput();
    vtkNew<vtkPolyData> prefix;
    prefix->DeepCopy(cloud);
    if (n >= 0)
    {
      prefix->GetPoints()->Resize(n);
      prefix->GetPoints()->SetNumberOfPoints(n);
      if (vtkDataArray* weights = prefix->GetPointData()->GetArray("PointWeight"))
      {
        weights->Resize(n);
        weights->SetNumberOfTuples(n);
      }
      const double integral = mcxtest::FieldValue(cloud, "Integral");
      vtkDoubleArray::SafeDownCast(prefix->GetFieldData()->GetArray("SampleWeight"))
        ->SetValue(0, integral / static_cast<double>(n));
    }
    vtkNew<vtkMCXProjector> projector;
    projector->SetInputData(prefix);
    projector->SetCamera(this->Renderer->GetActiveCamera());
    size = size ? size : this->Window->GetSize();
    projector->SetImageSize(size[0], size[1]);
    projector->Update();
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->ShallowCopy(projector->GetOutput());
    return image;
  }

  vtkSmartPointer<vtkImageData> OnScreen()
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    this->Mapper->GetLineIntegralImage(image);
    return image;
  }
};

// Number of pixels whose values differ (exact comparison).
vtkIdType DifferingPixels(vtkImageData* a, vtkImageData* b)
{
  vtkDataArray* x = mcxtest::LineIntegral(a);
  vtkDataArray* y = mcxtest::LineIntegral(b);
  if (!x || !y || x->GetNumberOfTuples() != y->GetNumberOfTuples())
  {
    return -1;
  }
  vtkIdType differing = 0;
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
  {
    differing += x->GetTuple1(i) != y->GetTuple1(i) ? 1 : 0;
  }
  return differing;
}

// The window as drawn (RGB, row 0 at the bottom), read back without
// rendering again.
vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->SetInputBufferTypeToRGB();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

// The display's documented mapping: g = clamp((v - (level - window / 2)) /
// window, 0, 1) of the value as the texture holds it (float), added to a
// black background, or with inversion 1 - g multiplied onto a white one.
double ExpectedGrey(double value, double window, double level, bool invert)
{
  const double lowest = level - 0.5 * window;
  const double g = std::min(1.0, std::max(0.0, (static_cast<float>(value) - lowest) / window));
  return 255.0 * (invert ? 1.0 - g : g);
}

// Pixels of the grabbed window more than one grey level (8-bit rounding of
// a float result) from what the display makes of `values` (laid out like the
// viewport, whose lower-left pixel is at x0, y0), or from the background
// outside the viewport.
vtkIdType MisdrawnPixels(vtkImageData* grabbed, vtkDataArray* values, const int origin[2],
  const int size[2], double window, double level, bool invert = false)
{
  const int* dims = grabbed->GetDimensions();
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(grabbed->GetPointData()->GetScalars());
  vtkIdType misdrawn = 0;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      const int i = x - origin[0], j = y - origin[1];
      const bool inside = i >= 0 && i < size[0] && j >= 0 && j < size[1];
      const double expected = inside
        ? ExpectedGrey(
            values->GetTuple1(i + static_cast<vtkIdType>(size[0]) * j), window, level, invert)
        : (invert ? 255.0 : 0.0);
      for (int c = 0; c < 3; ++c)
      {
        if (std::fabs(rgb->GetValue(3 * (x + static_cast<vtkIdType>(dims[0]) * y) + c) - expected) >
          1.0)
        {
          ++misdrawn;
          break;
        }
      }
    }
  }
  return misdrawn;
}

vtkIdType MisdrawnPixels(
  vtkImageData* grabbed, vtkDataArray* values, double window, double level, bool invert = false)
{
  const int origin[2] = { 0, 0 };
  const int size[2] = { grabbed->GetDimensions()[0], grabbed->GetDimensions()[1] };
  return MisdrawnPixels(grabbed, values, origin, size, window, level, invert);
}

// The documented automatic window of an image: 0 to the 99.5th percentile
// (rank floor(0.995 (n - 1))) of the positive means of its 4 x 4 pixel blocks
// (the last row and column of blocks may be smaller), of the float values.
double AutomaticWindow(vtkDataArray* values, int width, int height)
{
  std::vector<double> means;
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
          sum += static_cast<float>(values->GetTuple1(x + static_cast<vtkIdType>(width) * y));
        }
      }
      if (sum > 0)
      {
        means.push_back(sum / n);
      }
    }
  }
  std::sort(means.begin(), means.end());
  return means.empty() ? 0.0 : means[static_cast<std::size_t>(0.995 * (means.size() - 1))];
}

// Pixels where the RGB images differ by more than `levels` in a channel,
// position for position (no shift, no averaging).
vtkIdType DifferingColours(vtkImageData* a, vtkImageData* b, int levels)
{
  vtkDataArray* x = a->GetPointData()->GetScalars();
  vtkDataArray* y = b->GetPointData()->GetScalars();
  if (x->GetNumberOfTuples() != y->GetNumberOfTuples() || x->GetNumberOfComponents() < 3 ||
    y->GetNumberOfComponents() < 3)
  {
    return -1;
  }
  vtkIdType differing = 0;
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (std::fabs(x->GetComponent(i, c) - y->GetComponent(i, c)) > levels)
      {
        ++differing;
        break;
      }
    }
  }
  return differing;
}

// Compares the window with Testing/Baselines/<name>.png; writes what it saw
// to the build tree, and creates a missing baseline when
// MCXRAY_UPDATE_BASELINES is set.
void CompareWithBaseline(vtkRenderWindow* window, const std::string& name)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  const std::string actual = name + "-actual.png";
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(grab->GetOutputPort());
  writer->SetFileName(actual.c_str());
  writer->Write();
  const std::string baseline = MCXRAY_BASELINE_DIR "/" + name + ".png";
  if (!vtksys::SystemTools::FileExists(baseline) &&
    vtksys::SystemTools::GetEnv("MCXRAY_UPDATE_BASELINES"))
  {
    vtksys::SystemTools::CopyFileAlways(actual, baseline);
  }
  ASSERT_TRUE(vtksys::SystemTools::FileExists(baseline)) << "missing baseline " << baseline;
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(baseline.c_str());
  reader->Update();
  // Pixel for pixel, a few grey levels of slack for another GL driver's
  // rounding, no shift and no averaging: a mirrored, shifted or darker
  // picture fails.
  EXPECT_EQ(0, DifferingColours(grab->GetOutput(), reader->GetOutput(), 3))
    << name << ": compare " << actual;
}
}

TEST(Mapper, ParallelImageEqualsTheOfflineProjectors)
{
  Scene scene;
  scene.Renderer->GetActiveCamera()->ParallelProjectionOn();
  scene.Mapper->ProgressiveRefinementOff();
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->IsRefinementComplete());
  EXPECT_EQ((1 << 18) - 1, scene.Mapper->GetNumberOfAccumulatedSamples());
  auto offline = scene.Offline();
  EXPECT_EQ(0, DifferingPixels(scene.OnScreen(), offline));
  EXPECT_GT(mcxtest::LineIntegralSum(offline), 0.0);
  EXPECT_FALSE(scene.Mapper->GetLastRenderUsedDepth());
}

TEST(Mapper, PerspectiveImageEqualsTheOfflineProjectors)
{
  Scene scene;
  scene.Mapper->ProgressiveRefinementOff();
  scene.Renderer->GetActiveCamera()->Azimuth(30);
  scene.Renderer->GetActiveCamera()->Elevation(20);
  scene.Renderer->GetActiveCamera()->OrthogonalizeViewUp();
  scene.Renderer->ResetCameraClippingRange();
  scene.Window->Render();
  auto offline = scene.Offline();
  EXPECT_EQ(0, DifferingPixels(scene.OnScreen(), offline));
  EXPECT_GT(mcxtest::LineIntegralSum(offline), 0.0);
}

TEST(Mapper, CameraInsideTheVolumeGivesFiniteValues)
{
  // The eye sits in the skull: samples behind it, on it and before the near
  // plane must not count and must not produce Inf or NaN.
  Scene scene;
  scene.Mapper->ProgressiveRefinementOff();
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetPosition(102, 60, 70);
  camera->SetFocalPoint(102, 200, 70);
  camera->SetClippingRange(1e-3, 1000);
  scene.Window->Render();
  auto image = scene.OnScreen();
  vtkDataArray* values = mcxtest::LineIntegral(image);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    ASSERT_TRUE(std::isfinite(values->GetTuple1(i))) << "pixel " << i;
  }
  EXPECT_EQ(0, DifferingPixels(image, scene.Offline()));
}

TEST(Mapper, SameImageForAnyNumberOfThreads)
{
  Scene scene;
  scene.Mapper->ProgressiveRefinementOff();
  vtkSmartPointer<vtkImageData> images[2];
  const int threads[2] = { 1, 2 };
  for (int t = 0; t < 2; ++t)
  {
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads[t] },
      [&]
      {
        // Away and back: a new projection of the same view each time (the
        // sampler runs again, so no view takes back the image kept for it).
        scene.Sampler->Modified();
        vtkCamera* camera = scene.Renderer->GetActiveCamera();
        camera->SetPosition(102, -400, 70);
        scene.Window->Render();
        camera->SetPosition(102, -500, 70);
        scene.Window->Render();
        images[t] = scene.OnScreen();
      });
  }
  EXPECT_EQ(4, scene.Mapper->GetNumberOfRestarts());
  EXPECT_EQ(0, DifferingPixels(images[0], images[1]));
}

TEST(Mapper, RefinesByHaltonPrefixesWithoutRestarting)
{
  Scene scene(18);
  scene.Mapper->AutomaticWindowLevelOff();
  scene.Mapper->SetInitialSampleExponent(10);
  scene.Window->SetDesiredUpdateRate(1e6); // about a microsecond per frame: one level per render
  scene.Window->Render();
  EXPECT_EQ(1, scene.Mapper->GetNumberOfRestarts());
  std::vector<vtkTypeInt64> counts{ scene.Mapper->GetNumberOfAccumulatedSamples() };
  EXPECT_EQ((1 << 10) - 1, counts.back());
  auto coarse = scene.OnScreen();
  EXPECT_EQ(0, DifferingPixels(coarse, scene.Offline(counts.back())));
  while (!scene.Mapper->IsRefinementComplete() && counts.size() < 40)
  {
    scene.Window->Render();
    counts.push_back(scene.Mapper->GetNumberOfAccumulatedSamples());
    EXPECT_EQ(2 * counts[counts.size() - 2] + 1, counts.back()) << "each step adds one level";
    // Every intermediate image is the off-line image of its prefix.
    auto offline = scene.Offline(counts.back());
    auto onScreen = scene.OnScreen();
    EXPECT_EQ(0, DifferingPixels(onScreen, offline)) << counts.back() << " points";
    EXPECT_EQ(mcxtest::FieldValue(offline, "EstimatedRelativeError"),
      mcxtest::FieldValue(onScreen, "EstimatedRelativeError"))
      << counts.back() << " points";
  }
  EXPECT_EQ((1 << 18) - 1, counts.back());
  EXPECT_EQ(1, scene.Mapper->GetNumberOfRestarts());
  EXPECT_EQ(static_cast<vtkTypeInt64>(counts.size() - 1), scene.Mapper->GetNumberOfRefinements());
  // The refined image is the image of all points, bit for bit.
  EXPECT_EQ(0, DifferingPixels(scene.OnScreen(), scene.Offline()));
  // Its error estimate is that of the off-line projector from the same halves.
  const double estimate = scene.Mapper->GetEstimatedRelativeError();
  EXPECT_EQ(mcxtest::FieldValue(scene.Offline(), "EstimatedRelativeError"), estimate);
  EXPECT_GT(estimate, 0.0);

  // A still view (no time limit) completes in one render.
  scene.Renderer->GetActiveCamera()->Azimuth(5);
  scene.Window->SetDesiredUpdateRate(0.0001);
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->IsRefinementComplete());
  EXPECT_EQ(2, scene.Mapper->GetNumberOfRestarts());
}

TEST(Mapper, AViewThatComesBackTakesBackItsRefinedImage)
{
  // ParaView's screenshot dialog lays the view out at other sizes and back
  // to its own, each an interactive render: the last size is the view's.
  Scene scene(18);
  scene.Mapper->AutomaticWindowLevelOff();
  scene.Mapper->SetInitialSampleExponent(10);
  scene.Window->SetDesiredUpdateRate(0.0001); // a still render: every point
  scene.Window->Render();
  ASSERT_TRUE(scene.Mapper->IsRefinementComplete());
  const auto refined = scene.OnScreen();
  const double error = scene.Mapper->GetEstimatedRelativeError();
  scene.Window->SetDesiredUpdateRate(1e6); // interactive: the first prefix
  scene.Window->SetSize(150, 120);
  scene.Window->Render();
  EXPECT_EQ((1 << 10) - 1, scene.Mapper->GetNumberOfAccumulatedSamples());
  scene.Window->SetSize(160, 128);
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->IsRefinementComplete());
  EXPECT_EQ(error, scene.Mapper->GetEstimatedRelativeError());
  EXPECT_EQ(0, DifferingPixels(scene.OnScreen(), refined));
  EXPECT_EQ(2, scene.Mapper->GetNumberOfRestarts()) << "the view's own size restarted";

  // The prefixes of a moving camera do not push the refined image out.
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  double position[3];
  camera->GetPosition(position);
  for (int step = 0; step < 3; ++step)
  {
    camera->Azimuth(5);
    scene.Window->Render();
  }
  camera->SetPosition(position);
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->IsRefinementComplete());
  EXPECT_EQ(0, DifferingPixels(scene.OnScreen(), refined));

  // A TF edit in between: the kept image is another input's.
  scene.Window->SetSize(150, 120);
  scene.Window->Render();
  scene.TransferFunction->AddPoint(1000, 0.1);
  scene.Window->SetSize(160, 128);
  scene.Window->Render();
  EXPECT_EQ((1 << 10) - 1, scene.Mapper->GetNumberOfAccumulatedSamples());
  EXPECT_EQ(0, DifferingPixels(scene.OnScreen(), scene.Offline((1 << 10) - 1)));
}

TEST(Mapper, FootprintCloudRefinesLikeTheOfflineProjector)
{
  // A cloud of voxel centres (the footprint deposit): every progressive
  // prefix on screen is the off-line projector's image of that prefix, bit
  // for bit, parallel and perspective, and its estimate is the same.
  Scene scene(16);
  scene.Sampler->SetDepositToFootprint();
  scene.Mapper->AutomaticWindowLevelOff();
  scene.Mapper->SetInitialSampleExponent(10);
  scene.Window->SetDesiredUpdateRate(1e6); // one level per render
  for (bool parallel : { true, false })
  {
    scene.Renderer->GetActiveCamera()->SetParallelProjection(parallel);
    scene.Renderer->GetActiveCamera()->Azimuth(20);
    scene.Renderer->ResetCameraClippingRange();
    scene.Window->Render();
    int steps = 0;
    while (steps++ < 40)
    {
      const vtkTypeInt64 count = scene.Mapper->GetNumberOfAccumulatedSamples();
      auto offline = scene.Offline(count);
      auto onScreen = scene.OnScreen();
      ASSERT_EQ(0, DifferingPixels(onScreen, offline)) << count << " points";
      EXPECT_EQ(mcxtest::FieldValue(offline, "EstimatedRelativeError"),
        mcxtest::FieldValue(onScreen, "EstimatedRelativeError"))
        << count << " points";
      if (scene.Mapper->IsRefinementComplete())
      {
        break;
      }
      scene.Window->Render();
    }
    EXPECT_EQ((1 << 16) - 1, scene.Mapper->GetNumberOfAccumulatedSamples());
  }
}

TEST(Mapper, EveryVoxelCloudRefinesLikeTheOfflineProjector)
{
  // The sampler's EVERY_VOXEL cloud: every progressive prefix on screen is
  // the off-line projector's image of that prefix, bit for bit, and the
  // complete image is that of every voxel of non-zero weight; its error is
  // not estimated (NaN) on screen as off line.
  Scene scene(16);
  scene.Sampler->SetDepositToFootprint();
  scene.Sampler->SetStrategyToEveryVoxel();
  scene.Mapper->AutomaticWindowLevelOff();
  scene.Mapper->SetInitialSampleExponent(10);
  scene.Window->SetDesiredUpdateRate(1e6); // one level per render
  scene.Window->Render();
  const vtkIdType voxels = scene.Sampler->GetOutput()->GetNumberOfPoints();
  ASSERT_GT(voxels, 100000);
  int steps = 0;
  while (steps++ < 40)
  {
    const vtkTypeInt64 count = scene.Mapper->GetNumberOfAccumulatedSamples();
    auto offline = scene.Offline(count);
    ASSERT_EQ(0, DifferingPixels(scene.OnScreen(), offline)) << count << " points";
    EXPECT_TRUE(std::isnan(scene.Mapper->GetEstimatedRelativeError()));
    EXPECT_TRUE(std::isnan(mcxtest::FieldValue(offline, "EstimatedRelativeError")));
    if (scene.Mapper->IsRefinementComplete())
    {
      break;
    }
    scene.Window->Render();
  }
  EXPECT_GT(steps, 3);
  EXPECT_EQ(voxels, scene.Mapper->GetNumberOfAccumulatedSamples());
}

TEST(Mapper, ViewOrderedCloudInItsViewRefinesItsControlledImageLikeTheOfflineProjector)
{
  // A view-ordered cloud carries the control image of its ordering view:
  // in that view every progressive prefix on screen is the off-line
  // projector's controlled image of that prefix, bit for bit, with the
  // same estimate; another view, or a prop matrix, shows the plain estimate
  // (the control's image holds only for its own view and frame), and so
  // does opaque geometry in front of the volume, not behind it or empty.
  // The control image is sampled (one voxel a point, of 5.8): its own
  // variance is in both estimates.
  Scene scene(16);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->Azimuth(20);
  camera->SetClippingRange(100, 2000); // kept: the plates below do not move it
  scene.Sampler->SetDepositToFootprint();
  scene.Sampler->SetStrategyToViewOrdered();
  scene.Sampler->SetControlVoxelsPerPoint(1);
  scene.Sampler->SetOrderingView(camera, 160, 128);
  scene.Mapper->AutomaticWindowLevelOff();
  scene.Mapper->SetInitialSampleExponent(10);
  scene.Window->SetDesiredUpdateRate(1e6); // one level per render
  scene.Window->Render();
  EXPECT_GT(
    mcxtest::FieldValue(scene.Sampler->GetOutput(), vtkMCXTypes::ControlVarianceName()), 0.0);
  int steps = 0;
  while (steps++ < 40)
  {
    ASSERT_TRUE(scene.Mapper->GetLastRenderUsedControlImage());
    const vtkTypeInt64 count = scene.Mapper->GetNumberOfAccumulatedSamples();
    auto offline = scene.Offline(count);
    ASSERT_EQ(0, DifferingPixels(scene.OnScreen(), offline)) << count << " points";
    EXPECT_EQ(mcxtest::FieldValue(offline, "EstimatedRelativeError"),
      scene.Mapper->GetEstimatedRelativeError())
      << count << " points";
    if (scene.Mapper->IsRefinementComplete())
    {
      break;
    }
    scene.Window->Render();
  }
  EXPECT_GT(steps, 3);
  EXPECT_EQ((1 << 16) - 1, scene.Mapper->GetNumberOfAccumulatedSamples());
  auto controlled = scene.OnScreen();

  // The same cloud without its control: another image of the same scene.
  scene.Sampler->ControlVariateOff();
  scene.Mapper->ProgressiveRefinementOff();
  scene.Window->Render();
  EXPECT_FALSE(scene.Mapper->GetLastRenderUsedControlImage());
  EXPECT_EQ(0, DifferingPixels(scene.OnScreen(), scene.Offline()));
  EXPECT_GT(DifferingPixels(scene.OnScreen(), controlled), 1000);
  scene.Sampler->ControlVariateOn();
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->GetLastRenderUsedControlImage());
  EXPECT_EQ(0, DifferingPixels(scene.OnScreen(), controlled));

  camera->Azimuth(1); // not the ordering view
  scene.Window->Render();
  EXPECT_FALSE(scene.Mapper->GetLastRenderUsedControlImage());
  camera->Azimuth(-1);
  scene.Volume->SetPosition(0.5, 0, 0); // the cloud seen moved
  scene.Window->Render();
  EXPECT_FALSE(scene.Mapper->GetLastRenderUsedControlImage());
  scene.Volume->SetPosition(0, 0, 0);
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->GetLastRenderUsedControlImage());

  // A 100 mm plate on the view's axis (covering part of the view), 400 mm
  // behind the focal point (the head reaches about 160 mm from it), then
  // 300 mm in front; and an actor with nothing to draw, which is no
  // occluder.
  double direction[3];
  camera->GetDirectionOfProjection(direction);
  const double* focal = camera->GetFocalPoint();
  vtkNew<vtkPlaneSource> plate;
  plate->SetOrigin(0, 0, 0);
  plate->SetPoint1(100, 0, 0);
  plate->SetPoint2(0, 100, 0);
  plate->SetNormal(direction);
  vtkNew<vtkPolyDataMapper> plateMapper;
  plateMapper->SetInputConnection(plate->GetOutputPort());
  vtkNew<vtkActor> plateActor;
  plateActor->SetMapper(plateMapper);
  scene.Renderer->AddActor(plateActor);
  for (const double along : { 400.0, -300.0 })
  {
    plate->SetCenter(focal[0] + along * direction[0], focal[1] + along * direction[1],
      focal[2] + along * direction[2]);
    scene.Window->Render();
    EXPECT_TRUE(scene.Mapper->GetLastRenderUsedDepth()) << along;
    EXPECT_EQ(along > 0, scene.Mapper->GetLastRenderUsedControlImage()) << along;
  }
  vtkNew<vtkPolyDataMapper> emptyMapper;
  vtkNew<vtkPolyData> nothing;
  emptyMapper->SetInputData(nothing);
  plateActor->SetMapper(emptyMapper);
  scene.Window->Render();
  EXPECT_FALSE(scene.Mapper->GetLastRenderUsedDepth());
  EXPECT_TRUE(scene.Mapper->GetLastRenderUsedControlImage());
  EXPECT_EQ(0, DifferingPixels(scene.OnScreen(), controlled));
}

TEST(Mapper, WeightedCloudEqualsTheOfflineProjectorsAndFollowsItsWeights)
{
  // A cloud's PointWeight array scales each point's deposit, and the points
  // carry the cloud's integral together: on screen as off line, bit for
  // bit, points and footprints; a change of the weights alone starts the
  // image over (weights 2 everywhere give the unweighted image, up to each
  // pixel's rounding); a bad weight is one error line, and nothing is drawn
  // from it.
  Scene scene(14);
  scene.Mapper->ProgressiveRefinementOff();
  for (const bool footprint : { false, true })
  {
    scene.Sampler->SetDeposit(
      footprint ? vtkMCXTypes::FOOTPRINT : vtkMCXTypes::POINT);
    scene.Sampler->Update();
    vtkNew<vtkPolyData> cloud;
    cloud->DeepCopy(scene.Sampler->GetOutput());
    const vtkIdType n = cloud->GetNumberOfPoints();
    scene.Mapper->SetInputDataObject(cloud);
    scene.Window->Render();
    auto unweighted = scene.OnScreen();

    vtkNew<vtkFloatArray> weights;
    weights->SetName(vtkMCXTypes::PointWeightName());
    weights->SetNumberOfValues(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      weights->SetValue(i, 0.5f * static_cast<float>(i % 5));
    }
    cloud->GetPointData()->AddArray(weights);
    scene.Window->Render();
    vtkNew<vtkMCXProjector> projector;
    projector->SetInputData(cloud);
    projector->SetCamera(scene.Renderer->GetActiveCamera());
    projector->SetImageSize(160, 128);
    projector->Update();
    auto weighted = scene.OnScreen();
    EXPECT_EQ(0, DifferingPixels(weighted, projector->GetOutput())) << footprint;
    EXPECT_GT(DifferingPixels(weighted, unweighted), 1000) << footprint;

    const vtkTypeInt64 restarts = scene.Mapper->GetNumberOfRestarts();
    weights->Fill(2.0);
    weights->Modified();
    scene.Window->Render();
    EXPECT_EQ(restarts + 1, scene.Mapper->GetNumberOfRestarts()) << footprint;
    auto twice = scene.OnScreen();
    vtkDataArray* doubled = mcxtest::LineIntegral(twice);
    vtkDataArray* once = mcxtest::LineIntegral(unweighted);
    const double peak = mcxtest::MaximumAbsolute(once);
    ASSERT_GT(peak, 0.0);
    for (vtkIdType p = 0; p < once->GetNumberOfTuples(); ++p)
    {
      ASSERT_NEAR(once->GetTuple1(p), doubled->GetTuple1(p), 1e-6 * peak) << "pixel " << p;
    }

    weights->SetValue(3, -1.0f);
    weights->Modified();
    vtkNew<vtkMCXFirstErrorObserver> errors;
    const unsigned long observer = scene.Mapper->AddObserver(vtkCommand::ErrorEvent, errors);
    const vtkTypeInt64 draws = scene.Mapper->GetNumberOfDraws();
    scene.Window->Render();
    scene.Mapper->RemoveObserver(observer);
    EXPECT_EQ("The cloud's PointWeight array cannot be used: point 3 has the weight -1 (weights "
              "must be finite and in [0, 2^40]).",
      errors->GetErrorText());
    EXPECT_EQ(draws, scene.Mapper->GetNumberOfDraws());
  }
}

TEST(Mapper, FootprintReachSplitsTheCloudsKernelsAsTheProjectorDoes)
{
  // At 160 x 128 a tent reaches about 2 pixels: reach 1 splits every
  // kernel. The mapper's image with reach 1 is the off-line projector's
  // with reach 1, bit for bit, and not the image of the default reach.
  Scene scene(16);
  scene.Sampler->SetDepositToFootprint();
  scene.Mapper->ProgressiveRefinementOff();
  scene.Window->Render();
  auto whole = scene.OnScreen();
  scene.Mapper->SetFootprintReach(1.0);
  scene.Window->Render();
  auto split = scene.OnScreen();
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(scene.Sampler->GetOutputPort());
  projector->SetCamera(scene.Renderer->GetActiveCamera());
  projector->SetImageSize(160, 128);
  projector->SetFootprintReach(1.0);
  projector->Update();
  EXPECT_EQ(0, DifferingPixels(split, projector->GetOutput()));
  EXPECT_GT(DifferingPixels(split, whole), 1000);
}

TEST(Mapper, EachChangeRecomputesOnlyWhatItAffects)
{
  Scene scene(16);
  scene.Mapper->ProgressiveRefinementOff();
  scene.Mapper->AutomaticWindowLevelOff();
  mcxtest::ExecutionCounter indexRuns(scene.Index), samplerRuns(scene.Sampler);
  scene.Window->Render(); // the pipeline already ran to frame the camera
  EXPECT_EQ(0, indexRuns.Count);
  EXPECT_EQ(0, samplerRuns.Count);
  EXPECT_EQ(1, scene.Mapper->GetNumberOfRestarts());
  EXPECT_EQ(1, scene.Mapper->GetNumberOfUploads());
  EXPECT_EQ(1, scene.Mapper->GetNumberOfDraws());

  scene.Window->Render(); // nothing changed: draw the same texture again
  EXPECT_EQ(0, samplerRuns.Count);
  EXPECT_EQ(1, scene.Mapper->GetNumberOfRestarts());
  EXPECT_EQ(1, scene.Mapper->GetNumberOfUploads());
  EXPECT_EQ(2, scene.Mapper->GetNumberOfDraws());

  scene.Mapper->SetColorWindow(3000); // display change: re-map only
  scene.Mapper->InvertDisplayOn();
  scene.Window->Render();
  EXPECT_EQ(0, samplerRuns.Count);
  EXPECT_EQ(1, scene.Mapper->GetNumberOfRestarts());
  EXPECT_EQ(1, scene.Mapper->GetNumberOfUploads());
  EXPECT_EQ(3, scene.Mapper->GetNumberOfDraws());
  EXPECT_EQ(3000, scene.Mapper->GetDisplayedWindow());

  scene.Mapper->BeerLambertOn(); // radiograph physics: re-map the buffer, never re-project
  scene.Mapper->SetPhotonsPerPixel(1000);
  scene.Window->Render();
  EXPECT_EQ(0, samplerRuns.Count);
  EXPECT_EQ(1, scene.Mapper->GetNumberOfRestarts());
  EXPECT_EQ(2, scene.Mapper->GetNumberOfUploads());
  scene.Mapper->BeerLambertOff();
  scene.Mapper->SetPhotonsPerPixel(0);
  scene.Window->Render();
  EXPECT_EQ(1, scene.Mapper->GetNumberOfRestarts());
  EXPECT_EQ(3, scene.Mapper->GetNumberOfUploads());

  scene.Renderer->GetActiveCamera()->Azimuth(20); // camera change: re-project only
  scene.Window->Render();
  EXPECT_EQ(0, indexRuns.Count);
  EXPECT_EQ(0, samplerRuns.Count);
  EXPECT_EQ(2, scene.Mapper->GetNumberOfRestarts());
  EXPECT_EQ(4, scene.Mapper->GetNumberOfUploads());

  scene.TransferFunction->AddPoint(1000, 0.1); // TF change: resample, never re-index
  scene.Window->Render();
  EXPECT_EQ(0, indexRuns.Count);
  EXPECT_EQ(1, samplerRuns.Count);
  EXPECT_EQ(3, scene.Mapper->GetNumberOfRestarts());
  EXPECT_EQ(5, scene.Mapper->GetNumberOfUploads());
  EXPECT_EQ(0, DifferingPixels(scene.OnScreen(), scene.Offline()));
}

namespace
{
// A parallelogram occluder (vtkPlaneSource's origin and two corners).
struct Plate
{
  double Origin[3], Point1[3], Point2[3];

  // Eye depth (along the view direction) at which the ray through the centre
  // of display pixel (i, j) meets the plate; +inf if it misses. `margin` is
  // set to the hit's distance from the plate's outline, in pixels.
  double DepthAtPixel(vtkRenderer* renderer, int i, int j, double pixelSize, double& margin) const
  {
    double ray[2][3];
    for (int end = 0; end < 2; ++end)
    {
      renderer->SetDisplayPoint(i + 0.5, j + 0.5, end);
      renderer->DisplayToWorld();
      const double* w = renderer->GetWorldPoint();
      for (int a = 0; a < 3; ++a)
      {
        ray[end][a] = w[a] / w[3];
      }
    }
    double e1[3], e2[3], normal[3], direction[3], toOrigin[3];
    for (int a = 0; a < 3; ++a)
    {
      e1[a] = this->Point1[a] - this->Origin[a];
      e2[a] = this->Point2[a] - this->Origin[a];
      direction[a] = ray[1][a] - ray[0][a];
      toOrigin[a] = this->Origin[a] - ray[0][a];
    }
    vtkMath::Cross(e1, e2, normal);
    const double t = vtkMath::Dot(toOrigin, normal) / vtkMath::Dot(direction, normal);
    double hit[3], local[3];
    for (int a = 0; a < 3; ++a)
    {
      hit[a] = ray[0][a] + t * direction[a];
      local[a] = hit[a] - this->Origin[a];
    }
    // Plate coordinates of the hit: local = s e1 + u e2.
    const double e11 = vtkMath::Dot(e1, e1), e12 = vtkMath::Dot(e1, e2), e22 = vtkMath::Dot(e2, e2);
    const double l1 = vtkMath::Dot(local, e1), l2 = vtkMath::Dot(local, e2);
    const double det = e11 * e22 - e12 * e12;
    const double s = (l1 * e22 - l2 * e12) / det, u = (l2 * e11 - l1 * e12) / det;
    margin = std::min({ std::fabs(s) * std::sqrt(e11), std::fabs(1 - s) * std::sqrt(e11),
               std::fabs(u) * std::sqrt(e22), std::fabs(1 - u) * std::sqrt(e22) }) /
      pixelSize;
    if (s < 0 || s > 1 || u < 0 || u > 1)
    {
      return std::numeric_limits<double>::infinity();
    }
    vtkCamera* camera = renderer->GetActiveCamera();
    const double* eye = camera->GetPosition();
    const double* w = camera->GetDirectionOfProjection();
    return (hit[0] - eye[0]) * w[0] + (hit[1] - eye[1]) * w[1] + (hit[2] - eye[2]) * w[2];
  }
};
}

TEST(Mapper, OpaqueGeometryHidesTheSamplesBehindIt)
{
  // A tilted plate over part of the head: each pixel counts exactly the
  // points in front of the plate's depth at that pixel (where the pixel
  // centre's ray meets it), for a parallel and a perspective camera. The
  // expected image is the off-line projection of those points, found with
  // VTK's own projection; only points within the depth buffer's resolution
  // of the plate, and pixels whose centre lies on its outline, may go either way.
  Scene scene(18);
  scene.Mapper->ProgressiveRefinementOff();
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  Plate plate = { { 40, 60, -20 }, { 180, 150, 40 }, { 10, 90, 120 } };
  vtkNew<vtkPlaneSource> source;
  source->SetOrigin(plate.Origin);
  source->SetPoint1(plate.Point1);
  source->SetPoint2(plate.Point2);
  vtkNew<vtkPolyDataMapper> plateMapper;
  plateMapper->SetInputConnection(source->GetOutputPort());
  vtkNew<vtkActor> plateActor;
  plateActor->SetMapper(plateMapper);
  plateActor->GetProperty()->SetColor(0.2, 0.4, 0.8);
  plateActor->VisibilityOff();
  scene.Renderer->AddActor(plateActor);
  scene.Sampler->Update();
  vtkPolyData* cloud = scene.Sampler->GetOutput();

  for (bool parallel : { true, false })
  {
    camera->SetParallelProjection(parallel);
    camera->SetPosition(140, -400, 110); // oblique to the plate
    scene.Renderer->ResetCameraClippingRange();
    plateActor->VisibilityOff();
    // A hidden actor is no occluder: no depth work, the whole head counts.
    scene.Window->Render();
    EXPECT_FALSE(scene.Mapper->GetLastRenderUsedDepth());
    auto whole = scene.OnScreen();
    EXPECT_EQ(0, DifferingPixels(whole, scene.Offline()));

    plateActor->VisibilityOn();
    scene.Window->Render();
    EXPECT_TRUE(scene.Mapper->GetLastRenderUsedDepth());
    auto front = scene.OnScreen();

    // The plate's depth at every pixel centre.
    const int width = 160, height = 128;
    const double pixelSize = front->GetSpacing()[0];
    std::vector<double> plateDepth(width * height);
    std::vector<bool> onOutline(width * height);
    int covered = 0;
    for (int j = 0; j < height; ++j)
    {
      for (int i = 0; i < width; ++i)
      {
        double margin;
        plateDepth[i + width * j] = plate.DepthAtPixel(scene.Renderer, i, j, pixelSize, margin);
        onOutline[i + width * j] = margin < 0.01;
        covered += std::isfinite(plateDepth[i + width * j]) ? 1 : 0;
      }
    }
    EXPECT_GT(covered, width * height / 5);
    EXPECT_LT(covered, width * height * 4 / 5);
    // The 24-bit depth buffer resolves eye depth to (far - near) 2^-24 in a
    // parallel view and z^2 (far - near) / (near far) 2^-24 in perspective;
    // four steps of slack.
    const double* range = camera->GetClippingRange();
    const double step = parallel
      ? (range[1] - range[0]) * std::ldexp(1.0, -24)
      : range[1] * range[1] * (range[1] - range[0]) / (range[0] * range[1]) * std::ldexp(1.0, -24);
    const double* eye = camera->GetPosition();
    const double* w = camera->GetDirectionOfProjection();
    vtkNew<vtkPoints> surely, maybe;
    vtkIdType undecided = 0;
    for (vtkIdType k = 0; k < cloud->GetNumberOfPoints(); ++k)
    {
      const double* x = cloud->GetPoint(k);
      scene.Renderer->SetWorldPoint(x[0], x[1], x[2], 1.0);
      scene.Renderer->WorldToDisplay();
      const double* d = scene.Renderer->GetDisplayPoint();
      if (!(d[0] >= 0 && d[0] < width && d[1] >= 0 && d[1] < height))
      {
        continue;
      }
      const int p = static_cast<int>(d[0]) + width * static_cast<int>(d[1]);
      const double depth = (x[0] - eye[0]) * w[0] + (x[1] - eye[1]) * w[1] + (x[2] - eye[2]) * w[2];
      const bool onBorder =
        std::fabs(d[0] - std::round(d[0])) < 1e-6 || std::fabs(d[1] - std::round(d[1])) < 1e-6;
      if (onOutline[p] || onBorder || std::fabs(depth - plateDepth[p]) < 4 * step)
      {
        maybe->InsertNextPoint(x);
        ++undecided;
      }
      else if (depth < plateDepth[p])
      {
        surely->InsertNextPoint(x);
      }
    }
    auto project = [&](vtkPoints* points)
    {
      vtkNew<vtkPolyData> part;
      part->SetPoints(points);
      part->GetFieldData()->ShallowCopy(cloud->GetFieldData());
      vtkNew<vtkMCXProjector> projector;
      projector->SetInputData(part);
      projector->SetCamera(camera);
      projector->SetImageSize(width, height);
      projector->Update();
      auto image = vtkSmartPointer<vtkImageData>::New();
      image->DeepCopy(projector->GetOutput());
      return image;
    };
    auto lower = project(surely);
    for (vtkIdType k = 0; k < maybe->GetNumberOfPoints(); ++k)
    {
      surely->InsertNextPoint(maybe->GetPoint(k));
    }
    auto upper = project(surely);
    EXPECT_LT(undecided, cloud->GetNumberOfPoints() / 200) << "few points are undecided";
    vtkDataArray* a = mcxtest::LineIntegral(lower);
    vtkDataArray* b = mcxtest::LineIntegral(upper);
    vtkDataArray* m = mcxtest::LineIntegral(front);
    vtkIdType hidden = 0;
    for (vtkIdType p = 0; p < m->GetNumberOfTuples(); ++p)
    {
      const double v = m->GetTuple1(p);
      ASSERT_GE(v, a->GetTuple1(p) * (1 - 1e-12))
        << (parallel ? "parallel" : "perspective") << " pixel " << p % width << ", " << p / width;
      ASSERT_LE(v, b->GetTuple1(p) * (1 + 1e-12))
        << (parallel ? "parallel" : "perspective") << " pixel " << p % width << ", " << p / width;
      hidden += v < mcxtest::LineIntegral(whole)->GetTuple1(p) ? 1 : 0;
    }
    EXPECT_GT(hidden, covered / 2) << "the plate hides part of the head";
  }
  plateActor->VisibilityOff(); // and back: no depth work again
  scene.Window->Render();
  EXPECT_FALSE(scene.Mapper->GetLastRenderUsedDepth());
}

TEST(Mapper, RegressionImages)
{
  // What is drawn: a window and level, the inverted display on a white
  // background, and the composition with an opaque occluder; fixed seed,
  // all points. (The values drawn are checked against the off-line
  // projector by the tests above.)
  Scene scene(20, 200, 160);
  scene.Mapper->ProgressiveRefinementOff();
  scene.Mapper->AutomaticWindowLevelOff();
  scene.Mapper->SetColorWindow(60); // line integrals reach about 62 (TF units x mm)
  scene.Mapper->SetColorLevel(30);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  scene.Window->Render();
  CompareWithBaseline(scene.Window, "XRayParallel");

  camera->ParallelProjectionOff();
  camera->Azimuth(40);
  camera->Elevation(15);
  camera->OrthogonalizeViewUp();
  camera->Dolly(1.6);
  scene.Renderer->ResetCameraClippingRange();
  scene.Renderer->SetBackground(1, 1, 1);
  scene.Mapper->InvertDisplayOn();
  scene.Window->Render();
  CompareWithBaseline(scene.Window, "XRayInverted");
  scene.Renderer->SetBackground(0, 0, 0);
  scene.Mapper->InvertDisplayOff();

  vtkNew<vtkPlaneSource> tool;
  tool->SetCenter(102, 102, 70);
  tool->SetNormal(1, 0.3, 0.2);
  tool->SetResolution(1, 1);
  vtkNew<vtkPolyDataMapper> toolMapper;
  toolMapper->SetInputConnection(tool->GetOutputPort());
  vtkNew<vtkActor> toolActor;
  toolActor->SetMapper(toolMapper);
  toolActor->SetScale(120);
  toolActor->SetOrigin(102, 102, 70);
  toolActor->GetProperty()->SetColor(0.9, 0.5, 0.1);
  scene.Renderer->AddActor(toolActor);
  scene.Renderer->ResetCameraClippingRange();
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->GetLastRenderUsedDepth());
  CompareWithBaseline(scene.Window, "XRayOccluded");
}

// The automatic window's prefix for a 160 x 128 viewport: the smallest
// 2^k - 1 with at least 4 points per pixel (81920).
constexpr vtkIdType WindowPrefix160x128 = (1 << 17) - 1;

TEST(Mapper, DisplayShowsTheWindowedImage)
{
  // Every pixel drawn is the documented grey of the line integral under it:
  // a set window and level on black, inverted on white, and the automatic
  // window, which is the documented percentile of the block means of the
  // image of the window's prefix (the off-line image of those points).
  Scene scene(18, 160, 128);
  scene.Mapper->ProgressiveRefinementOff();
  scene.Mapper->AutomaticWindowLevelOff();
  scene.Mapper->SetColorWindow(40);
  scene.Mapper->SetColorLevel(25);
  scene.Window->Render();
  auto image = scene.OnScreen();
  vtkDataArray* values = mcxtest::LineIntegral(image);
  EXPECT_EQ(0, MisdrawnPixels(Grab(scene.Window), values, 40, 25));

  scene.Mapper->InvertDisplayOn();
  scene.Renderer->SetBackground(1, 1, 1);
  scene.Window->Render();
  EXPECT_EQ(0, MisdrawnPixels(Grab(scene.Window), values, 40, 25, true));

  scene.Mapper->InvertDisplayOff();
  scene.Renderer->SetBackground(0, 0, 0);
  scene.Mapper->AutomaticWindowLevelOn();
  scene.TransferFunction->AddPoint(2000, 0.5); // a new input: a new automatic window
  scene.Window->Render();
  image = scene.OnScreen();
  values = mcxtest::LineIntegral(image);
  auto prefix = scene.Offline(WindowPrefix160x128);
  const double window = AutomaticWindow(mcxtest::LineIntegral(prefix), 160, 128);
  EXPECT_GT(window, 0.0);
  EXPECT_NEAR(window, scene.Mapper->GetDisplayedWindow(), 1e-6 * window);
  EXPECT_NEAR(0.5 * window, scene.Mapper->GetDisplayedLevel(), 1e-6 * window);
  EXPECT_EQ(0, MisdrawnPixels(Grab(scene.Window), values, window, 0.5 * window));
}

TEST(Mapper, AutomaticWindowIsThePicturesNotTheNoises)
{
  // The automatic window is taken from the window's prefix whatever the
  // sample count (2^17 - 1 to 2^20 - 1 points), the time budget or the
  // refinement: it is the same number for all of them, and stays while
  // points are added.
  double first = 0;
  for (const int exponent : { 17, 18, 20 })
  {
    for (const bool progressive : { false, true })
    {
      Scene scene(exponent, 160, 128);
      scene.Mapper->SetProgressiveRefinement(progressive);
      scene.Window->SetDesiredUpdateRate(progressive ? 1e6 : 1e-3); // a tiny or an ample budget
      scene.Window->Render();
      const double window = scene.Mapper->GetDisplayedWindow();
      first = first > 0 ? first : window;
      EXPECT_EQ(first, window) << exponent << (progressive ? " progressive" : "");
      for (int render = 0; render < 4 && !scene.Mapper->IsRefinementComplete(); ++render)
      {
        scene.Window->Render();
        EXPECT_EQ(first, scene.Mapper->GetDisplayedWindow()) << "after " << render + 1;
      }
    }
  }
  EXPECT_GT(first, 0.0);

  // A first view that shows nothing (ParaView renders before it resets the
  // camera) sets no window; the first view of the volume does.
  Scene scene(17, 160, 128);
  scene.Renderer->GetCullers()->RemoveAllItems(); // as ParaView: the mapper renders anyway
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  double focal[3], position[3];
  camera->GetFocalPoint(focal);
  camera->GetPosition(position);
  camera->SetFocalPoint(focal[0] + 5000, focal[1], focal[2]);
  camera->SetPosition(position[0] + 5000, position[1], position[2]);
  scene.Window->Render();
  auto away = scene.OnScreen();
  vtkDataArray* nothing = mcxtest::LineIntegral(away);
  EXPECT_TRUE(!nothing || nothing->GetRange()[1] == 0.0);
  camera->SetFocalPoint(focal);
  camera->SetPosition(position);
  scene.Window->Render();
  EXPECT_EQ(first, scene.Mapper->GetDisplayedWindow());
}

TEST(Mapper, FilmLooksTheSameOnAnyBackground)
{
  // Film compositing (the default) draws the grey opaquely: on ParaView's
  // blue-grey background the picture is the one on black, and inverted it
  // is the one on white. Additive compositing adds to the background.
  Scene scene(17, 160, 128);
  scene.Mapper->ProgressiveRefinementOff();
  scene.Mapper->AutomaticWindowLevelOff();
  scene.Mapper->SetColorWindow(40);
  scene.Mapper->SetColorLevel(20);
  scene.Window->Render();
  auto image = scene.OnScreen();
  vtkDataArray* values = mcxtest::LineIntegral(image);
  for (const bool invert : { false, true })
  {
    scene.Mapper->SetInvertDisplay(invert);
    scene.Renderer->SetBackground(0.32, 0.34, 0.43);
    scene.Window->Render();
    EXPECT_EQ(0, MisdrawnPixels(Grab(scene.Window), values, 40, 20, invert)) << invert;
  }
  scene.Mapper->InvertDisplayOff();
  scene.Mapper->SetCompositingToAdditive();
  scene.Window->Render();
  EXPECT_GT(MisdrawnPixels(Grab(scene.Window), values, 40, 20), 160 * 128 / 2);
}

TEST(Mapper, CompositedByDepthKeepsThePictureAndMarksItsPixels)
{
  // For a depth compositor (IceT), the image writes a depth just in front of
  // the far plane where nothing opaque was drawn, and nothing where geometry
  // is: the colours and the geometry's depths are those of the ordinary
  // render, for film and additive compositing.
  Scene scene(17, 160, 128);
  scene.Mapper->ProgressiveRefinementOff();
  vtkNew<vtkPlaneSource> plate;
  plate->SetOrigin(40, 60, -20);
  plate->SetPoint1(180, 150, 40);
  plate->SetPoint2(10, 90, 120);
  vtkNew<vtkPolyDataMapper> plateMapper;
  plateMapper->SetInputConnection(plate->GetOutputPort());
  vtkNew<vtkActor> plateActor;
  plateActor->SetMapper(plateMapper);
  scene.Renderer->AddActor(plateActor);
  scene.Renderer->GetActiveCamera()->SetPosition(140, -400, 110);
  scene.Renderer->ResetCameraClippingRange();
  const float marked = 1.0f - std::ldexp(1.0f, -20);
  for (const int compositing : { vtkMCXXRayMapper::FILM, vtkMCXXRayMapper::ADDITIVE })
  {
    scene.Mapper->SetCompositing(compositing);
    std::vector<float> depth[2];
    vtkSmartPointer<vtkImageData> colours[2];
    for (const bool composited : { false, true })
    {
      scene.Mapper->SetCompositedByDepth(composited);
      scene.Window->Render();
      colours[composited] = Grab(scene.Window);
      depth[composited].resize(160 * 128);
      scene.Window->GetZbufferData(0, 0, 159, 127, depth[composited].data());
    }
    vtkDataArray* plain = colours[0]->GetPointData()->GetScalars();
    vtkDataArray* marking = colours[1]->GetPointData()->GetScalars();
    ASSERT_EQ(plain->GetNumberOfValues(), marking->GetNumberOfValues());
    vtkIdType differing = 0;
    for (vtkIdType v = 0; v < plain->GetNumberOfValues(); ++v)
    {
      differing += plain->GetVariantValue(v) == marking->GetVariantValue(v) ? 0 : 1;
    }
    EXPECT_EQ(0, differing) << compositing;
    int empty = 0, geometry = 0, wrong = 0;
    for (std::size_t p = 0; p < depth[0].size(); ++p)
    {
      if (depth[0][p] == 1.0f) // nothing opaque: marked, within the buffer's 2^-24 steps
      {
        ++empty;
        wrong += std::abs(depth[1][p] - marked) <= std::ldexp(1.0f, -23) ? 0 : 1;
      }
      else // the plate's depth, untouched
      {
        ++geometry;
        wrong += depth[1][p] == depth[0][p] ? 0 : 1;
      }
    }
    EXPECT_GT(empty, 160 * 128 / 5) << compositing;
    EXPECT_GT(geometry, 160 * 128 / 5) << compositing;
    EXPECT_EQ(0, wrong) << compositing;
  }
}

TEST(Mapper, BoundsAreTheSupportEvenForAnEmptyCloud)
{
  // A TF that is zero everywhere leaves the cloud empty: the bounds are still
  // the volume's support (a camera reset frames the volume, never NaN).
  Scene scene(12, 64, 64);
  scene.TransferFunction->RemoveAllPoints();
  scene.TransferFunction->AddPoint(0, 0);
  scene.TransferFunction->AddPoint(5000, 0);
  double bounds[6];
  scene.Mapper->GetBounds(bounds);
  double volume[6];
  scene.Reader->Update();
  scene.Reader->GetOutput()->GetBounds(volume);
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_LE(bounds[2 * a], volume[2 * a]);
    EXPECT_GE(bounds[2 * a + 1], volume[2 * a + 1]);
    EXPECT_LT(bounds[2 * a + 1] - bounds[2 * a], 1.5 * (volume[2 * a + 1] - volume[2 * a]));
  }
  scene.Renderer->ResetCamera();
  const double* position = scene.Renderer->GetActiveCamera()->GetPosition();
  EXPECT_TRUE(
    std::isfinite(position[0]) && std::isfinite(position[1]) && std::isfinite(position[2]));
}

TEST(Mapper, FilmKeepsOtherXRaysAndTranslucentProps)
{
  // Film is laid once per render, by the first X-ray: a second X-ray volume
  // beside the first adds to it (both heads show, each as it shows alone),
  // and a translucent prop is not covered.
  Scene scene(16, 200, 100);
  scene.Mapper->ProgressiveRefinementOff();
  scene.Mapper->AutomaticWindowLevelOff();
  scene.Mapper->SetColorWindow(40);
  scene.Mapper->SetColorLevel(20);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetParallelScale(1.2 * camera->GetParallelScale());
  double focal[3];
  camera->GetFocalPoint(focal);
  vtkNew<vtkMCXXRayMapper> secondMapper;
  secondMapper->SetInputConnection(scene.Sampler->GetOutputPort());
  secondMapper->ProgressiveRefinementOff();
  secondMapper->AutomaticWindowLevelOff();
  secondMapper->SetColorWindow(40);
  secondMapper->SetColorLevel(20);
  vtkNew<vtkVolume> second;
  second->SetMapper(secondMapper);
  scene.Renderer->AddVolume(second);
  const double shift = 1.1 * camera->GetParallelScale(); // half the view's height
  double right[3];
  vtkMath::Cross(camera->GetDirectionOfProjection(), camera->GetViewUp(), right);
  vtkMath::Normalize(right);
  scene.Volume->SetPosition(-shift * right[0], -shift * right[1], -shift * right[2]);
  second->SetPosition(shift * right[0], shift * right[1], shift * right[2]);
  scene.Window->Render();
  auto both = Grab(scene.Window);
  vtkDataArray* rgb = both->GetPointData()->GetScalars();
  double halves[2] = { 0, 0 };
  for (vtkIdType p = 0; p < rgb->GetNumberOfTuples(); ++p)
  {
    halves[(p % 200) < 100 ? 0 : 1] += rgb->GetComponent(p, 0);
  }
  EXPECT_GT(halves[0], 0.25 * halves[1]);
  EXPECT_GT(halves[1], 0.25 * halves[0]);

  scene.Renderer->RemoveVolume(second);
  scene.Volume->SetPosition(0, 0, 0);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(focal);
  sphere->SetRadius(0.3 * camera->GetParallelScale());
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> glass;
  glass->SetMapper(sphereMapper);
  glass->GetProperty()->SetColor(1, 0, 0);
  glass->GetProperty()->SetOpacity(0.5);
  scene.Renderer->AddActor(glass);
  scene.Window->Render();
  auto withGlass = Grab(scene.Window);
  vtkDataArray* colours = withGlass->GetPointData()->GetScalars();
  vtkIdType reddish = 0;
  for (vtkIdType p = 0; p < colours->GetNumberOfTuples(); ++p)
  {
    reddish += colours->GetComponent(p, 0) > colours->GetComponent(p, 1) + 40 ? 1 : 0;
  }
  EXPECT_GT(reddish, 100);
}

TEST(Mapper, RadiographPhysicsMatchesTheOfflineFilter)
{
  // Beer-Lambert, Poisson noise and the negative log on screen are
  // vtkMCXRadiograph's images of the same line integrals, pixel for pixel
  // (the noise too: same seed, same counts), each under its own automatic
  // window.
  Scene scene(18, 160, 128);
  scene.TransferFunction->RemoveAllPoints(); // about 0.03 per mm in bone: transmissions 0.1 .. 1
  scene.TransferFunction->AddPoint(400, 0);
  scene.TransferFunction->AddPoint(3926, 0.03);
  scene.Mapper->ProgressiveRefinementOff();
  scene.Window->Render();
  auto lineIntegrals = scene.OnScreen();
  auto prefix = scene.Offline(WindowPrefix160x128); // what the automatic window sees
  struct Case
  {
    const char* Name;
    bool BeerLambert;
    double Photons;
    bool NegativeLog;
  };
  const Case cases[] = { { "Beer-Lambert", true, 0, false }, { "noise", true, 1000, false },
    { "negative log of noise", true, 1000, true }, { "negative log", false, 0, true } };
  for (const Case& c : cases)
  {
    scene.Mapper->SetBeerLambert(c.BeerLambert);
    scene.Mapper->SetIncidentIntensity(2.0);
    scene.Mapper->SetPhotonsPerPixel(c.Photons);
    scene.Mapper->SetNoiseSeed(5);
    scene.Mapper->SetNegativeLog(c.NegativeLog);
    scene.Window->Render();
    // The same physics on the screen's line integrals and on the window's
    // prefix, each from a filter of its own (an update frees the last output).
    vtkNew<vtkMCXRadiograph> radiograph;
    vtkNew<vtkMCXRadiograph> prefixRadiograph;
    for (vtkMCXRadiograph* filter : { radiograph.GetPointer(), prefixRadiograph.GetPointer() })
    {
      filter->SetBeerLambert(c.BeerLambert);
      filter->SetIncidentIntensity(2.0);
      filter->SetPhotonsPerPixel(c.Photons);
      filter->SetNoiseSeed(5);
      filter->SetNegativeLog(c.NegativeLog);
    }
    radiograph->SetInputData(lineIntegrals);
    radiograph->Update();
    prefixRadiograph->SetInputData(prefix);
    prefixRadiograph->Update();
    const char* name =
      c.NegativeLog ? vtkMCXTypes::AttenuationName() : vtkMCXTypes::IntensityName();
    vtkDataArray* expected = radiograph->GetOutput()->GetPointData()->GetArray(name);
    ASSERT_NE(nullptr, expected) << c.Name;
    const double window =
      AutomaticWindow(prefixRadiograph->GetOutput()->GetPointData()->GetArray(name), 160, 128);
    EXPECT_NEAR(window, scene.Mapper->GetDisplayedWindow(), 1e-6 * window) << c.Name;
    EXPECT_EQ(0, MisdrawnPixels(Grab(scene.Window), expected, window, 0.5 * window)) << c.Name;
  }
}

TEST(Mapper, LargeScreenshotsAreOneImageNotTiles)
{
  // vtkWindowToImageFilter at scale 2 (as ParaView's screenshots at a larger
  // resolution) renders four tiles, each through a shifted window centre and
  // the renderer's tiled viewport: together they must be the picture of a
  // window twice the size, not four copies of the small one. Samples are
  // placed by the same geometry up to rounding, so pixels may differ only
  // where a sample sits on a pixel edge.
  for (const bool parallel : { true, false })
  {
    Scene small(18, 160, 128);
    Scene large(18, 320, 256);
    for (Scene* scene : { &small, &large })
    {
      scene->Renderer->GetActiveCamera()->SetParallelProjection(parallel);
      scene->Mapper->ProgressiveRefinementOff();
      scene->Mapper->AutomaticWindowLevelOff();
      scene->Mapper->SetColorWindow(40);
      scene->Mapper->SetColorLevel(20);
    }
    large.Window->Render();
    auto expected = Grab(large.Window);
    small.Window->Render();
    vtkNew<vtkWindowToImageFilter> tiled;
    tiled->SetInput(small.Window);
    tiled->SetScale(2);
    tiled->ReadFrontBufferOff();
    tiled->SetInputBufferTypeToRGB();
    tiled->Update();
    ASSERT_EQ(320, tiled->GetOutput()->GetDimensions()[0]);
    ASSERT_EQ(256, tiled->GetOutput()->GetDimensions()[1]);
    const vtkIdType differing = DifferingColours(tiled->GetOutput(), expected, 3);
    EXPECT_LE(differing, 320 * 256 / 200) << (parallel ? "parallel" : "perspective");
    EXPECT_GT(mcxtest::LineIntegralSum(large.OnScreen()), 0.0);
  }
}

TEST(Mapper, ObliqueParallelCameraIsTheProjectorsView)
{
  // A parallel camera with view shear casts oblique rays: the mapper's image
  // is the off-line projector's for that camera, pixel for pixel, and not the
  // image of the same camera without the shear (which it once drew, with a
  // warning).
  Scene scene(18, 160, 128);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetViewShear(0.45, -0.3, 1.0);
  scene.Mapper->ProgressiveRefinementOff();
  scene.Window->Render();
  auto image = scene.OnScreen();
  EXPECT_EQ(0, DifferingPixels(image, scene.Offline()));
  EXPECT_GT(mcxtest::LineIntegralSum(image), 0.0);
  camera->SetViewShear(0, 0, 1.0);
  EXPECT_GT(DifferingPixels(image, scene.Offline()), 160 * 128 / 4);
}

TEST(Mapper, ViewportSmallerThanTheWindow)
{
  // A renderer in part of the window: the image has the viewport's size and
  // the camera's view of it, and is drawn there only.
  Scene scene(18, 200, 160);
  scene.Renderer->SetViewport(0.2, 0.25, 0.7, 0.9);
  scene.Mapper->ProgressiveRefinementOff();
  scene.Mapper->AutomaticWindowLevelOff();
  scene.Mapper->SetColorWindow(50);
  scene.Mapper->SetColorLevel(25);
  scene.Window->Render();
  int size[2], origin[2];
  scene.Renderer->GetTiledSizeAndOrigin(&size[0], &size[1], &origin[0], &origin[1]);
  EXPECT_EQ(100, size[0]);
  EXPECT_EQ(104, size[1]);
  auto image = scene.OnScreen();
  ASSERT_EQ(size[0], image->GetDimensions()[0]);
  ASSERT_EQ(size[1], image->GetDimensions()[1]);
  EXPECT_EQ(0, DifferingPixels(image, scene.Offline(-1, size)));
  EXPECT_EQ(
    0, MisdrawnPixels(Grab(scene.Window), mcxtest::LineIntegral(image), origin, size, 50, 25));
}

TEST(Mapper, PutsEachPointInVTKsPixel)
{
  // Single points, each far from a pixel border where vtkRenderer's
  // WorldToDisplay puts it: the mapper's image lights exactly those pixels,
  // for a parallel and a perspective camera of a non-square window.
  Scene scene(10, 200, 160);
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 60; ++k)
  {
    points->InsertNextPoint(102 + 80 * std::sin(1.7 * k), 102 + 80 * std::cos(2.3 * k + 1),
      70 + 60 * std::sin(0.9 * k + 0.2));
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<vtkDoubleArray> integral;
  integral->SetName(vtkMCXTypes::IntegralName());
  integral->InsertNextValue(static_cast<double>(points->GetNumberOfPoints()));
  cloud->GetFieldData()->AddArray(integral);
  scene.Mapper->SetInputDataObject(cloud);
  scene.Mapper->ProgressiveRefinementOff();
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->Azimuth(25);
  camera->Elevation(10);
  camera->OrthogonalizeViewUp();
  for (bool parallel : { true, false })
  {
    camera->SetParallelProjection(parallel);
    scene.Renderer->ResetCameraClippingRange();
    scene.Window->Render();
    std::vector<double> expected(200 * 160, 0.0);
    int seen = 0;
    for (vtkIdType k = 0; k < points->GetNumberOfPoints(); ++k)
    {
      const double* x = points->GetPoint(k);
      scene.Renderer->SetWorldPoint(x[0], x[1], x[2], 1.0);
      scene.Renderer->WorldToDisplay();
      const double* d = scene.Renderer->GetDisplayPoint();
      const bool inside = d[0] >= 0 && d[0] < 200 && d[1] >= 0 && d[1] < 160;
      ASSERT_TRUE(
        std::fabs(d[0] - std::round(d[0])) > 1e-3 && std::fabs(d[1] - std::round(d[1])) > 1e-3)
        << "point " << k << " lies on a pixel border";
      if (inside)
      {
        ++seen;
        expected[static_cast<std::size_t>(std::floor(d[0]) + 200 * std::floor(d[1]))] += 1.0;
      }
    }
    ASSERT_GT(seen, 30);
    auto image = scene.OnScreen();
    vtkDataArray* values = mcxtest::LineIntegral(image);
    const double area = image->GetSpacing()[0] * image->GetSpacing()[1];
    for (std::size_t p = 0; p < expected.size(); ++p)
    {
      // Lit where VTK projects a point (each one sample of weight 1, over the
      // pixel area, times the perspective factor), dark elsewhere.
      ASSERT_EQ(expected[p] > 0, values->GetTuple1(p) > 0)
        << (parallel ? "parallel" : "perspective") << " pixel (" << p % 200 << ", " << p / 200
        << ")";
      if (parallel)
      {
        ASSERT_NEAR(expected[p] / area, values->GetTuple1(p), 1e-9 / area);
      }
    }
  }
}
