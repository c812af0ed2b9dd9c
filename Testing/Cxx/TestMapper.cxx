// The X-ray mapper in a real render window (Xvfb + Mesa here): its image
// equals the off-line projector's for the same camera and points, it refines
// by prefixes without restarting, it recomputes only what a change calls for,
// it culls samples behind opaque geometry only when there is some, and its
// pictures match the baselines.
#include "mcxHeadScene.h"
#include "mcxTestHelpers.h"
#include "vtkMCXProjector.h"
#include "vtkMCXXRayMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
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
#include "vtkWindowToImageFilter.h"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace
{
// The bundled CT head (204 x 204 x 140 mm), with the checks the tests share.
struct Scene : mcxtest::HeadScene
{
  explicit Scene(int exponent = 18, int width = 160, int height = 128)
    : HeadScene(exponent, width, height)
  {
  }

  // The off-line projector's image of the first n points for the renderer's camera.
  vtkSmartPointer<vtkImageData> Offline(vtkIdType n = -1)
  {
    this->Sampler->Update();
    vtkPolyData* cloud = this->Sampler->GetOutput();
    vtkNew<vtkPolyData> prefix;
    prefix->DeepCopy(cloud);
    if (n >= 0)
    {
      prefix->GetPoints()->Resize(n);
      prefix->GetPoints()->SetNumberOfPoints(n);
      const double integral = mcxtest::FieldValue(cloud, "Integral");
      vtkDoubleArray::SafeDownCast(prefix->GetFieldData()->GetArray("SampleWeight"))
        ->SetValue(0, integral / static_cast<double>(n));
    }
    vtkNew<vtkMCXProjector> projector;
    projector->SetInputData(prefix);
    projector->SetCamera(this->Renderer->GetActiveCamera());
    const int* size = this->Window->GetSize();
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

double Sum(vtkImageData* image)
{
  double sum = 0;
  vtkDataArray* values = mcxtest::LineIntegral(image);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    sum += values->GetTuple1(i);
  }
  return sum;
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
  vtkNew<vtkImageDifference> difference;
  difference->SetInputConnection(grab->GetOutputPort());
  difference->SetImageConnection(reader->GetOutputPort());
  difference->Update();
  // A few grey levels of slack for another GL driver's rounding.
  EXPECT_LT(difference->GetThresholdedError(), 10.0) << name << ": compare " << actual;
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
  EXPECT_GT(Sum(offline), 0.0);
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
  EXPECT_GT(Sum(offline), 0.0);
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
        // Away and back: a new projection of the same view each time.
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
  }
  EXPECT_EQ((1 << 18) - 1, counts.back());
  EXPECT_EQ(1, scene.Mapper->GetNumberOfRestarts());
  EXPECT_EQ(static_cast<vtkTypeInt64>(counts.size() - 1), scene.Mapper->GetNumberOfRefinements());
  // The refined image is the image of all points, bit for bit.
  EXPECT_EQ(0, DifferingPixels(scene.OnScreen(), scene.Offline()));
  // Its error estimate is that of the off-line projector from the same halves.
  const double estimate = scene.Mapper->GetEstimatedRelativeError();
  EXPECT_GT(estimate, 0.0);
  EXPECT_LT(estimate, 0.5);

  // A still view (no time limit) completes in one render.
  scene.Renderer->GetActiveCamera()->Azimuth(5);
  scene.Window->SetDesiredUpdateRate(0.0001);
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->IsRefinementComplete());
  EXPECT_EQ(2, scene.Mapper->GetNumberOfRestarts());
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

TEST(Mapper, OpaqueGeometryHidesTheSamplesBehindIt)
{
  Scene scene(18);
  scene.Mapper->ProgressiveRefinementOff();
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  // A plate through the middle of the head, facing the camera (which looks along +y).
  vtkNew<vtkPlaneSource> plate;
  plate->SetOrigin(-100, 102, -100);
  plate->SetPoint1(300, 102, -100);
  plate->SetPoint2(-100, 102, 300);
  vtkNew<vtkPolyDataMapper> plateMapper;
  plateMapper->SetInputConnection(plate->GetOutputPort());
  vtkNew<vtkActor> plateActor;
  plateActor->SetMapper(plateMapper);
  plateActor->GetProperty()->SetColor(0.2, 0.4, 0.8);
  plateActor->VisibilityOff();
  scene.Renderer->AddActor(plateActor);
  scene.Renderer->ResetCameraClippingRange();

  // A hidden actor is no occluder: no depth work, the whole head counts.
  scene.Window->Render();
  EXPECT_FALSE(scene.Mapper->GetLastRenderUsedDepth());
  auto whole = scene.OnScreen();
  EXPECT_EQ(0, DifferingPixels(whole, scene.Offline()));

  plateActor->VisibilityOn();
  scene.Window->Render();
  EXPECT_TRUE(scene.Mapper->GetLastRenderUsedDepth());
  EXPECT_EQ(2, scene.Mapper->GetNumberOfRestarts());
  auto front = scene.OnScreen();

  // Expected: the off-line image of the points in front of the plate (y < 102).
  scene.Sampler->Update();
  vtkPolyData* cloud = scene.Sampler->GetOutput();
  vtkNew<vtkPoints> frontPoints;
  frontPoints->SetDataTypeToFloat();
  vtkIdType nearPlate = 0;
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    const double* p = cloud->GetPoint(i);
    nearPlate += std::fabs(p[1] - 102) < 1e-3 ? 1 : 0;
    if (p[1] < 102)
    {
      frontPoints->InsertNextPoint(p);
    }
  }
  vtkNew<vtkPolyData> frontCloud;
  frontCloud->SetPoints(frontPoints);
  frontCloud->GetFieldData()->ShallowCopy(cloud->GetFieldData());
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputData(frontCloud);
  projector->SetCamera(camera);
  projector->SetImageSize(160, 128);
  projector->Update();
  // Only points within the depth buffer's resolution of the plate may differ.
  const double weight = mcxtest::FieldValue(cloud, "SampleWeight");
  const double pixelArea = std::pow(projector->GetOutput()->GetSpacing()[0], 2);
  EXPECT_NEAR(Sum(projector->GetOutput()), Sum(front), (nearPlate + 1) * weight / pixelArea);
  EXPECT_LT(Sum(front), 0.7 * Sum(whole));
  EXPECT_GT(Sum(front), 0.3 * Sum(whole));

  plateActor->VisibilityOff(); // and back: no depth work again
  scene.Window->Render();
  EXPECT_FALSE(scene.Mapper->GetLastRenderUsedDepth());
  EXPECT_EQ(0, DifferingPixels(whole, scene.OnScreen()));
}

TEST(Mapper, RegressionImages)
{
  // Parallel, perspective, and a scene with an opaque occluder; fixed seed,
  // window and level, all points.
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
  scene.Window->Render();
  CompareWithBaseline(scene.Window, "XRayPerspective");

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
