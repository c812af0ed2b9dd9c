// vtkMCXXRayMapper as a drop-in for vtkSmartVolumeMapper: given the volume
// itself and a TF on the volume's property, it draws the image that the
// explicit index -> sampler -> mapper pipeline draws, bit for bit; it
// indexes once, re-samples on a TF edit, sorts a view-ordered cloud for the
// view of each edit, reads the array a VTK application selects, and refuses
// what is no density in one line. README.md's C++ snippet of the mapper is
// the five lines of DropInMapper.SwitchesAVolumeApplicationToAnXRay.
#include "mcxHeadScene.h"
#include "mcxTestHelpers.h"
#include "vtkMCXFirstErrorObserver.h"
#include "vtkMCXXRayMapper.h"

#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkXMLImageDataReader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace
{
constexpr int Width = 160;
constexpr int Height = 128;

// The image on screen, in line-integral units.
std::vector<double> LineIntegrals(vtkMCXXRayMapper* mapper)
{
  vtkNew<vtkImageData> image;
  mapper->GetLineIntegralImage(image);
  vtkDataArray* values = image->GetPointData()->GetScalars();
  std::vector<double> out(static_cast<std::size_t>(values ? values->GetNumberOfTuples() : 0));
  for (std::size_t p = 0; p < out.size(); ++p)
  {
    out[p] = values->GetTuple1(static_cast<vtkIdType>(p));
  }
  return out;
}

// The head scene's view (mcxHeadScene.h) in a window of its own around a
// mapper that is given the volume.
struct VolumeScene
{
  vtkNew<vtkXMLImageDataReader> reader;
  vtkNew<vtkPiecewiseFunction> tf;
  vtkNew<vtkVolume> volume;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> renderWindow;

  VolumeScene()
  {
    this->reader->SetFileName(MCXRAY_TEST_DATA_DIR "/ct_head_headsq.vti");
    this->tf->AddPoint(400, 0);
    this->tf->AddPoint(3926, 1);
    this->renderer->AddVolume(this->volume);
    this->renderWindow->SetOffScreenRendering(1);
    this->renderWindow->SetMultiSamples(0);
    this->renderWindow->SetSize(Width, Height);
    this->renderWindow->AddRenderer(this->renderer);
    vtkCamera* camera = this->renderer->GetActiveCamera();
    camera->SetFocalPoint(102, 102, 70);
    camera->SetPosition(102, -500, 70);
    camera->SetViewUp(0, 0, 1);
    camera->SetParallelScale(90);
  }
};
}

TEST(DropInMapper, SwitchesAVolumeApplicationToAnXRay)
{
  // A volume application's scene; its mapper replaced by the X-ray mapper
  // draws the explicit pipeline's image (same TF, points and seed), bit for bit.
  VolumeScene scene;
  vtkXMLImageDataReader* reader = scene.reader;
  vtkVolume* volume = scene.volume;
  vtkPiecewiseFunction* tf = scene.tf;
  vtkRenderWindow* renderWindow = scene.renderWindow;

  vtkNew<vtkMCXXRayMapper> mapper; // was vtkSmartVolumeMapper
  mapper->SetInputConnection(reader->GetOutputPort());
  volume->SetMapper(mapper);
  volume->GetProperty()->SetScalarOpacity(tf); // X-ray weight per data value
  renderWindow->Render();

  mcxtest::HeadScene pipeline(vtkMCXTypes::DefaultSampleExponent, Width, Height);
  pipeline.Sampler->SetSeed(0);
  pipeline.Sampler->SetDeposit(vtkMCXTypes::FOOTPRINT); // the classes' default
  pipeline.Mapper->ProgressiveRefinementOff();
  mapper->ProgressiveRefinementOff();
  renderWindow->Render();
  pipeline.Window->Render();
  EXPECT_EQ(mapper->GetNumberOfInputPoints(), (vtkTypeInt64(1) << 22) - 1);
  EXPECT_TRUE(mapper->IsRefinementComplete());
  const std::vector<double> dropIn = LineIntegrals(mapper);
  const std::vector<double> explicitPipeline = LineIntegrals(pipeline.Mapper);
  ASSERT_EQ(static_cast<std::size_t>(Width * Height), dropIn.size());
  EXPECT_TRUE(dropIn == explicitPipeline);
  double total = 0;
  for (double v : dropIn)
  {
    total += v;
  }
  EXPECT_GT(total, 0.0);
  // The camera reset frames the sampler's support, as for a cloud input.
  double expected[6], bounds[6];
  pipeline.Mapper->GetBounds(expected);
  mapper->GetBounds(bounds);
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_DOUBLE_EQ(expected[i], bounds[i]);
  }
}

TEST(DropInMapper, IndexesOnceAndResamplesOnATransferFunctionEdit)
{
  VolumeScene scene;
  vtkNew<vtkMCXXRayMapper> mapper;
  mapper->SetInputConnection(scene.reader->GetOutputPort());
  mapper->SetSampleExponent(16);
  mapper->ProgressiveRefinementOff();
  scene.volume->SetMapper(mapper);
  scene.volume->GetProperty()->SetScalarOpacity(scene.tf);
  mcxtest::ExecutionCounter indexRuns(mapper->GetDensityIndex());
  mcxtest::ExecutionCounter samplerRuns(mapper->GetPointSampler());
  scene.renderWindow->Render();
  EXPECT_EQ(1, indexRuns.Count);
  EXPECT_EQ(1, samplerRuns.Count);
  const std::vector<double> first = LineIntegrals(mapper);

  scene.renderer->GetActiveCamera()->Azimuth(30); // a camera move projects again only
  scene.renderWindow->Render();
  EXPECT_EQ(1, indexRuns.Count);
  EXPECT_EQ(1, samplerRuns.Count);
  EXPECT_EQ(2, mapper->GetNumberOfRestarts());

  scene.tf->AddPoint(1000, 0.5); // a TF edit re-samples, never re-indexes
  scene.renderWindow->Render();
  EXPECT_EQ(1, indexRuns.Count);
  EXPECT_EQ(2, samplerRuns.Count);
  EXPECT_EQ(3, mapper->GetNumberOfRestarts());

  mapper->SetSampleExponent(17); // a sampling setting re-samples too
  scene.renderWindow->Render();
  EXPECT_EQ(1, indexRuns.Count);
  EXPECT_EQ(3, samplerRuns.Count);
  EXPECT_EQ((vtkTypeInt64(1) << 17) - 1, mapper->GetNumberOfInputPoints());

  scene.reader->Modified(); // a new volume is indexed again
  scene.renderWindow->Render();
  EXPECT_EQ(2, indexRuns.Count);
  EXPECT_EQ(4, samplerRuns.Count);

  // Back to the first TF, view and count: the first image again.
  scene.tf->RemovePoint(1000);
  scene.renderer->GetActiveCamera()->Azimuth(-30);
  mapper->SetSampleExponent(16);
  scene.renderWindow->Render();
  EXPECT_TRUE(LineIntegrals(mapper) == first);
}

TEST(DropInMapper, ViewOrderedVolumeIsSortedForTheViewOfEachEdit)
{
  // The view-ordered strategy holds its control image in the view it was
  // sorted for: the first render's, and after a TF edit the view of then.
  VolumeScene scene;
  vtkNew<vtkMCXXRayMapper> mapper;
  mapper->SetInputConnection(scene.reader->GetOutputPort());
  mapper->SetStrategy(vtkMCXTypes::VIEW_ORDERED);
  mapper->SetSampleExponent(16);
  mapper->ProgressiveRefinementOff();
  scene.volume->SetMapper(mapper);
  scene.volume->GetProperty()->SetScalarOpacity(scene.tf);
  mcxtest::ExecutionCounter samplerRuns(mapper->GetPointSampler());
  scene.renderWindow->Render();
  EXPECT_TRUE(mapper->GetLastRenderUsedControlImage());
  scene.renderer->GetActiveCamera()->Azimuth(40); // no sort for a camera move
  scene.renderWindow->Render();
  EXPECT_EQ(1, samplerRuns.Count);
  EXPECT_FALSE(mapper->GetLastRenderUsedControlImage());
  scene.tf->AddPoint(1000, 0.5); // the edit sorts for the moved view
  scene.renderWindow->Render();
  EXPECT_EQ(2, samplerRuns.Count);
  EXPECT_TRUE(mapper->GetLastRenderUsedControlImage());
}

TEST(DropInMapper, ReadsTheSelectedArrayAndRefusesWhatIsNoDensity)
{
  // Two arrays: the active scalars are zero, "density" is 1 in a 5^3 block.
  vtkNew<vtkImageData> image;
  image->SetDimensions(9, 9, 9);
  vtkNew<vtkFloatArray> zeros, density, vectors;
  zeros->SetName("zeros");
  density->SetName("density");
  vectors->SetName("vectors");
  vectors->SetNumberOfComponents(3);
  const vtkIdType n = image->GetNumberOfPoints();
  zeros->SetNumberOfValues(n);
  density->SetNumberOfValues(n);
  vectors->SetNumberOfTuples(n);
  for (vtkIdType p = 0; p < n; ++p)
  {
    int ijk[3] = { static_cast<int>(p % 9), static_cast<int>(p / 9 % 9), static_cast<int>(p / 81) };
    const bool inside =
      ijk[0] >= 2 && ijk[0] <= 6 && ijk[1] >= 2 && ijk[1] <= 6 && ijk[2] >= 2 && ijk[2] <= 6;
    zeros->SetValue(p, 0.0f);
    density->SetValue(p, inside ? 1.0f : 0.0f);
    vectors->SetTuple3(p, 1, 1, 1);
  }
  image->GetPointData()->SetScalars(zeros);
  image->GetPointData()->AddArray(density);
  image->GetPointData()->AddArray(vectors);

  VolumeScene scene;
  vtkNew<vtkPiecewiseFunction> identity; // g = the density
  identity->AddPoint(0, 0);
  identity->AddPoint(1, 1);
  vtkNew<vtkMCXXRayMapper> mapper;
  mapper->SetInputData(image);
  mapper->ProgressiveRefinementOff();
  mapper->SetSampleExponent(14);
  scene.volume->SetMapper(mapper);
  scene.volume->GetProperty()->SetScalarOpacity(identity);
  vtkCamera* camera = scene.renderer->GetActiveCamera();
  camera->SetFocalPoint(4, 4, 4);
  camera->SetPosition(4, -100, 4);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(8);
  scene.renderer->ResetCameraClippingRange(-1, 10, -1, 10, -1, 10);

  auto mass = [&]()
  {
    vtkNew<vtkImageData> shown;
    mapper->GetLineIntegralImage(shown);
    const double* spacing = shown->GetSpacing();
    double sum = 0;
    vtkDataArray* values = shown->GetPointData()->GetScalars();
    for (vtkIdType p = 0; values && p < values->GetNumberOfTuples(); ++p)
    {
      sum += values->GetTuple1(p);
    }
    return sum * spacing[0] * spacing[1];
  };
  scene.renderWindow->Render(); // the active scalars: nothing to see
  EXPECT_EQ(0.0, mass());

  // The integral of the tent-reconstructed block: 5^3 voxels of 1.
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectScalarArray("density");
  scene.renderWindow->Render();
  EXPECT_NEAR(125.0, mass(), 1e-9 * 125.0);

  vtkNew<vtkMCXFirstErrorObserver> errors;
  mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  mapper->SelectScalarArray("vectors");
  scene.renderWindow->Render();
  EXPECT_EQ("Cannot draw this volume as an X-ray: the selected array has 3 components; select a "
            "one-component density array.",
    errors->GetErrorText());
  errors->Clear();
  mapper->SelectScalarArray("missing");
  scene.renderWindow->Render();
  EXPECT_EQ("Cannot draw this volume as an X-ray: the selected array is not among its point data.",
    errors->GetErrorText());
}
