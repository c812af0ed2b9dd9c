// Projection matrices and pinhole cameras (Core/mcxProjectionMatrix.h) and
// plastimatch's view (Core/mcxPlastimatchView.h), without a pipeline.
#include "mcxPlastimatchView.h"
#include "mcxProjectionMatrix.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace
{
const double Pi = 3.14159265358979323846;

// A proper rotation from Euler angles (z, y, x).
void Rotation(double a, double b, double c, double R[9])
{
  const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b),
               cc = std::cos(c), sc = std::sin(c);
  const double rz[9] = { ca, -sa, 0, sa, ca, 0, 0, 0, 1 };
  const double ry[9] = { cb, 0, sb, 0, 1, 0, -sb, 0, cb };
  const double rx[9] = { 1, 0, 0, 0, cc, -sc, 0, sc, cc };
  double t[9];
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
    {
      t[3 * r + k] = 0;
      for (int m = 0; m < 3; ++m)
        t[3 * r + k] += rz[3 * r + m] * ry[3 * m + k];
    }
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
    {
      R[3 * r + k] = 0;
      for (int m = 0; m < 3; ++m)
        R[3 * r + k] += t[3 * r + m] * rx[3 * m + k];
    }
}

mcx::PinholeCamera RandomCamera(std::mt19937_64& random)
{
  std::uniform_real_distribution<double> angle(-Pi, Pi), focal(100, 5000), centre(-50, 600),
    position(-1500, 1500);
  mcx::PinholeCamera c;
  c.Fx = focal(random);
  c.Fy = focal(random);
  c.Cx = centre(random);
  c.Cy = centre(random);
  Rotation(angle(random), angle(random) / 2, angle(random), c.R);
  for (double& t : c.T)
  {
    t = position(random);
  }
  return c;
}

void ExpectSameCamera(const mcx::PinholeCamera& a, const mcx::PinholeCamera& b, double tolerance)
{
  EXPECT_NEAR(a.Fx, b.Fx, tolerance * a.Fx);
  EXPECT_NEAR(a.Fy, b.Fy, tolerance * a.Fy);
  EXPECT_NEAR(a.Cx, b.Cx, tolerance * a.Fx);
  EXPECT_NEAR(a.Cy, b.Cy, tolerance * a.Fy);
  for (int k = 0; k < 9; ++k)
  {
    EXPECT_NEAR(a.R[k], b.R[k], tolerance);
  }
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_NEAR(a.T[k], b.T[k], tolerance * 2000);
  }
}

// Plastimatch writes the image centre ic apart from its matrix: u = ic[0]
// + (P0 X) / (P2 X). Folded in, the matrix is [1 0 ic0; 0 1 ic1; 0 0 1] P.
void FoldImageCentre(const double ic[2], const double plastimatch[12], double P[12])
{
  for (int k = 0; k < 4; ++k)
  {
    P[k] = plastimatch[k] + ic[0] * plastimatch[8 + k];
    P[4 + k] = plastimatch[4 + k] + ic[1] * plastimatch[8 + k];
    P[8 + k] = plastimatch[8 + k];
  }
}

// Equal up to a positive scale.
void ExpectSameMatrix(const double a[12], const double b[12], double tolerance)
{
  double na = 0, nb = 0;
  for (int k = 0; k < 12; ++k)
  {
    na += a[k] * a[k];
    nb += b[k] * b[k];
  }
  na = std::sqrt(na);
  nb = std::sqrt(nb);
  for (int k = 0; k < 12; ++k)
  {
    EXPECT_NEAR(a[k] / na, b[k] / nb, tolerance) << "element " << k;
  }
}
}

TEST(ProjectionMatrix, DecomposesWhatItComposesAtAnyScale)
{
  std::mt19937_64 random(7);
  for (int trial = 0; trial < 200; ++trial)
  {
    const mcx::PinholeCamera camera = RandomCamera(random);
    double P[12];
    mcx::MatrixFromPinhole(camera, P);
    for (double scale : { 1.0, -2.5, 1e-6, 3e4, 1e-300, -1e290 })
    {
      double scaled[12];
      for (int k = 0; k < 12; ++k)
      {
        scaled[k] = scale * P[k];
      }
      mcx::PinholeCamera back;
      ASSERT_EQ("", mcx::PinholeFromMatrix(scaled, back));
      ExpectSameCamera(camera, back, 1e-9);
    }
  }
}

TEST(ProjectionMatrix, AgreesWithTheGeometryPixelByPixel)
{
  // A point's pixel by the matrix equals its pixel by the projector's own
  // geometry (ProjectToPlane, then the grid), row 0 of the matrix at the top.
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> offset(-200, 200);
  for (int trial = 0; trial < 100; ++trial)
  {
    const mcx::PinholeCamera camera = RandomCamera(random);
    const int size[2] = { 300 + trial, 200 + 2 * trial };
    mcx::ProjectionGeometry g;
    ASSERT_EQ("", mcx::GeometryFromPinhole(camera, size, 800.0, g));
    for (bool perspective : { true, false })
    {
      g.Perspective = perspective;
      if (!perspective)
      {
        g.Obliquity[0] = 0.3;
        g.Obliquity[1] = -0.1;
      }
      double P[12];
      mcx::MatrixFromGeometry(g, P);
      double source[3];
      camera.Source(source);
      for (int point = 0; point < 20; ++point)
      {
        double x[3];
        for (int a = 0; a < 3; ++a)
        {
          // In front of the source: along the optical axis plus an offset.
          x[a] = source[a] + 900 * camera.R[6 + a] + offset(random);
        }
        double a, b, u, v;
        ASSERT_TRUE(mcx::ProjectToPlane(g, x, a, b));
        ASSERT_TRUE(mcx::ProjectPoint(P, x, u, v));
        const double i = (a - g.Origin[0]) / g.Spacing[0];
        const double j = (b - g.Origin[1]) / g.Spacing[1];
        EXPECT_NEAR(i, u, 1e-7);
        EXPECT_NEAR(size[1] - 1 - j, v, 1e-7);
      }
    }
  }
}

TEST(ProjectionMatrix, TheGeometryGivesBackItsCamera)
{
  std::mt19937_64 random(5);
  for (int trial = 0; trial < 50; ++trial)
  {
    const mcx::PinholeCamera camera = RandomCamera(random);
    const int size[2] = { 640, 480 };
    mcx::ProjectionGeometry g;
    ASSERT_EQ("", mcx::GeometryFromPinhole(camera, size, 1000.0, g));
    ExpectSameCamera(camera, mcx::PinholeFromGeometry(g), 1e-12);
    EXPECT_NEAR(1000.0 / camera.Fx, g.Spacing[0], 1e-12);
  }
}

TEST(ProjectionMatrix, AnAffineMatrixGivesBackItsParallelView)
{
  // A parallel view's affine P (MatrixFromGeometry) read back gives a
  // geometry of the same P, the same beams (cross-section) and rays, at any
  // scale: rays along W, and oblique ones whose P's rows are not
  // perpendicular (the plane then tilted so that the pixels are rectangles).
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> obliquity(-0.8, 0.8);
  for (int trial = 0; trial < 60; ++trial)
  {
    const int size[2] = { 100 + trial, 300 - trial };
    mcx::ProjectionGeometry g;
    ASSERT_EQ("", mcx::GeometryFromPinhole(RandomCamera(random), size, 700.0, g));
    g.Perspective = false;
    if (trial % 3 != 0)
    {
      g.Obliquity[0] = obliquity(random);
      g.Obliquity[1] = trial % 3 == 1 ? 0.0 : obliquity(random);
    }
    double P[12];
    mcx::MatrixFromGeometry(g, P);
    const double scale = trial % 2 == 0 ? -3.5 : 1e-3;
    double scaled[12];
    for (int k = 0; k < 12; ++k)
    {
      scaled[k] = scale * P[k];
    }
    ASSERT_TRUE(mcx::IsAffineMatrix(scaled));
    EXPECT_EQ("", mcx::ProjectionMatrixProblem(scaled));
    mcx::ProjectionGeometry back;
    ASSERT_EQ("", mcx::GeometryFromAffineMatrix(scaled, size, back)) << trial;
    EXPECT_FALSE(back.Perspective);
    EXPECT_EQ(size[0], back.Size[0]);
    EXPECT_EQ(size[1], back.Size[1]);
    double again[12];
    mcx::MatrixFromGeometry(back, again);
    for (int k = 0; k < 12; ++k)
    {
      EXPECT_NEAR(P[k], again[k], 1e-12 * (1.0 + std::fabs(P[k]))) << trial << " " << k;
    }
    EXPECT_NEAR(g.BeamCrossSection(), back.BeamCrossSection(), 1e-12 * g.BeamCrossSection());
    // The rays W + o0 U + o1 V of both, as unit vectors, agree up to sign.
    double rays[2][3];
    for (int a = 0; a < 3; ++a)
    {
      rays[0][a] = g.W[a] + g.Obliquity[0] * g.U[a] + g.Obliquity[1] * g.V[a];
      rays[1][a] = back.W[a] + back.Obliquity[0] * back.U[a] + back.Obliquity[1] * back.V[a];
    }
    double dot = 0, n0 = 0, n1 = 0;
    for (int a = 0; a < 3; ++a)
    {
      dot += rays[0][a] * rays[1][a];
      n0 += rays[0][a] * rays[0][a];
      n1 += rays[1][a] * rays[1][a];
    }
    EXPECT_NEAR(1.0, std::fabs(dot) / std::sqrt(n0 * n1), 1e-12);
    if (g.Obliquity[0] == 0 && g.Obliquity[1] == 0)
    {
      EXPECT_EQ(0.0, back.Obliquity[0]);
      EXPECT_EQ(0.0, back.Obliquity[1]);
    }
  }
  // Rows that are not independent: no direction for the rays.
  const double flat[12] = { 1, 2, 3, 0, 2, 4, 6, 1, 0, 0, 0, 1 };
  EXPECT_NE(std::string::npos, mcx::ProjectionMatrixProblem(flat).find("not independent"));
  // A last row of zeros is no affine matrix: the pinhole's rank error.
  const double zero[12] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0 };
  EXPECT_FALSE(mcx::IsAffineMatrix(zero));
  EXPECT_NE(std::string::npos, mcx::ProjectionMatrixProblem(zero).find("rank below 3"));
}

TEST(ProjectionMatrix, RefusesWhatIsNoCamera)
{
  mcx::PinholeCamera camera;
  double P[12] = { 1000, 0, 256, 0, 0, 1000, 256, 0, 0, 0, 1, 1000 };
  ASSERT_EQ("", mcx::PinholeFromMatrix(P, camera));
  double bad[12];
  std::copy(P, P + 12, bad);
  bad[5] = std::nan("");
  EXPECT_NE(std::string::npos, mcx::PinholeFromMatrix(bad, camera).find("finite"));
  // An affine matrix (a parallel view): no source point.
  const double affine[12] = { 1, 0, 0, 5, 0, 1, 0, 5, 0, 0, 0, 1 };
  EXPECT_NE(std::string::npos, mcx::PinholeFromMatrix(affine, camera).find("rank below 3"));
  // Rank 2: the third row a combination of the first two.
  std::copy(P, P + 12, bad);
  for (int k = 0; k < 4; ++k)
  {
    bad[8 + k] = P[k] + 2 * P[4 + k];
  }
  EXPECT_NE(std::string::npos, mcx::PinholeFromMatrix(bad, camera).find("rank below 3"));
  // Skewed pixels: K's element (0, 1) at 1 % of fx.
  std::copy(P, P + 12, bad);
  bad[1] = 10;
  EXPECT_NE(std::string::npos, mcx::PinholeFromMatrix(bad, camera).find("skewed"));
  const int size[2] = { 512, 512 };
  mcx::ProjectionGeometry g;
  EXPECT_NE("", mcx::GeometryFromPinhole(camera, size, 0.0, g));
  const int none[2] = { 0, 512 };
  EXPECT_NE("", mcx::GeometryFromPinhole(camera, none, 1000.0, g));
}

// The matrices plastimatch 1.9.4 wrote (`plastimatch drr -G -O g ...
// --sad 1000 --sid 1500 -o "5 6 7"`, the files g0000.txt, g0001.txt): its
// image centre, then its 3x4 matrix. The CLI test compares with a live
// plastimatch too, where one is installed.
TEST(PlastimatchView, GivesTheMatricesPlastimatchWrites)
{
  struct Case
  {
    const char* Options;
    mcx::PlastimatchView View;
    double Centre[2];
    double Matrix[12];
  };
  mcx::PlastimatchView base;
  base.Isocenter[0] = 5;
  base.Isocenter[1] = 6;
  base.Isocenter[2] = 7;
  base.Pixels[0] = base.Pixels[1] = 64;
  base.DetectorSize[0] = base.DetectorSize[1] = 200;
  Case cases[4] = {
    { "-r \"64 64\" -z \"200 200\" (gantry 0)", base, { 31.5, 31.5 },
      { 0, 0.32, 0, -1.92, 0, 0, -0.32, 2.24, -6.66666667e-04, 0, 0, 6.70e-01 } },
    { "-a 2 -N 30, the second", base, { 31.5, 31.5 },
      { 1.60000004e-01, 2.77128127e-01, 0, -2.46276878e+00, 0, 0, -3.2e-01, 2.24, -5.77350264e-04,
        3.33333342e-04, 0, 6.67553418e-01 } },
    { "--nrm \"1 1 0\" --vup \"0 0 -1\"", base, { 31.5, 31.5 },
      { 2.26274170e-01, -2.26274170e-01, 0, 2.26274170e-01, 0, 0, 3.2e-01, -2.24, -4.71404521e-04,
        -4.71404521e-04, 0, 6.71852116e-01 } },
    { "-c \"10 20\"", base, { 10, 20 },
      { 0, 0.32, 0, -1.92, 0, 0, -0.32, 2.24, -6.66666667e-04, 0, 0, 6.70e-01 } },
  };
  cases[1].View.GantryDegrees = 30;
  cases[2].View.HasNormal = true;
  cases[2].View.Normal[0] = cases[2].View.Normal[1] = 1;
  cases[2].View.Normal[2] = 0;
  cases[2].View.Up[2] = -1;
  cases[3].View.HasImageCenter = true;
  cases[3].View.ImageCenter[0] = 10;
  cases[3].View.ImageCenter[1] = 20;
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.Options);
    mcx::PinholeCamera camera;
    ASSERT_EQ("", c.View.Camera(camera));
    double ours[12], theirs[12];
    mcx::MatrixFromPinhole(camera, ours);
    FoldImageCentre(c.Centre, c.Matrix, theirs);
    // Plastimatch writes 9 digits and computes in single precision.
    ExpectSameMatrix(ours, theirs, 2e-7);
  }
}

TEST(PlastimatchView, TurnsTheSourceFromPlusXTowardsMinusY)
{
  mcx::PlastimatchView view;
  for (double angle : { 0.0, 90.0, 180.0, 270.0 })
  {
    view.GantryDegrees = angle;
    mcx::PinholeCamera camera;
    ASSERT_EQ("", view.Camera(camera));
    double source[3];
    camera.Source(source);
    const double a = angle * Pi / 180;
    EXPECT_NEAR(1000 * std::cos(a), source[0], 1e-9);
    EXPECT_NEAR(-1000 * std::sin(a), source[1], 1e-9);
    EXPECT_NEAR(0, source[2], 1e-9);
  }
}

TEST(PlastimatchView, RefusesImpossibleViews)
{
  mcx::PinholeCamera camera;
  mcx::PlastimatchView view;
  view.SourceToImage = 0;
  EXPECT_NE("", view.Camera(camera));
  view = mcx::PlastimatchView();
  view.HasNormal = true;
  view.Normal[0] = 0;
  view.Normal[2] = 1; // along vup
  EXPECT_NE(std::string::npos, view.Camera(camera).find("view-up"));
  view.Normal[2] = 0; // zero
  EXPECT_NE(std::string::npos, view.Camera(camera).find("normal"));
  view = mcx::PlastimatchView();
  view.DetectorSize[1] = std::nan("");
  EXPECT_NE("", view.Camera(camera));
  view = mcx::PlastimatchView();
  view.Pixels[0] = 0;
  EXPECT_NE("", view.Camera(camera));
}
