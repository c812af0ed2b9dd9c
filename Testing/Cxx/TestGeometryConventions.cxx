// RTK's circular geometry (Core/mcxRTKView.h) and IEC 61217 beams
// (Core/mcxIECBeamView.h), without a pipeline: RTK's matrices against the
// ones its documentation prints, the cameras they make, the cardinal
// gantry, couch and collimator angles.
#include "mcxIECBeamView.h"
#include "mcxProjectionMatrix.h"
#include "mcxRTKView.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
// Where a camera puts a world point: (u, v) in pixels.
void Project(const mcx::PinholeCamera& camera, const double x[3], double& u, double& v)
{
  double P[12];
  mcx::MatrixFromPinhole(camera, P);
  ASSERT_TRUE(mcx::ProjectPoint(P, x, u, v));
}
}

// RTK's documentation (documentation/docs/Geometry.md, "XML File") prints
// two projections with the matrices RTK wrote for them.
TEST(RTKView, GivesTheMatricesRTKWrites)
{
  struct Case
  {
    double Gantry, OffsetX, OffsetY;
    double Matrix[12];
  };
  const Case cases[2] = {
    { 271.847274780273, -117.056503295898, -1.01195001602173,
      { -166.5093078829, 0, -1531.42837748039, -117056.503295898, -1.01142410874151, -1536,
        0.0326206557691505, -1011.95001602173, -0.999480303105996, 0, 0.0322354417240802, -1000 } },
    { 271.852905273438, -117.056831359863, -1.01187002658844,
      { -166.660129424325, 0, -1531.41199650136, -117056.831359863, -1.01134095059569, -1536,
        0.0327174625589984, -1011.87002658844, -0.999477130482326, 0, 0.0323336611415466, -1000 } },
  };
  for (const Case& c : cases)
  {
    mcx::RTKProjection p;
    p.SourceToIsocenterDistance = 1000;
    p.SourceToDetectorDistance = 1536;
    p.GantryAngle = c.Gantry;
    p.ProjectionOffsetX = c.OffsetX;
    p.ProjectionOffsetY = c.OffsetY;
    double M[12];
    mcx::RTKMatrix(p, M);
    double largest = 0, deviation = 0;
    for (int k = 0; k < 12; ++k)
    {
      largest = std::max(largest, std::abs(c.Matrix[k]));
      deviation = std::max(deviation, std::abs(M[k] - c.Matrix[k]));
    }
    EXPECT_LT(deviation / largest, 1e-9) << "gantry " << c.Gantry;
  }
}

// On a pixel grid the matrix is a camera: focal lengths SDD / spacing, the
// source where RTK puts it (at (sx, sy, sid) of the rotated system), and a
// point straight below the source (rotated (sx, sy, z)) on RTK's detector
// point (sx - px, sy - py), in the pixel that the origin and spacing give.
TEST(RTKView, MakesACameraOnThePixelGrid)
{
  mcx::RTKProjection p;
  p.SourceToIsocenterDistance = 800;
  p.SourceToDetectorDistance = 1200;
  p.GantryAngle = 90; // the source on +x of the fixed system (RTK: Ry(-90) takes +x to +z)
  p.SourceOffsetX = 10;
  p.ProjectionOffsetY = 5;
  const int pixels[2] = { 100, 80 };
  const double origin[2] = { -50, -40 }, spacing[2] = { 1.0, 0.5 };
  double P[12];
  ASSERT_EQ("", mcx::RTKPixelMatrix(p, pixels, origin, spacing, P));
  mcx::PinholeCamera camera;
  ASSERT_EQ("", mcx::PinholeFromMatrix(P, camera));
  EXPECT_NEAR(1200.0, camera.Fx, 1e-9);
  EXPECT_NEAR(2400.0, camera.Fy, 1e-9);
  double source[3];
  camera.Source(source);
  // Rotated (sx, sy, sid) = (10, 0, 800) back by gantry 90: x' = z, z' = -x.
  EXPECT_NEAR(800.0, source[0], 1e-9);
  EXPECT_NEAR(0.0, source[1], 1e-9);
  EXPECT_NEAR(-10.0, source[2], 1e-9);
  // Rotated (10, 0, 0) is world (0, 0, -10); detector (10, -5) mm is column
  // (10 + 50) / 1 and row (-5 + 40) / 0.5 = 70, 9 from the top.
  const double foot[3] = { 0, 0, -10 };
  double u, v;
  ASSERT_TRUE(mcx::ProjectPoint(P, foot, u, v));
  EXPECT_NEAR(60.0, u, 1e-9);
  EXPECT_NEAR(9.0, v, 1e-9);
}

TEST(RTKView, RefusesWhatItDoesNotRender)
{
  const int pixels[2] = { 10, 10 };
  const double origin[2] = { 0, 0 }, spacing[2] = { 1, 1 };
  double P[12];
  mcx::RTKProjection parallel;
  parallel.SourceToIsocenterDistance = 1000;
  EXPECT_NE(
    std::string::npos, mcx::RTKPixelMatrix(parallel, pixels, origin, spacing, P).find("parallel"));
  mcx::RTKProjection bad = parallel;
  bad.SourceToDetectorDistance = 1500;
  bad.InPlaneAngle = std::nan("");
  EXPECT_NE("", mcx::RTKPixelMatrix(bad, pixels, origin, spacing, P));
}

// IEC 61217, head first supine: where the source stands and which way the
// image's columns and rows run, for the cardinal angles (directions written
// out, LPS: +x the patient's left, +y posterior, +z the head).
TEST(IECBeamView, TurnsAsIEC61217States)
{
  struct Case
  {
    const char* Name;
    double Gantry, Collimator, Couch;
    double Source[3]; // from the isocentre
    double Right[3];  // along the columns
    double Up[3];     // towards the top row
  };
  const Case cases[] = {
    { "gantry 0", 0, 0, 0, { 0, -1, 0 }, { 1, 0, 0 }, { 0, 0, 1 } },
    { "gantry 90", 90, 0, 0, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } },
    { "gantry 180", 180, 0, 0, { 0, 1, 0 }, { -1, 0, 0 }, { 0, 0, 1 } },
    { "gantry 270", 270, 0, 0, { -1, 0, 0 }, { 0, -1, 0 }, { 0, 0, 1 } },
    { "couch 90", 0, 0, 90, { 0, -1, 0 }, { 0, 0, -1 }, { 1, 0, 0 } },
    { "collimator 90", 0, 90, 0, { 0, -1, 0 }, { 0, 0, 1 }, { -1, 0, 0 } },
    { "gantry 90, couch 90", 90, 0, 90, { 0, 0, -1 }, { 0, 1, 0 }, { 1, 0, 0 } },
  };
  for (const Case& c : cases)
  {
    mcx::IECBeamView view;
    view.GantryDegrees = c.Gantry;
    view.CollimatorDegrees = c.Collimator;
    view.CouchDegrees = c.Couch;
    view.Isocenter[0] = 3;
    view.Isocenter[1] = -4;
    view.Isocenter[2] = 5;
    view.Pixels[0] = 101;
    view.Pixels[1] = 81;
    mcx::PinholeCamera camera;
    ASSERT_EQ("", view.Camera(camera)) << c.Name;
    double source[3];
    camera.Source(source);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(view.Isocenter[a] + 1000 * c.Source[a], source[a], 1e-9) << c.Name;
      EXPECT_NEAR(c.Right[a], camera.R[a], 1e-12) << c.Name;
      EXPECT_NEAR(-c.Up[a], camera.R[3 + a], 1e-12) << c.Name;
    }
    // The isocentre's ray meets the detector's centre.
    double u, v;
    Project(camera, view.Isocenter, u, v);
    EXPECT_NEAR(50.0, u, 1e-9) << c.Name;
    EXPECT_NEAR(40.0, v, 1e-9) << c.Name;
  }
}

TEST(IECBeamView, RefusesImpossibleViews)
{
  mcx::PinholeCamera camera;
  mcx::IECBeamView view;
  view.SourceToImage = 0;
  EXPECT_NE("", view.Camera(camera));
  view = mcx::IECBeamView();
  view.GantryDegrees = std::nan("");
  EXPECT_NE("", view.Camera(camera));
  view = mcx::IECBeamView();
  view.Pitch[1] = -1;
  EXPECT_NE("", view.Camera(camera));
}
