// A scripted session with the viewer behind `mcxray view`: mouse and key
// events in, frames out, TF edits applied through the keys and the sliders,
// progressive refinement driven by the timer.
#include "mcxXRayViewer.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXXRayMapper.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSliderRepresentation2D.h"
#include "vtkSliderWidget.h"
#include "vtkTextActor.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLImageDataReader.h"

#include "mcxTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace
{
constexpr int Size = 320;

// Mean grey level of the window's current frame, 0..255.
double MeanBrightness(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkDataArray* rgb = grab->GetOutput()->GetPointData()->GetScalars();
  double sum = 0;
  for (vtkIdType i = 0; i < rgb->GetNumberOfTuples(); ++i)
  {
    sum += rgb->GetComponent(i, 0);
  }
  return sum / rgb->GetNumberOfTuples();
}

void Press(vtkRenderWindowInteractor* interactor, char key)
{
  const char symbol[2] = { key, '\0' };
  interactor->SetKeyEventInformation(0, 0, key, 1, symbol);
  interactor->InvokeEvent(vtkCommand::KeyPressEvent);
  interactor->InvokeEvent(vtkCommand::CharEvent);
  interactor->InvokeEvent(vtkCommand::KeyReleaseEvent);
}

void Drag(vtkRenderWindowInteractor* interactor, int x0, int y0, int x1, int y1)
{
  interactor->SetEventInformation(x0, y0);
  interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent);
  const int steps = 5;
  for (int s = 1; s <= steps; ++s)
  {
    interactor->SetEventInformation(x0 + (x1 - x0) * s / steps, y0 + (y1 - y0) * s / steps);
    interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  }
  interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
}

vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  return grab->GetOutput();
}

// Keeps the frame as a PNG beside the test, to be looked at.
void SavePNG(vtkImageData* image, const char* name)
{
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(name);
  writer->Write();
}

// WCAG relative luminance of an 8-bit sRGB pixel, 0 (black) to 1 (white).
double Luminance(const unsigned char* rgb)
{
  auto linear = [](unsigned char c)
  {
    const double v = c / 255.0;
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  };
  return 0.2126 * linear(rgb[0]) + 0.7152 * linear(rgb[1]) + 0.0722 * linear(rgb[2]);
}

// WCAG contrast ratio (1 to 21) between the darkest and the brightest 2 %
// of the pixels in [x0, x1) x [y0, y1): the ink of a control against what
// it is drawn on (4.5 reads as body text, 3 as large text).
double RegionContrast(vtkImageData* image, int x0, int y0, int x1, int y1)
{
  const int* dims = image->GetDimensions();
  std::vector<double> values;
  for (int y = std::max(0, y0); y < std::min(dims[1], y1); ++y)
  {
    for (int x = std::max(0, x0); x < std::min(dims[0], x1); ++x)
    {
      values.push_back(Luminance(static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0))));
    }
  }
  if (values.empty())
  {
    return 0.0; // no region: nothing reads
  }
  std::sort(values.begin(), values.end());
  const double dark = values[values.size() / 50];
  const double light = values[values.size() - 1 - values.size() / 50];
  return (light + 0.05) / (dark + 0.05);
}

// Mean grey (channel 0) of the n x n pixels around the image centre.
double CentreGrey(vtkImageData* image, int n)
{
  const int* dims = image->GetDimensions();
  double sum = 0;
  for (int y = dims[1] / 2 - n / 2; y < dims[1] / 2 - n / 2 + n; ++y)
  {
    for (int x = dims[0] / 2 - n / 2; x < dims[0] / 2 - n / 2 + n; ++x)
    {
      sum += static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0))[0];
    }
  }
  return sum / (n * n);
}

// A CT phantom in HU (short): air (-1000) around a water cylinder (0 HU,
// radius 30 mm, along z) holding a bone rod (1000 HU, radius 8 mm); 2 mm voxels.
vtkSmartPointer<vtkImageData> HounsfieldPhantom()
{
  const int dims[3] = { 64, 64, 64 };
  const double spacing[3] = { 2, 2, 2 };
  return mcxtest::MakeVolume(
    VTK_SHORT, dims,
    [](int i, int j, int)
    {
      const double r = 2.0 * std::hypot(i - 31.5, j - 31.5);
      return r < 8 ? 1000.0 : r < 30 ? 0.0 : -1000.0;
    },
    spacing);
}

std::string Formatted(const char* format, double value)
{
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

vtkSmartPointer<vtkImageData> BundledCT()
{
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(MCXRAY_TEST_DATA_DIR "/ct_head_headsq.vti");
  reader->Update();
  return reader->GetOutput();
}
}

TEST(Viewer, ScriptedSession)
{
  mcxapp::ViewerOptions options;
  options.SampleExponent = 18;
  options.Size[0] = options.Size[1] = Size;
  options.OffScreen = true;
  mcxapp::XRayViewer viewer(BundledCT(), options);
  ASSERT_EQ("", viewer.Error());
  vtkRenderWindowInteractor* interactor = viewer.GetInteractor();
  interactor->Initialize();
  mcxtest::ExecutionCounter samplerRuns(viewer.GetSampler());

  // First frame, refined to all points; the overlay reports them.
  viewer.RefineUntilComplete();
  EXPECT_TRUE(viewer.GetMapper()->IsRefinementComplete());
  EXPECT_EQ(1, samplerRuns.Count);
  const std::string overlay = viewer.OverlayText();
  EXPECT_NE(std::string::npos, overlay.find("262,143 of 262,143 samples")) << overlay;
  EXPECT_NE(std::string::npos, overlay.find("est. error")) << overlay;
  EXPECT_NE(std::string::npos, overlay.find("ms/frame")) << overlay;
  const double errorEstimate = viewer.GetMapper()->GetEstimatedRelativeError();
  EXPECT_GT(errorEstimate, 0.0);
  EXPECT_LT(errorEstimate, 1.0);

  // A left drag rotates the camera: frames are drawn, only the projection is redone.
  double before[3], after[3];
  viewer.GetRenderer()->GetActiveCamera()->GetPosition(before);
  const int frames = viewer.GetNumberOfFrames();
  const vtkTypeInt64 restarts = viewer.GetMapper()->GetNumberOfRestarts();
  Drag(interactor, Size / 2, Size / 2, Size / 2 + 60, Size / 2 + 10);
  viewer.GetRenderer()->GetActiveCamera()->GetPosition(after);
  EXPECT_GT(std::hypot(after[0] - before[0], after[1] - before[1], after[2] - before[2]), 1.0);
  EXPECT_GE(viewer.GetNumberOfFrames(), frames + 5);
  EXPECT_GT(viewer.GetMapper()->GetNumberOfRestarts(), restarts);
  EXPECT_EQ(1, samplerRuns.Count);

  // Key 3: the soft-tissue preset; the style must not see it (it would turn stereo on).
  Press(interactor, '3');
  vtkPiecewiseFunction* tf = viewer.GetTransferFunction();
  EXPECT_DOUBLE_EQ(1.0, tf->GetValue(0));
  EXPECT_DOUBLE_EQ(0.0, tf->GetValue(-300));
  EXPECT_FALSE(viewer.GetRenderWindow()->GetStereoRender());
  EXPECT_EQ(2, samplerRuns.Count);

  // Key 2: the bone preset (0 below 150, 1 from 700); the sampler reruns once.
  Press(interactor, '2');
  EXPECT_EQ(2, tf->GetSize());
  EXPECT_DOUBLE_EQ(0.0, tf->GetValue(150));
  EXPECT_DOUBLE_EQ(1.0, tf->GetValue(700));
  EXPECT_DOUBLE_EQ(0.5, tf->GetValue(425));
  EXPECT_EQ(3, samplerRuns.Count);

  // A click on the centre slider's track jumps the TF window's centre there.
  auto* centre =
    vtkSliderRepresentation2D::SafeDownCast(viewer.GetCentreSlider()->GetRepresentation());
  auto* width =
    vtkSliderRepresentation2D::SafeDownCast(viewer.GetWidthSlider()->GetRepresentation());
  const double* p1 = centre->GetPoint1Coordinate()->GetValue();
  const double* p2 = centre->GetPoint2Coordinate()->GetValue();
  const double t = 0.6;
  const int x = static_cast<int>((p1[0] + t * (p2[0] - p1[0])) * Size);
  const int y = static_cast<int>(p1[1] * Size);
  interactor->SetEventInformation(x, y);
  interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent);
  interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
  const double expectedCentre =
    centre->GetMinimumValue() + t * (centre->GetMaximumValue() - centre->GetMinimumValue());
  EXPECT_NEAR(expectedCentre, centre->GetValue(),
    0.02 * (centre->GetMaximumValue() - centre->GetMinimumValue()));
  double range[2];
  tf->GetRange(range);
  EXPECT_NEAR(centre->GetValue(), 0.5 * (range[0] + range[1]), 1e-9 * centre->GetMaximumValue());
  EXPECT_NEAR(width->GetValue(), range[1] - range[0], 1e-9 * width->GetMaximumValue());
  EXPECT_EQ(4, samplerRuns.Count);

  // Progressive refinement from the timer: with about a microsecond per
  // frame each timer tick adds one Halton level until all points count.
  viewer.GetMapper()->AutomaticWindowLevelOff(); // else the first image has 4 points per pixel
  viewer.GetInteractor()->SetStillUpdateRate(1e6);
  viewer.GetRenderWindow()->SetDesiredUpdateRate(1e6);
  Press(interactor, '1');
  EXPECT_FALSE(viewer.GetMapper()->IsRefinementComplete());
  vtkTypeInt64 previous = viewer.GetMapper()->GetNumberOfAccumulatedSamples();
  int ticks = 0;
  while (!viewer.GetMapper()->IsRefinementComplete() && ticks < 50)
  {
    interactor->InvokeEvent(vtkCommand::TimerEvent);
    ++ticks;
    const vtkTypeInt64 now = viewer.GetMapper()->GetNumberOfAccumulatedSamples();
    EXPECT_EQ(2 * previous + 1, now);
    previous = now;
  }
  EXPECT_TRUE(viewer.GetMapper()->IsRefinementComplete());
  EXPECT_GT(ticks, 2);
  interactor->InvokeEvent(vtkCommand::TimerEvent); // one more frame brings the overlay up to date
  EXPECT_NE(std::string::npos, viewer.OverlayText().find("262,143 of 262,143"))
    << viewer.OverlayText();

  // Key i inverts the display (film on a white light box): each pixel's
  // 255 g on black becomes 255 (1 - g) on white, so the mean brightness goes
  // to 255 minus the old one, up to the overlay's text and sliders (a few
  // percent of the window, drawn alike both ways). p switches to parallel.
  const double dark = MeanBrightness(viewer.GetRenderWindow());
  Press(interactor, 'i');
  EXPECT_TRUE(viewer.GetMapper()->GetInvertDisplay());
  EXPECT_NEAR(255.0 - dark, MeanBrightness(viewer.GetRenderWindow()), 12.0) << "dark " << dark;
  Press(interactor, 'p');
  EXPECT_TRUE(viewer.GetRenderer()->GetActiveCamera()->GetParallelProjection());
  EXPECT_EQ(5, samplerRuns.Count) << "display and projection keys never resample";

  // + doubles the points.
  Press(interactor, '+');
  EXPECT_EQ(19, viewer.GetSampler()->GetSampleExponent());
  EXPECT_EQ(6, samplerRuns.Count);
}

TEST(Viewer, ViewOrderedSessionSortsForTheViewOfEachTFEdit)
{
  // --method view-ordered: the sampler is ordered by the window's view from
  // the start; a camera move alone neither sorts nor samples again; the TF
  // edit after it orders by the moved camera, and the image is the cloud
  // sorted for that view, all of its points, with its control image (not
  // in the moved view before the edit). A turn past the mapper's
  // ReorderAngle (30 degrees) sorts; a smaller one keeps that order, and
  // the TF edit after it shows the turned view's control image.
  mcxapp::ViewerOptions options;
  options.Strategy = vtkMCXTypes::VIEW_ORDERED;
  options.SampleExponent = 16;
  options.Size[0] = options.Size[1] = Size;
  options.OffScreen = true;
  mcxapp::XRayViewer viewer(BundledCT(), options);
  ASSERT_EQ("", viewer.Error());
  vtkRenderWindowInteractor* interactor = viewer.GetInteractor();
  interactor->Initialize();
  mcxtest::ExecutionCounter samplerRuns(viewer.GetSampler());
  viewer.RefineUntilComplete();
  // The mapper sorts for the view of its first render (it sees the camera
  // only then), before it samples.
  EXPECT_TRUE(viewer.GetSampler()->HasOrderingView());
  EXPECT_EQ(1, samplerRuns.Count);
  EXPECT_EQ(65535, viewer.GetMapper()->GetNumberOfAccumulatedSamples());
  EXPECT_GT(MeanBrightness(viewer.GetRenderWindow()), 1.0);
  EXPECT_TRUE(viewer.GetMapper()->GetLastRenderUsedControlImage());
  viewer.GetRenderer()->GetActiveCamera()->Azimuth(40);
  viewer.RefineUntilComplete();
  EXPECT_EQ(1, samplerRuns.Count);
  EXPECT_FALSE(viewer.GetMapper()->GetLastRenderUsedControlImage());
  Press(interactor, '2'); // bone
  viewer.RefineUntilComplete();
  EXPECT_EQ(2, samplerRuns.Count);
  EXPECT_TRUE(viewer.GetMapper()->GetLastRenderUsedControlImage());
  vtkNew<vtkMCXPointSampler> fresh;
  fresh->SetInputConnection(viewer.GetIndex()->GetOutputPort());
  fresh->SetTransferFunction(viewer.GetTransferFunction());
  fresh->SetStrategyToViewOrdered();
  fresh->SetSampleExponent(16);
  fresh->SetDeposit(viewer.GetSampler()->GetDeposit());
  fresh->SetOrderingView(viewer.GetRenderer()->GetActiveCamera(), Size, Size);
  fresh->Update();
  vtkPolyData* shown = viewer.GetSampler()->GetOutput();
  ASSERT_EQ(fresh->GetOutput()->GetNumberOfPoints(), shown->GetNumberOfPoints());
  const float* a = static_cast<const float*>(fresh->GetOutput()->GetPoints()->GetVoidPointer(0));
  const float* b = static_cast<const float*>(shown->GetPoints()->GetVoidPointer(0));
  EXPECT_TRUE(std::equal(a, a + 3 * shown->GetNumberOfPoints(), b));
  EXPECT_EQ(65535, viewer.GetMapper()->GetNumberOfAccumulatedSamples());

  EXPECT_EQ(30.0, viewer.GetSampler()->GetReorderAngle());
  viewer.GetRenderer()->GetActiveCamera()->Azimuth(10);
  Press(interactor, '3'); // soft tissue
  viewer.RefineUntilComplete();
  EXPECT_EQ(3, samplerRuns.Count);
  EXPECT_TRUE(viewer.GetMapper()->GetLastRenderUsedControlImage());
  fresh->Update(); // the new TF, sorted for the view before the turn
  shown = viewer.GetSampler()->GetOutput();
  ASSERT_EQ(fresh->GetOutput()->GetNumberOfPoints(), shown->GetNumberOfPoints());
  a = static_cast<const float*>(fresh->GetOutput()->GetPoints()->GetVoidPointer(0));
  b = static_cast<const float*>(shown->GetPoints()->GetVoidPointer(0));
  EXPECT_TRUE(std::equal(a, a + 3 * shown->GetNumberOfPoints(), b));

  // --reorder-angle reaches the mapper and its sampler.
  options.ReorderAngle = 12.5;
  mcxapp::XRayViewer other(BundledCT(), options);
  ASSERT_EQ("", other.Error());
  EXPECT_EQ(12.5, other.GetMapper()->GetReorderAngle());
  other.RefineUntilComplete();
  EXPECT_EQ(12.5, other.GetSampler()->GetReorderAngle());
}

TEST(Viewer, EveryVoxelSession)
{
  // --method every-voxel: the overlay counts voxels and shows no error
  // estimate; + and - leave the cloud alone; a preset reruns the sampler
  // once, for a cloud of the voxels it keeps.
  mcxapp::ViewerOptions options;
  options.Strategy = vtkMCXTypes::EVERY_VOXEL;
  options.TransferFunction = "bone";
  options.Size[0] = options.Size[1] = Size;
  options.OffScreen = true;
  mcxapp::XRayViewer viewer(BundledCT(), options);
  ASSERT_EQ("", viewer.Error());
  vtkRenderWindowInteractor* interactor = viewer.GetInteractor();
  interactor->Initialize();
  mcxtest::ExecutionCounter samplerRuns(viewer.GetSampler());
  viewer.RefineUntilComplete();
  const vtkIdType bone = viewer.GetSampler()->GetOutput()->GetNumberOfPoints();
  ASSERT_GT(bone, 1000);
  EXPECT_EQ(bone, viewer.GetMapper()->GetNumberOfAccumulatedSamples());
  const std::string overlay = viewer.OverlayText();
  EXPECT_NE(std::string::npos, overlay.find(" voxels ")) << overlay;
  EXPECT_NE(std::string::npos, overlay.find("each voxel once")) << overlay;
  EXPECT_EQ(std::string::npos, overlay.find("est. error")) << overlay;
  EXPECT_GT(MeanBrightness(viewer.GetRenderWindow()), 1.0);
  Press(interactor, '+');
  Press(interactor, '-');
  EXPECT_EQ(1, samplerRuns.Count);
  Press(interactor, '3'); // soft tissue: other voxels
  viewer.RefineUntilComplete();
  EXPECT_EQ(2, samplerRuns.Count);
  EXPECT_NE(bone, viewer.GetSampler()->GetOutput()->GetNumberOfPoints());
  EXPECT_EQ(viewer.GetSampler()->GetOutput()->GetNumberOfPoints(),
    viewer.GetMapper()->GetNumberOfAccumulatedSamples());
}

namespace
{
mcxapp::ViewerOptions SmallWindowOptions(int sampleExponent)
{
  mcxapp::ViewerOptions options;
  options.SampleExponent = sampleExponent;
  options.Size[0] = options.Size[1] = Size;
  options.OffScreen = true;
  return options;
}

// The camera looks beside the volume: the film is all air.
void LookBesideTheVolume(vtkRenderer* renderer)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  double focal[3], position[3];
  camera->GetFocalPoint(focal);
  camera->GetPosition(position);
  const double shift = 20.0 * camera->GetDistance();
  camera->SetFocalPoint(focal[0] + shift, focal[1], focal[2]);
  camera->SetPosition(position[0] + shift, position[1], position[2]);
}
}

TEST(Viewer, ControlsReadOnAnyFilm)
{
  // Air is black film by default, white film inverted (key i) and in the
  // Beer-Lambert radiograph (key b): the overlay's text and the sliders must
  // stand out from either, as body text does (WCAG contrast 4.5 or more).
  mcxapp::XRayViewer viewer(BundledCT(), SmallWindowOptions(14));
  ASSERT_EQ("", viewer.Error());
  vtkRenderWindowInteractor* interactor = viewer.GetInteractor();
  interactor->Initialize();
  LookBesideTheVolume(viewer.GetRenderer());
  struct Film
  {
    const char* Keys;
    const char* Picture;
  };
  for (const Film& film : { Film{ "", "viewer-controls-black-film.png" },
         Film{ "i", "viewer-controls-inverted-film.png" },
         Film{ "ib", "viewer-controls-beer-lambert-film.png" } })
  {
    for (const char* key = film.Keys; *key; ++key)
    {
      Press(interactor, *key);
    }
    viewer.RefineUntilComplete();
    vtkSmartPointer<vtkImageData> image = Grab(viewer.GetRenderWindow());
    SavePNG(image, film.Picture);
    // The text's box, from its anchor (top left) on screen.
    double box[4];
    viewer.GetOverlay()->GetBoundingBox(viewer.GetRenderer(), box);
    const int* anchor =
      viewer.GetOverlay()->GetPositionCoordinate()->GetComputedDisplayValue(viewer.GetRenderer());
    EXPECT_GT(RegionContrast(image, anchor[0] + static_cast<int>(box[0]),
                anchor[1] + static_cast<int>(box[2]), anchor[0] + static_cast<int>(box[1]),
                anchor[1] + static_cast<int>(box[3])),
      4.5)
      << film.Picture << ": the overlay's text";
    EXPECT_GT(RegionContrast(image, Size / 4, Size / 50, Size * 95 / 100, Size / 4), 4.5)
      << film.Picture << ": the sliders";
  }
}

TEST(Viewer, SliderDragDrawsWithinTheBudgetAndTheReleaseRefines)
{
  // Each drag step edits the TF (a new cloud): the frame it draws projects
  // only what fits the drag budget (here none: the first image's
  // 2^14 - 1 points), keeping the window it had; the release renders still,
  // with the automatic window (4 points a pixel), and refinement goes on to
  // all points.
  mcxapp::XRayViewer viewer(BundledCT(), SmallWindowOptions(20));
  ASSERT_EQ("", viewer.Error());
  vtkRenderWindowInteractor* interactor = viewer.GetInteractor();
  interactor->Initialize();
  viewer.RefineUntilComplete();
  vtkMCXXRayMapper* mapper = viewer.GetMapper();
  const vtkTypeInt64 all = (1 << 20) - 1;
  ASSERT_EQ(all, mapper->GetNumberOfAccumulatedSamples());
  viewer.SetDragRenderTime(1e-9);
  mcxtest::ExecutionCounter samplerRuns(viewer.GetSampler());
  auto* centre =
    vtkSliderRepresentation2D::SafeDownCast(viewer.GetCentreSlider()->GetRepresentation());
  const double t = (centre->GetValue() - centre->GetMinimumValue()) /
    (centre->GetMaximumValue() - centre->GetMinimumValue());
  const double* p1 = centre->GetPoint1Coordinate()->GetValue();
  const double* p2 = centre->GetPoint2Coordinate()->GetValue();
  int x = static_cast<int>((p1[0] + t * (p2[0] - p1[0])) * Size);
  const int y = static_cast<int>(p1[1] * Size);
  interactor->SetEventInformation(x, y);
  interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
  interactor->InvokeEvent(vtkCommand::LeftButtonPressEvent);
  for (int step = 1; step <= 4; ++step)
  {
    x += 6;
    interactor->SetEventInformation(x, y);
    interactor->InvokeEvent(vtkCommand::MouseMoveEvent);
    EXPECT_EQ(step, samplerRuns.Count) << "each step samples the edited TF";
    EXPECT_EQ((1 << 14) - 1, mapper->GetNumberOfAccumulatedSamples()) << "step " << step;
  }
  interactor->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);
  EXPECT_EQ(0.0, mapper->GetMaximumRenderTime());
  EXPECT_TRUE(mapper->GetAutomaticWindowLevel());
  EXPECT_GE(mapper->GetNumberOfAccumulatedSamples(), (1 << 19) - 1);
  viewer.RefineUntilComplete();
  EXPECT_EQ(all, mapper->GetNumberOfAccumulatedSamples());
  double range[2];
  viewer.GetTransferFunction()->GetRange(range);
  EXPECT_NEAR(centre->GetValue(), 0.5 * (range[0] + range[1]), 1e-6 * centre->GetMaximumValue());
}

TEST(Viewer, IntegerDataGetsIntegerSliderLabels)
{
  // CT in HU (short): whole numbers; data in floats keeps four digits.
  vtkSmartPointer<vtkImageData> hounsfield = HounsfieldPhantom();
  mcxapp::XRayViewer viewer(hounsfield, SmallWindowOptions(14));
  ASSERT_EQ("", viewer.Error());
  const std::pair<vtkSliderWidget*, double> settings[] = { { viewer.GetCentreSlider(), -312.4 },
    { viewer.GetWidthSlider(), 412.6 } };
  for (const auto& setting : settings)
  {
    auto* representation =
      vtkSliderRepresentation2D::SafeDownCast(setting.first->GetRepresentation());
    representation->SetValue(setting.second);
    const std::string label =
      Formatted(representation->GetLabelFormat(), representation->GetValue());
    EXPECT_EQ(std::to_string(std::lround(setting.second)), label);
  }
  vtkNew<vtkImageData> scaled;
  scaled->DeepCopy(hounsfield);
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfValues(hounsfield->GetNumberOfPoints());
  for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
  {
    values->SetValue(i, 0.001f * hounsfield->GetPointData()->GetScalars()->GetComponent(i, 0));
  }
  scaled->GetPointData()->SetScalars(values);
  mcxapp::XRayViewer floats(scaled, SmallWindowOptions(14));
  auto* centre =
    vtkSliderRepresentation2D::SafeDownCast(floats.GetCentreSlider()->GetRepresentation());
  centre->SetValue(-0.3124);
  EXPECT_EQ("-0.3124", Formatted(centre->GetLabelFormat(), centre->GetValue()));
}

TEST(Viewer, BeerLambertShowsARadiographOfEachPreset)
{
  // Key b: the radiograph I0 exp(-line integral of mu), mu from HU (water
  // 0.02 per mm), the preset selecting the tissue (1 all, 2 bone, 3 soft
  // tissue). Through the phantom's centre: 44 mm water and 16 mm bone;
  // air sets the window (0 to 1), so grey = 255 exp(-integral).
  mcxapp::XRayViewer viewer(HounsfieldPhantom(), SmallWindowOptions(18));
  ASSERT_EQ("", viewer.Error());
  vtkRenderWindowInteractor* interactor = viewer.GetInteractor();
  interactor->Initialize();
  viewer.ShowControls(false);
  testing::internal::CaptureStderr();
  Press(interactor, 'b');
  struct Preset
  {
    char Key;
    double Integral;
  };
  for (const Preset& preset :
    { Preset{ '1', 44 * 0.02 + 16 * 0.04 }, Preset{ '2', 16 * 0.04 }, Preset{ '3', 44 * 0.02 } })
  {
    Press(interactor, preset.Key);
    viewer.RefineUntilComplete();
    vtkSmartPointer<vtkImageData> image = Grab(viewer.GetRenderWindow());
    SavePNG(image, (std::string("viewer-beer-lambert-preset-") + preset.Key + ".png").c_str());
    const double expected = 255.0 * std::exp(-preset.Integral);
    EXPECT_NEAR(expected, CentreGrey(image, 4), 0.15 * expected) << "preset " << preset.Key;
  }
  EXPECT_EQ("", testing::internal::GetCapturedStderr()) << "CT in HU: no warning";
  EXPECT_NEAR(0.02, viewer.GetTransferFunction()->GetValue(0), 1e-9) << "soft tissue: mu";
  EXPECT_DOUBLE_EQ(0.0, viewer.GetTransferFunction()->GetValue(1000)) << "bone: left out";
  Press(interactor, 'b'); // back to the weight
  EXPECT_DOUBLE_EQ(1.0, viewer.GetTransferFunction()->GetValue(0));
  EXPECT_FALSE(viewer.GetMapper()->GetBeerLambert());
}

TEST(Viewer, BeerLambertOnDataNotInHounsfieldUnitsWarnsOnce)
{
  // The bundled head's values start at 0, not at air's -1000 HU: mu takes
  // its lowest value for air, and says so once, in one line.
  mcxapp::XRayViewer viewer(BundledCT(), SmallWindowOptions(14));
  ASSERT_EQ("", viewer.Error());
  vtkRenderWindowInteractor* interactor = viewer.GetInteractor();
  interactor->Initialize();
  testing::internal::CaptureStderr();
  Press(interactor, 'b');
  Press(interactor, '2');
  Press(interactor, 'b');
  Press(interactor, 'b');
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_EQ(1, std::count(warnings.begin(), warnings.end(), '\n')) << warnings;
  EXPECT_EQ(0u, warnings.find("mcxray: warning: ")) << warnings;
  EXPECT_NE(std::string::npos, warnings.find("hold no air (none at or below -500)")) << warnings;
  EXPECT_NEAR(0.02, viewer.GetTransferFunction()->GetValue(1000), 1e-9) << "1000 above air: water";
}

TEST(Viewer, PolychromaticSessionMapsTheSameChannelsOnASpectrumChange)
{
  // mcxray view --spectrum: the phantom's channels drawn once; the image is
  // -ln T, harder at 120 kVp than at 60 kVp without drawing again; the TF
  // controls are off and b shows the intensity.
  mcxapp::XRayViewer viewer(HounsfieldPhantom(), SmallWindowOptions(18));
  ASSERT_EQ("", viewer.Error());
  vtkRenderWindowInteractor* interactor = viewer.GetInteractor();
  interactor->Initialize();
  viewer.SetPolychromatic("60kVp,2.5mmAl", "default", "integrating");
  EXPECT_TRUE(viewer.IsPolychromatic());
  EXPECT_FALSE(viewer.GetCentreSlider()->GetEnabled());
  EXPECT_FALSE(viewer.GetWidthSlider()->GetEnabled());
  vtkMCXXRayMapper* mapper = viewer.GetMapper();
  viewer.RefineUntilComplete();
  ASSERT_TRUE(mapper->IsRefinementComplete());
  EXPECT_EQ(mapper->GetNumberOfChannels(), 4);
  const std::string overlay = viewer.OverlayText();
  EXPECT_NE(overlay.find("spectrum 60kVp,2.5mmAl, materials default"), std::string::npos)
    << overlay;
  EXPECT_NE(overlay.find("(-ln T)"), std::string::npos) << overlay;
  const auto centre = [mapper]()
  {
    vtkNew<vtkImageData> image;
    mapper->GetLineIntegralImage(image);
    return image->GetPointData()->GetScalars()->GetTuple1(Size / 2 + Size * (Size / 2));
  };
  const double at60 = centre();
  EXPECT_GT(at60, 1.0); // 44 mm of water and 16 mm of bone
  const vtkTypeInt64 restarts = mapper->GetNumberOfRestarts();
  const vtkTypeInt64 count = mapper->GetNumberOfAccumulatedSamples();

  Press(interactor, '2'); // no TF to choose: nothing is drawn again
  viewer.RefineUntilComplete();
  EXPECT_EQ(mapper->GetNumberOfRestarts(), restarts);

  viewer.SetPolychromatic("120kVp,2.5mmAl", "default", "integrating");
  viewer.RefineUntilComplete();
  EXPECT_EQ(mapper->GetNumberOfRestarts(), restarts);
  EXPECT_EQ(mapper->GetNumberOfAccumulatedSamples(), count);
  const double at120 = centre();
  EXPECT_LT(at120, 0.9 * at60);
  EXPECT_GT(at120, 0.0);

  Press(interactor, 'b');
  viewer.RefineUntilComplete();
  EXPECT_TRUE(mapper->GetBeerLambert());
  EXPECT_EQ(mapper->GetNumberOfRestarts(), restarts);
  EXPECT_NE(viewer.OverlayText().find("(intensity I)"), std::string::npos);
}
