// The camera-to-detector geometry against VTK's own: the projectors and the
// mapper share one piece of code (mcx::GeometryFromCamera), so comparing
// them with one another cannot catch an error in it. Here world points are
// projected with vtkCamera's composite projection matrix, for parallel and
// perspective cameras and square and non-square images, and the pixels our
// code gives must agree.
#include "mcxTestHelpers.h"
#include "vtkMCXCameraGeometry.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"
#include "vtkMCXRadiographGeometry.h"
#include "vtkMCXReferenceProjector.h"

#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace
{
struct View
{
  std::string Name;
  vtkSmartPointer<vtkCamera> Camera;
  int Width;
  int Height;
};

vtkSmartPointer<vtkCamera> NewCamera(bool parallel, bool horizontalAngle)
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetFocalPoint(3, -2, 5);
  camera->SetPosition(43, 28, 25);
  camera->SetViewUp(0.2, 0, 1);
  camera->SetViewAngle(40);
  camera->SetParallelScale(17);
  camera->SetParallelProjection(parallel);
  camera->SetUseHorizontalViewAngle(horizontalAngle);
  camera->SetClippingRange(1, 500);
  return camera;
}

std::vector<View> Views()
{
  std::vector<View> views;
  const int sizes[][2] = { { 64, 64 }, { 200, 160 }, { 160, 200 }, { 37, 91 } };
  for (bool parallel : { true, false })
  {
    for (bool horizontal : { false, true })
    {
      for (const auto& size : sizes)
      {
        views.push_back({ std::string(parallel ? "parallel " : "perspective ") +
            (horizontal ? "horizontal angle " : "") + std::to_string(size[0]) + "x" +
            std::to_string(size[1]),
          NewCamera(parallel, horizontal), size[0], size[1] });
      }
    }
    // An off-axis screen and a tracked eye beside it, as a CAVE sets them.
    if (!parallel)
    {
      auto offAxis = NewCamera(false, false);
      offAxis->SetUseOffAxisProjection(true);
      // A screen 30 x 24 across the plane y = -15, the eye off its centre
      // in front of it, the focal point's region behind it.
      const double bottomLeft[3] = { -12, -15, -7 }, bottomRight[3] = { 18, -15, -7 },
                   topRight[3] = { 18, -15, 17 };
      offAxis->SetScreenBottomLeft(bottomLeft);
      offAxis->SetScreenBottomRight(bottomRight);
      offAxis->SetScreenTopRight(topRight);
      double eye[3] = { 7, -60, 8 };
      offAxis->SetEyePosition(eye);
      views.push_back({ "perspective off-axis 200x160", offAxis, 200, 160 });
      auto sheared = NewCamera(false, false);
      sheared->SetViewShear(0.3, -0.2, 1.0);
      views.push_back({ "perspective view shear 200x160", sheared, 200, 160 });
    }
    else
    {
      // Oblique rays: a sheared box, alone and tiled.
      auto sheared = NewCamera(true, false);
      sheared->SetViewShear(0.3, -0.2, 1.0);
      views.push_back({ "parallel view shear 200x160", sheared, 200, 160 });
      auto shearedTile = NewCamera(true, false);
      shearedTile->SetViewShear(-0.7, 0.4, 0.5);
      shearedTile->SetWindowCenter(-0.5, 0.25);
      views.push_back({ "parallel view shear window centre 160x200", shearedTile, 160, 200 });
    }
    // A window centre, as tiled rendering (large screenshots) sets it.
    auto shifted = NewCamera(parallel, false);
    shifted->SetWindowCenter(0.3, -0.45);
    views.push_back({ std::string(parallel ? "parallel " : "perspective ") + "window centre 200x160",
      shifted, 200, 160 });
  }
  return views;
}

// Points spread over the view's field around the focal point.
std::vector<std::array<double, 3>> WorldPoints(const View& view)
{
  std::vector<std::array<double, 3>> points;
  vtkCamera* camera = view.Camera;
  if (camera->GetUseOffAxisProjection())
  {
    // Off-axis frusta are hard to aim by hand: points inside this one, found
    // by inverting VTK's own matrix at irregular normalized coordinates.
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(camera->GetCompositeProjectionTransformMatrix(
                           static_cast<double>(view.Width) / view.Height, -1, 1),
      inverse);
    for (int k = 0; k < 40; ++k)
    {
      const double ndc[4] = { 0.9 * std::sin(1.7 * k + 0.3), 0.9 * std::cos(2.3 * k + 1.1),
        0.9 * std::sin(0.9 * k), 1.0 };
      double x[4];
      inverse->MultiplyPoint(ndc, x);
      points.push_back({ x[0] / x[3], x[1] / x[3], x[2] / x[3] });
    }
    return points;
  }
  const double* focal = camera->GetFocalPoint();
  for (int k = 0; k < 40; ++k)
  {
    // Deterministic, irregular offsets within about 14 of the focal point.
    const double a = std::sin(1.7 * k + 0.3), b = std::cos(2.3 * k + 1.1), c = std::sin(0.9 * k);
    points.push_back({ focal[0] + 14 * a, focal[1] + 14 * b, focal[2] + 14 * c });
  }
  return points;
}

// Our continuous pixel coordinates (pixel i centred at i) of a world point.
bool PixelCoordinates(const mcx::ProjectionGeometry& g, const double x[3], double pixel[2])
{
  double ab[2];
  if (!mcx::ProjectToPlane(g, x, ab[0], ab[1]))
  {
    return false;
  }
  for (int k = 0; k < 2; ++k)
  {
    pixel[k] = (ab[k] - g.Origin[k]) / g.Spacing[k];
  }
  return true;
}
// A uniform box of 6 x 5 x 4 voxels of spacing (2, 3, 2.5) from (1, -4, 2),
// indexed: with the box kernel its support is x in [0, 12], y in
// [-5.5, 9.5], z in [0.75, 10.75].
vtkSmartPointer<vtkMCXDensityIndex> UniformBoxIndex()
{
  const int dims[3] = { 6, 5, 4 };
  const double spacing[3] = { 2, 3, 2.5 };
  const double origin[3] = { 1, -4, 2 };
  auto volume = mcxtest::MakeVolume(
    VTK_UNSIGNED_CHAR, dims, [](int, int, int) { return 1.0; }, spacing, origin);
  auto index = vtkSmartPointer<vtkMCXDensityIndex>::New();
  index->SetInputData(volume);
  return index;
}

// A parallel camera looking down the box's z axis, off its centre.
vtkSmartPointer<vtkCamera> CameraAboveTheBox()
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetFocalPoint(6.17, 1.31, 0);
  camera->SetPosition(6.17, 1.31, 100);
  camera->SetViewUp(0, 1, 0);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(13.3);
  return camera;
}

// The exact reference of an index with the box kernel, for a camera.
vtkSmartPointer<vtkMCXReferenceProjector> BoxKernelReference(
  vtkMCXDensityIndex* index, vtkCamera* camera, int width, int height)
{
  auto reference = vtkSmartPointer<vtkMCXReferenceProjector>::New();
  reference->SetInputConnection(index->GetOutputPort());
  reference->SetKernel(vtkMCXTypes::BOX);
  reference->SetCamera(camera);
  reference->SetImageSize(width, height);
  reference->Update();
  return reference;
}

// A cloud of the points, each one sample of weight 1.
vtkSmartPointer<vtkPolyData> UnitWeightCloud(vtkPoints* points)
{
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  vtkNew<vtkDoubleArray> weight;
  weight->SetName(vtkMCXTypes::SampleWeightName());
  weight->InsertNextValue(1.0);
  cloud->GetFieldData()->AddArray(weight);
  return cloud;
}

// The projector's image of the cloud for the view's camera and size.
vtkSmartPointer<vtkImageData> Project(vtkPolyData* cloud, const View& view, bool onDetectorPlane)
{
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputData(cloud);
  projector->SetCamera(view.Camera);
  projector->SetImageSize(view.Width, view.Height);
  projector->SetPlaceOnDetectorPlane(onDetectorPlane);
  projector->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(projector->GetOutput());
  return image;
}
}

TEST(CameraGeometry, PixelsOfWorldPointsAreVTKs)
{
  for (const View& view : Views())
  {
    mcx::ProjectionGeometry g;
    const int size[2] = { view.Width, view.Height };
    ASSERT_EQ("", mcx::GeometryFromCamera(view.Camera, size, 0.0, 0.0, g)) << view.Name;
    EXPECT_EQ(view.Width, g.Size[0]);
    EXPECT_EQ(view.Height, g.Size[1]);
    for (const auto& x : WorldPoints(view))
    {
      double ours[2], vtk[2];
      ASSERT_TRUE(PixelCoordinates(g, x.data(), ours)) << view.Name;
      ASSERT_TRUE(mcxtest::DisplayCoordinates(view.Camera, view.Width, view.Height, x.data(), vtk));
      // VTK's pixel i covers [i, i + 1); ours is centred at i.
      EXPECT_NEAR(vtk[0] - 0.5, ours[0], 1e-9 * view.Width) << view.Name;
      EXPECT_NEAR(vtk[1] - 0.5, ours[1], 1e-9 * view.Height) << view.Name;
    }
  }
}

TEST(CameraGeometry, CamerasThatDescribeNoViewAreNamed)
{
  // A NaN anywhere is named as such (it said the points coincide).
  const double nan = std::nan("");
  const int size[2] = { 8, 8 };
  struct Case
  {
    double Position[3];
    double Focal[3];
    double Up[3];
    const char* Expected;
  };
  const Case cases[] = {
    { { nan, 0, 10 }, { 0, 0, 0 }, { 0, 1, 0 },
      "the camera's position, focal point and view-up must be finite" },
    { { 0, 0, 10 }, { 0, 0, 0 }, { 0, nan, 0 },
      "the camera's position, focal point and view-up must be finite" },
    { { 0, 0, 10 }, { 0, 0, 10 }, { 0, 1, 0 }, "the camera's position and focal point coincide" },
  };
  for (const Case& c : cases)
  {
    vtkNew<vtkCamera> camera;
    camera->SetPosition(c.Position[0], c.Position[1], c.Position[2]);
    camera->SetFocalPoint(c.Focal[0], c.Focal[1], c.Focal[2]);
    camera->SetViewUp(c.Up[0], c.Up[1], c.Up[2]);
    mcx::ProjectionGeometry g;
    EXPECT_EQ(c.Expected, mcx::GeometryFromCamera(camera, size, 0.0, 0.0, g));
  }
}

TEST(CameraGeometry, ProjectorPutsEachPointInVTKsPixel)
{
  // A cloud of single points, each far from a pixel border in VTK's
  // projection: the projector's image must light exactly those pixels, with
  // the weight of one sample over the pixel area (times the perspective
  // factor D^2 s / z^3).
  for (const View& view : Views())
  {
    vtkNew<vtkPoints> points;
    std::vector<std::array<double, 2>> pixels;
    for (const auto& x : WorldPoints(view))
    {
      double d[2];
      ASSERT_TRUE(mcxtest::DisplayCoordinates(view.Camera, view.Width, view.Height, x.data(), d));
      const bool inside = d[0] >= 0 && d[0] < view.Width && d[1] >= 0 && d[1] < view.Height;
      const bool clear =
        std::fabs(d[0] - std::round(d[0])) > 1e-3 && std::fabs(d[1] - std::round(d[1])) > 1e-3;
      if (inside && clear)
      {
        points->InsertNextPoint(x.data());
        pixels.push_back({ std::floor(d[0]), std::floor(d[1]) });
      }
    }
    ASSERT_GT(pixels.size(), 10u) << view.Name;
    auto projected = Project(UnitWeightCloud(points), view, false);
    vtkImageData* image = projected;
    ASSERT_EQ(view.Width, image->GetDimensions()[0]) << view.Name;
    ASSERT_EQ(view.Height, image->GetDimensions()[1]) << view.Name;
    std::vector<double> expected(static_cast<std::size_t>(view.Width) * view.Height, 0.0);
    const double area = image->GetSpacing()[0] * image->GetSpacing()[1];
    for (std::size_t i = 0; i < pixels.size(); ++i)
    {
      const std::size_t p = static_cast<std::size_t>(pixels[i][0] + view.Width * pixels[i][1]);
      expected[p] += mcxtest::PerspectiveWeight(view.Camera, points->GetPoint(i)) / area;
    }
    vtkDataArray* values = mcxtest::LineIntegral(image);
    for (std::size_t p = 0; p < expected.size(); ++p)
    {
      ASSERT_NEAR(expected[p], values->GetTuple1(p), 1e-6 * expected[p] + 1e-300)
        << view.Name << " pixel (" << p % view.Width << ", " << p / view.Width << ")";
    }
  }
}

TEST(CameraGeometry, ImagePlacedOnTheDetectorPlaneFacesItsView)
{
  // PlaceOnDetectorPlane: the world position of each pixel centre (origin,
  // spacing and direction matrix of the output) is where VTK's projection of
  // this camera puts that pixel, on the focal plane; the values are those of
  // the image in detector coordinates.
  for (const View& view : Views())
  {
    vtkNew<vtkPoints> points;
    for (const auto& x : WorldPoints(view))
    {
      points->InsertNextPoint(x.data());
    }
    auto cloud = UnitWeightCloud(points);
    auto flat = Project(cloud, view, false);
    auto placed = Project(cloud, view, true);
    vtkImageData* image = placed;
    EXPECT_NEAR(1.0, image->GetDirectionMatrix()->Determinant(), 1e-12)
      << view.Name << ": the placement is a rotation";
    const double* focal = view.Camera->GetFocalPoint();
    const double* normal = view.Camera->GetDirectionOfProjection();
    for (const int i : { 0, view.Width / 3, view.Width - 1 })
    {
      for (const int j : { 0, view.Height / 2, view.Height - 1 })
      {
        double x[3], d[2];
        image->TransformContinuousIndexToPhysicalPoint(i, j, 0, x);
        ASSERT_TRUE(mcxtest::DisplayCoordinates(view.Camera, view.Width, view.Height, x, d));
        EXPECT_NEAR(i + 0.5, d[0], 1e-6 * view.Width) << view.Name;
        EXPECT_NEAR(j + 0.5, d[1], 1e-6 * view.Height) << view.Name;
        if (!view.Camera->GetUseOffAxisProjection()) // else: a plane facing the screen's normal
        {
          const double off[3] = { x[0] - focal[0], x[1] - focal[1], x[2] - focal[2] };
          EXPECT_NEAR(0.0, vtkMath::Dot(off, normal), 1e-9 * view.Camera->GetDistance())
            << view.Name;
        }
      }
    }
    vtkDataArray* a = mcxtest::LineIntegral(flat);
    vtkDataArray* b = mcxtest::LineIntegral(image);
    ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples());
    for (vtkIdType p = 0; p < a->GetNumberOfTuples(); ++p)
    {
      ASSERT_EQ(a->GetTuple1(p), b->GetTuple1(p)) << view.Name;
    }
  }
}

TEST(CameraGeometry, ReferenceFramesABoxAsVTKProjectsIt)
{
  // A uniform box seen along its z axis by a parallel camera of a
  // non-square window: each pixel is the box's depth times the fraction of
  // the pixel's S x S rays (at the centres of its subdivision) inside the
  // box's outline, whose edges lie where VTK's projection puts them.
  auto index = UniformBoxIndex();
  auto camera = CameraAboveTheBox();
  const int width = 50, height = 40;
  auto reference = BoxKernelReference(index, camera, width, height);
  // The box kernel fills voxel centres +- half a spacing: x in [0, 12],
  // y in [-5.5, 9.5], depth 4 * 2.5 = 10.
  const double low[3] = { 0, -5.5, 2 }, high[3] = { 12, 9.5, 2 };
  double a[2], b[2];
  ASSERT_TRUE(mcxtest::DisplayCoordinates(camera, width, height, low, a));
  ASSERT_TRUE(mcxtest::DisplayCoordinates(camera, width, height, high, b));
  // The camera looks along -z with y up, so x runs to the right.
  vtkDataArray* values = mcxtest::LineIntegral(reference->GetOutput());
  const int rays =
    static_cast<int>(mcxtest::FieldValue(reference->GetOutput(), "RaysPerPixelAxis"));
  ASSERT_GE(rays, 3);
  auto covered = [rays](double lo, double hi, int pixel)
  {
    int inside = 0;
    for (int s = 0; s < rays; ++s)
    {
      const double x = pixel + (s + 0.5) / rays;
      EXPECT_GT(std::min(std::fabs(x - lo), std::fabs(x - hi)), 1e-6) << "a ray on an edge";
      inside += x > lo && x < hi ? 1 : 0;
    }
    return static_cast<double>(inside) / rays;
  };
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const double expected = 10.0 * covered(a[0], b[0], i) * covered(a[1], b[1], j);
      ASSERT_NEAR(expected, values->GetTuple1(i + width * j), 1e-9) << "pixel " << i << ", " << j;
    }
  }
}

TEST(CameraGeometry, ObliqueRaysCrossABoxAlongTheirLength)
{
  // A sheared parallel camera sends its rays obliquely through a uniform box
  // seen along its z axis. Where a pixel's whole beam enters by the top face
  // and leaves by the bottom one (inside both faces' outlines as VTK projects
  // them), every ray's chord is the box's depth, 10, over the cosine of the
  // rays' angle: the exact reference gives that, and the Monte Carlo
  // projector's footprint deposit agrees within its sampling error. Mass is
  // conserved: the values times the beams' cross-sections sum to the box's
  // mass exactly.
  auto index = UniformBoxIndex();
  auto camera = CameraAboveTheBox();
  camera->SetViewShear(0.5, -0.4, 1.0);
  const int width = 50, height = 40;
  const double top = 10.75, bottom = 0.75; // the box kernel's reach in z
  const double origin3[3] = { 0, 0, 0 };
  const double chord = (top - bottom) * mcxtest::PerspectiveWeight(camera, origin3);
  ASSERT_GT(chord, 1.1 * (top - bottom)) << "the rays are oblique";
  double faces[2][2][2]; // [top, bottom][low corner, high corner][display axis]
  for (int f = 0; f < 2; ++f)
  {
    const double z = f == 0 ? top : bottom;
    const double low[3] = { 0, -5.5, z }, high[3] = { 12, 9.5, z };
    ASSERT_TRUE(mcxtest::DisplayCoordinates(camera, width, height, low, faces[f][0]));
    ASSERT_TRUE(mcxtest::DisplayCoordinates(camera, width, height, high, faces[f][1]));
  }
  auto insideBoth = [&](int i, int j)
  {
    for (int f = 0; f < 2; ++f)
    {
      if (!(i >= faces[f][0][0] && i + 1 <= faces[f][1][0] && j >= faces[f][0][1] &&
            j + 1 <= faces[f][1][1]))
      {
        return false;
      }
    }
    return true;
  };

  auto reference = BoxKernelReference(index, camera, width, height);
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(0, 1);
  tf->AddPoint(255, 1);
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(index->GetOutputPort());
  projector->SetTransferFunction(tf);
  projector->SetKernel(vtkMCXTypes::BOX);
  projector->SetDepositToFootprint();
  projector->SetSampleExponent(20);
  projector->SetCamera(camera);
  projector->SetImageSize(width, height);
  projector->Update();
  vtkImageData* exact = reference->GetOutput();
  vtkImageData* sampled = projector->GetOutput();
  vtkDataArray* exactValues = mcxtest::LineIntegral(exact);
  vtkDataArray* sampledValues = mcxtest::LineIntegral(sampled);
  int interior = 0;
  double sum = 0.0;
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const vtkIdType p = i + width * j;
      sum += sampledValues->GetTuple1(p);
      if (insideBoth(i, j))
      {
        ++interior;
        ASSERT_NEAR(chord, exactValues->GetTuple1(p), 1e-9 * chord) << "pixel " << i << ", " << j;
        // 2^20 samples over 120 voxels: a deposit is 1 / 8738 of a voxel's
        // mass, the rounding of a voxel's share at most one deposit.
        ASSERT_NEAR(chord, sampledValues->GetTuple1(p), 2e-3 * chord)
          << "pixel " << i << ", " << j;
      }
    }
  }
  EXPECT_GT(interior, 100);
  const double* s = sampled->GetSpacing();
  const double mass = 12.0 * 15.0 * 10.0;
  EXPECT_NEAR(mass, sum * s[0] * s[1] * (top - bottom) / chord, 1e-9 * mass);
}

TEST(CameraGeometry, ProjectorsWriteTheMatrixTheyWereGivenBesideTheirFields)
{
  // Both projectors, given a 3x4 matrix, write it (at some scale) as
  // ProjectionMatrix next to their own fields, and a new matrix replaces it.
  auto index = UniformBoxIndex();
  vtkNew<vtkMCXRadiographGeometry> radiograph;
  radiograph->SetIsocenter(6, 2, 5);
  radiograph->SetDetectorPixels(16, 12);
  radiograph->SetPixelPitch(4.0);
  vtkNew<vtkMCXProjector> monteCarlo;
  monteCarlo->SetNumberOfSamples(1023);
  vtkNew<vtkMCXReferenceProjector> reference;
  for (vtkMCXProjectorBase* projector :
    { static_cast<vtkMCXProjectorBase*>(monteCarlo), static_cast<vtkMCXProjectorBase*>(reference) })
  {
    projector->SetInputConnection(index->GetOutputPort());
    projector->UseProjectionMatrixOn();
    projector->SetImageSize(16, 12);
    for (double gantry : { 0.0, 70.0 })
    {
      radiograph->SetGantryAngle(gantry);
      double given[12];
      ASSERT_TRUE(radiograph->GetProjectionMatrix(given));
      projector->SetProjectionMatrix(given);
      projector->Update();
      vtkFieldData* fd = projector->GetOutput()->GetFieldData();
      vtkDataArray* written = fd->GetArray("ProjectionMatrix");
      ASSERT_NE(nullptr, written) << projector->GetClassName() << " at gantry " << gantry;
      // One tuple of 12: the matrix, row-major.
      ASSERT_EQ(1, written->GetNumberOfTuples());
      ASSERT_EQ(12, written->GetNumberOfComponents());
      const double scale = written->GetComponent(0, 11) / given[11];
      for (int i = 0; i < 12; ++i)
      {
        EXPECT_NEAR(
          given[i] * scale, written->GetComponent(0, i), 1e-9 * std::fabs(given[11] * scale))
          << projector->GetClassName() << " entry " << i << " at gantry " << gantry;
      }
      EXPECT_NE(nullptr, fd->GetArray("EstimatedRelativeError")) << projector->GetClassName();
    }
  }
  EXPECT_EQ(1023, mcxtest::FieldValue(monteCarlo->GetOutput(), "SampleCount"));
  EXPECT_GE(mcxtest::FieldValue(reference->GetOutput(), "RaysPerPixelAxis"), 1);
}

TEST(CameraGeometry, TurnDegreesIsTheRotationOfTheAxesNotAPanOrAZoom)
{
  // Axes turned by a known angle about V: that angle, both ways round.
  for (double degrees : { 0.0, 1e-3, 10.0, 90.0, 179.0 })
  {
    const double t = vtkMath::RadiansFromDegrees(degrees);
    mcx::ProjectionGeometry a, b;
    const double u[3] = { std::cos(t), 0, -std::sin(t) }, w[3] = { std::sin(t), 0, std::cos(t) };
    std::copy(u, u + 3, b.U);
    std::copy(w, w + 3, b.W);
    EXPECT_NEAR(degrees, mcx::TurnDegrees(a, b), 1e-6);
    EXPECT_NEAR(degrees, mcx::TurnDegrees(b, a), 1e-6);
  }
  // A camera's azimuth, elevation and roll turn it; a pan, a zoom and
  // another image size do not.
  const int size[2] = { 40, 30 };
  auto geometryOf = [&](vtkCamera* camera, const int* pixels)
  {
    mcx::ProjectionGeometry g;
    EXPECT_EQ("", mcx::GeometryFromCamera(camera, pixels, 0.0, 0.0, g));
    return g;
  };
  vtkNew<vtkCamera> start;
  start->SetPosition(10, -300, 20);
  start->SetFocalPoint(10, 0, 20);
  start->SetViewUp(0, 0, 1);
  const mcx::ProjectionGeometry first = geometryOf(start, size);
  auto moved = [&](const std::function<void(vtkCamera*)>& move, const int* pixels)
  {
    vtkNew<vtkCamera> camera;
    camera->DeepCopy(start);
    move(camera);
    return mcx::TurnDegrees(first, geometryOf(camera, pixels));
  };
  EXPECT_NEAR(10.0, moved([](vtkCamera* c) { c->Azimuth(10); }, size), 1e-9);
  EXPECT_NEAR(25.0, moved([](vtkCamera* c) { c->Roll(25); }, size), 1e-9);
  EXPECT_NEAR(35.0,
    moved(
      [](vtkCamera* c)
      {
        c->Elevation(35);
        c->OrthogonalizeViewUp();
      },
      size),
    1e-9);
  EXPECT_NEAR(180.0, moved([](vtkCamera* c) { c->Azimuth(180); }, size), 1e-6);
  const int larger[2] = { 64, 64 };
  EXPECT_NEAR(0.0,
    moved(
      [](vtkCamera* c)
      {
        c->Zoom(2.5);
        c->SetPosition(40, -250, 0); // a pan and a dolly: the same direction
        c->SetFocalPoint(40, 50, 0);
      },
      larger),
    1e-6);
}

TEST(CameraGeometry, SameFramingHoldsForTurnsAboutThePointAndNotForPansZoomsOrResizes)
{
  // A perspective camera looking at the point, turned about it: the same
  // framing; zoomed, dollied, panned, resized or made parallel: another.
  // Tolerance 5 %: a zoom of 1.02 keeps it, one of 1.1 does not.
  const double centre[3] = { 10, 0, 20 };
  const int size[2] = { 40, 30 };
  vtkNew<vtkCamera> start;
  start->SetPosition(10, -300, 20);
  start->SetFocalPoint(centre);
  start->SetViewUp(0, 0, 1);
  auto geometryOf = [](vtkCamera* camera, const int* pixels)
  {
    mcx::ProjectionGeometry g;
    EXPECT_EQ("", mcx::GeometryFromCamera(camera, pixels, 0.0, 0.0, g));
    return g;
  };
  for (bool parallel : { false, true })
  {
    start->SetParallelProjection(parallel);
    const mcx::ProjectionGeometry first = geometryOf(start, size);
    auto framed = [&](const std::function<void(vtkCamera*)>& move, const int* pixels)
    {
      vtkNew<vtkCamera> camera;
      camera->DeepCopy(start);
      move(camera);
      return mcx::SameFraming(first, geometryOf(camera, pixels), centre, 0.05);
    };
    EXPECT_TRUE(framed([](vtkCamera*) {}, size));
    EXPECT_TRUE(framed([](vtkCamera* c) { c->Azimuth(40); }, size)) << parallel;
    EXPECT_TRUE(framed([](vtkCamera* c) { c->Roll(30); }, size)) << parallel;
    EXPECT_TRUE(framed([](vtkCamera* c) { c->Zoom(1.02); }, size)) << parallel;
    EXPECT_FALSE(framed([](vtkCamera* c) { c->Zoom(1.1); }, size)) << parallel;
    EXPECT_FALSE(framed(
      [](vtkCamera* c)
      {
        c->SetPosition(30, -300, 20); // a pan of 20 mm, a third of the image
        c->SetFocalPoint(30, 0, 20);
      },
      size))
      << parallel;
    const int larger[2] = { 48, 30 };
    EXPECT_FALSE(framed([](vtkCamera*) {}, larger)) << parallel;
    EXPECT_FALSE(
      framed([](vtkCamera* c) { c->SetParallelProjection(!c->GetParallelProjection()); }, size))
      << parallel;
  }
  start->SetParallelProjection(false);
  EXPECT_FALSE(mcx::SameFraming(geometryOf(start, size), geometryOf(start, size),
    std::array<double, 3>{ 10, -400, 20 }.data(), 0.05))
    << "a point behind the eye";
  vtkNew<vtkCamera> dollied;
  dollied->DeepCopy(start);
  dollied->Dolly(1.5); // nearer: larger in the perspective image
  EXPECT_FALSE(mcx::SameFraming(geometryOf(start, size), geometryOf(dollied, size), centre, 0.05));
}

TEST(CameraGeometry, TurnDegreesOfAMirroredImageIs180)
{
  mcx::ProjectionGeometry a, b;
  const double t = vtkMath::RadiansFromDegrees(10.0);
  const double u[3] = { -std::cos(t), 0, std::sin(t) }, w[3] = { std::sin(t), 0, std::cos(t) };
  std::copy(u, u + 3, b.U); // U flipped: the image mirrored
  std::copy(w, w + 3, b.W);
  EXPECT_EQ(180.0, mcx::TurnDegrees(a, b));
  EXPECT_EQ(180.0, mcx::TurnDegrees(b, a));
}
