// A scripted session with the viewer behind `mcxray view`: mouse and key
// events in, frames out, TF edits applied through the keys and the sliders,
// progressive refinement driven by the timer.
#include "mcxXRayViewer.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXXRayMapper.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSliderRepresentation2D.h"
#include "vtkSliderWidget.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLImageDataReader.h"

#include "mcxTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

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
  // in the moved view before the edit).
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
