// X-ray physics on demand: the HU-to-mu transfer function, the radiograph
// geometry, Beer-Lambert attenuation, Poisson noise and the negative log,
// each against an analytic expectation; and a real CT against plastimatch.
#include "mcxSharedData.h"
#include "mcxTestHelpers.h"
#include "vtkMCXAttenuationFunction.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXProjector.h"
#include "vtkMCXRadiograph.h"
#include "vtkMCXRadiographGeometry.h"
#include "vtkMCXReferenceProjector.h"
#include "vtkPiecewiseFunction.h"

#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkMatrix3x3.h"
#include "vtkMetaImageWriter.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtksys/SystemTools.hxx"

#include "mcxVolumeReader.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <vector>

namespace
{
constexpr double MuWater = 0.02; // per mm

// A constant image of `value` in LineIntegral, width x height pixels of 1 mm.
vtkSmartPointer<vtkImageData> ConstantLineIntegral(int width, int height, double value)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  vtkNew<vtkDoubleArray> values;
  values->SetName("LineIntegral");
  values->SetNumberOfValues(static_cast<vtkIdType>(width) * height);
  values->FillValue(value);
  image->GetPointData()->SetScalars(values);
  return image;
}

vtkSmartPointer<vtkImageData> Apply(vtkMCXRadiograph* physics, vtkImageData* input)
{
  physics->SetInputData(input);
  physics->Update();
  auto output = vtkSmartPointer<vtkImageData>::New();
  output->ShallowCopy(physics->GetOutput());
  return output;
}

// Mean and unbiased variance of an array.
void Moments(vtkDataArray* values, double& mean, double& variance)
{
  const vtkIdType n = values->GetNumberOfTuples();
  double sum = 0, squares = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    sum += values->GetTuple1(i);
  }
  mean = sum / n;
  for (vtkIdType i = 0; i < n; ++i)
  {
    squares += (values->GetTuple1(i) - mean) * (values->GetTuple1(i) - mean);
  }
  variance = squares / (n - 1);
}

// A volume in HU indexed and projected exactly under the HU-to-mu TF.
struct ExactAttenuation
{
  vtkNew<vtkMCXDensityIndex> Index;
  vtkNew<vtkPiecewiseFunction> Mu;
  vtkNew<vtkMCXReferenceProjector> Projector;

  explicit ExactAttenuation(vtkImageData* volume, double muWater = MuWater)
  {
    this->Index->SetInputData(volume);
    vtkNew<vtkMCXAttenuationFunction> attenuation;
    attenuation->SetWaterAttenuation(muWater);
    attenuation->FillTransferFunction(this->Mu);
    this->Projector->SetInputConnection(this->Index->GetOutputPort());
    this->Projector->SetTransferFunction(this->Mu);
  }
};

// A water cube (HU 0) of side `side` mm, 1 mm voxels, centred on the origin.
vtkSmartPointer<vtkImageData> WaterCube(int side)
{
  const int dims[3] = { side + 1, side + 1, side + 1 };
  const double spacing[3] = { 1, 1, 1 };
  const double origin[3] = { -side / 2.0, -side / 2.0, -side / 2.0 };
  return mcxtest::MakeVolume(
    VTK_SHORT, dims, [](int, int, int) { return 0.0; }, spacing, origin);
}
}

TEST(Radiograph, AttenuationFunctionIsMuWaterTimesOnePlusHUOver1000)
{
  vtkNew<vtkMCXAttenuationFunction> attenuation;
  attenuation->SetWaterAttenuation(MuWater);
  vtkNew<vtkPiecewiseFunction> mu;
  attenuation->FillTransferFunction(mu);
  EXPECT_DOUBLE_EQ(0.0, mu->GetValue(-2000)); // below the range: its end value, air
  EXPECT_DOUBLE_EQ(0.0, mu->GetValue(-1024));
  EXPECT_DOUBLE_EQ(0.0, mu->GetValue(-1000));
  EXPECT_NEAR(MuWater, mu->GetValue(0), 1e-15);
  EXPECT_NEAR(2 * MuWater, mu->GetValue(1000), 1e-15);
  EXPECT_NEAR(MuWater * 4.071, mu->GetValue(3071), 1e-15);
  EXPECT_NEAR(MuWater * 0.5, mu->GetValue(-500), 1e-15);
  const vtkMTimeType before = mu->GetMTime();
  attenuation->SetWaterAttenuation(0.03); // the energy changes the function
  attenuation->FillTransferFunction(mu);
  EXPECT_GT(mu->GetMTime(), before);
  EXPECT_NEAR(0.03, mu->GetValue(0), 1e-15);
  attenuation->SetHounsfieldRange(-1000, 5000); // metal: still exact beyond 3071
  attenuation->FillTransferFunction(mu);
  EXPECT_NEAR(0.03 * 5, mu->GetValue(4000), 1e-15);
}

TEST(Radiograph, NothingAskedForIsAPassThrough)
{
  auto input = ConstantLineIntegral(8, 8, 0.5);
  vtkNew<vtkMCXRadiograph> physics;
  EXPECT_FALSE(physics->HasEffects());
  auto output = Apply(physics, input);
  EXPECT_EQ(input->GetPointData()->GetArray("LineIntegral"),
    output->GetPointData()->GetArray("LineIntegral"));
  EXPECT_EQ(1, output->GetPointData()->GetNumberOfArrays());
}

TEST(Radiograph, UniformCubeGivesExpOfMinusMuL)
{
  // Along z through the interior of a water cube of 21 voxels of 1 mm (20 mm
  // between the outer voxel centres) the trilinear field integrates to the
  // voxels' sum, mu_water x 21 mm, exactly: I = exp(-0.42).
  auto cube = WaterCube(20);
  ExactAttenuation scene(cube);
  vtkMCXDensityIndex* index = scene.Index;
  vtkPiecewiseFunction* mu = scene.Mu;
  vtkMCXReferenceProjector* exact = scene.Projector;
  exact->SetImageSize(8, 8);
  exact->SetPixelSpacing(1.0);
  exact->CenterOnVolumeOff();
  vtkNew<vtkMCXRadiograph> physics;
  physics->BeerLambertOn();
  physics->SetIncidentIntensity(1000);
  physics->SetInputConnection(exact->GetOutputPort());
  physics->Update();
  vtkDataArray* intensity = physics->GetOutput()->GetPointData()->GetArray("Intensity");
  ASSERT_NE(nullptr, intensity);
  for (vtkIdType p = 0; p < intensity->GetNumberOfTuples(); ++p)
  {
    EXPECT_NEAR(1000 * std::exp(-MuWater * 21), intensity->GetTuple1(p), 1e-6) << "pixel " << p;
  }

  // Monte Carlo: each pixel's line integral L has standard deviation
  // sqrt(L w / A) (its sample count is binomial, w the weight of a sample, A
  // the pixel area), so I = exp(-L) lies within 5 of those of exp(-mu L).
  vtkNew<vtkMCXProjector> monteCarlo;
  monteCarlo->SetInputConnection(index->GetOutputPort());
  monteCarlo->SetTransferFunction(mu);
  monteCarlo->SetSampleExponent(22);
  monteCarlo->SetImageSize(8, 8);
  monteCarlo->SetPixelSpacing(1.0);
  monteCarlo->CenterOnVolumeOff();
  physics->SetIncidentIntensity(1.0);
  physics->SetInputConnection(monteCarlo->GetOutputPort());
  physics->Update();
  const double weight = mcxtest::FieldValue(monteCarlo->GetOutput(), "SampleWeight");
  const double sigmaL = std::sqrt(MuWater * 21 * weight / 1.0);
  intensity = physics->GetOutput()->GetPointData()->GetArray("Intensity");
  for (vtkIdType p = 0; p < intensity->GetNumberOfTuples(); ++p)
  {
    EXPECT_NEAR(
      std::exp(-MuWater * 21), intensity->GetTuple1(p), 5 * sigmaL * std::exp(-MuWater * 21))
      << p;
  }
}

TEST(Radiograph, PoissonNoiseHasTheVarianceOfItsMean)
{
  // n pixels of one mean lambda: the sample mean of the counts is within
  // 5 sqrt(lambda / n) of lambda, and the sample variance within 5 standard
  // deviations of the variance estimator, lambda^2 (2 / (n - 1) + 1 / (lambda n)).
  const int width = 256, height = 256;
  const double n = width * height;
  for (const double lineIntegral : { 0.0, 0.5, 3.0 })
  {
    for (const double photons : { 3.0, 40.0, 1000.0, 1e6 })
    {
      auto input = ConstantLineIntegral(width, height, lineIntegral);
      vtkNew<vtkMCXRadiograph> physics;
      physics->SetPhotonsPerPixel(photons);
      physics->SetNoiseSeed(11);
      auto output = Apply(physics, input);
      vtkDataArray* intensity = output->GetPointData()->GetArray("Intensity");
      vtkNew<vtkDoubleArray> counts;
      counts->SetNumberOfValues(intensity->GetNumberOfTuples());
      for (vtkIdType p = 0; p < intensity->GetNumberOfTuples(); ++p)
      {
        const double k = intensity->GetTuple1(p) * photons;
        ASSERT_NEAR(std::round(k), k, 1e-6 * std::max(1.0, k)) << "counts are whole photons";
        counts->SetValue(p, k);
      }
      double mean, variance;
      Moments(counts, mean, variance);
      const double lambda = photons * std::exp(-lineIntegral);
      EXPECT_NEAR(lambda, mean, 5 * std::sqrt(lambda / n))
        << photons << " photons, L " << lineIntegral;
      EXPECT_NEAR(lambda, variance, 5 * lambda * std::sqrt(2 / (n - 1) + 1 / (lambda * n)))
        << photons << " photons, L " << lineIntegral;
    }
  }
}

TEST(Radiograph, NoiseIsSeededAndThreadIndependent)
{
  auto input = ConstantLineIntegral(128, 128, 1.0);
  vtkNew<vtkMCXRadiograph> physics;
  physics->SetPhotonsPerPixel(500);
  physics->SetNoiseSeed(3);
  vtkSmartPointer<vtkImageData> images[2];
  const int threads[2] = { 1, 2 };
  for (int t = 0; t < 2; ++t)
  {
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads[t] },
      [&]
      {
        physics->Modified();
        images[t] = Apply(physics, input);
      });
  }
  vtkDataArray* a = images[0]->GetPointData()->GetArray("Intensity");
  vtkDataArray* b = images[1]->GetPointData()->GetArray("Intensity");
  for (vtkIdType p = 0; p < a->GetNumberOfTuples(); ++p)
  {
    ASSERT_EQ(a->GetTuple1(p), b->GetTuple1(p)) << p;
  }
  physics->SetNoiseSeed(4);
  auto other = Apply(physics, input);
  vtkIdType differing = 0;
  for (vtkIdType p = 0; p < a->GetNumberOfTuples(); ++p)
  {
    differing +=
      other->GetPointData()->GetArray("Intensity")->GetTuple1(p) != a->GetTuple1(p) ? 1 : 0;
  }
  EXPECT_GT(differing, a->GetNumberOfTuples() / 2);
}

TEST(Radiograph, NegativeLogGivesBackTheLineIntegral)
{
  auto input = ConstantLineIntegral(256, 256, 2.0);
  vtkNew<vtkMCXRadiograph> physics;
  physics->NegativeLogOn();
  auto clean = Apply(physics, input);
  vtkDataArray* attenuation = clean->GetPointData()->GetArray("Attenuation");
  ASSERT_NE(nullptr, attenuation);
  EXPECT_EQ(2.0, attenuation->GetTuple1(0));
  EXPECT_EQ(attenuation, clean->GetPointData()->GetScalars());
  // With N photons, -ln(k / N) has mean L + 1 / (2 lambda) + O(lambda^-2)
  // and variance about 1 / lambda (delta method).
  physics->SetPhotonsPerPixel(10000);
  auto noisy = Apply(physics, input);
  double mean, variance;
  Moments(noisy->GetPointData()->GetArray("Attenuation"), mean, variance);
  const double lambda = 10000 * std::exp(-2.0);
  EXPECT_NEAR(
    2.0 + 0.5 / lambda, mean, 5 * std::sqrt(1 / lambda / (256.0 * 256.0)) + 1 / (lambda * lambda));
  EXPECT_NEAR(1 / lambda, variance, 0.05 / lambda);
  // No photons at all: half a photon, -ln(0.5 / N) (the mean N exp(-50) is
  // below 1e-19: every pixel counts none).
  for (const double photons : { 1e-9, 100.0 })
  {
    physics->SetPhotonsPerPixel(photons);
    auto dark = Apply(physics, ConstantLineIntegral(4, 4, 50.0));
    vtkDataArray* values = dark->GetPointData()->GetArray("Attenuation");
    for (vtkIdType p = 0; p < values->GetNumberOfTuples(); ++p)
    {
      EXPECT_DOUBLE_EQ(-std::log(0.5 / photons), values->GetTuple1(p)) << photons << ", " << p;
    }
  }
}

TEST(Radiograph, ConeBeamViewOfACubeHasTheExpectedLineIntegrals)
{
  // A water cube of 41 voxels of 1 mm at the isocentre; SAD 1000, SID 1500,
  // 0.8 mm pitch.
  vtkNew<vtkMCXRadiographGeometry> geometry;
  geometry->SetDetectorPixels(101, 101);
  const int centre[2] = { 50, 50 };
  EXPECT_TRUE(geometry->IsValid());
  vtkNew<vtkCamera> camera;
  geometry->ConfigureCamera(camera);
  auto cube = WaterCube(40);
  ExactAttenuation scene(cube);
  vtkMCXDensityIndex* index = scene.Index;
  vtkMCXReferenceProjector* exact = scene.Projector;
  exact->SetCamera(camera);
  exact->SetImageSize(101, 101);
  exact->SetPixelSpacing(geometry->GetPixelSpacingAtIsocenter());
  exact->Update();
  vtkDataArray* values = mcxtest::LineIntegral(exact->GetOutput());
  auto at = [&](int column, int row)
  { return values->GetTuple1(static_cast<vtkIdType>(row) * 101 + column); };
  // The central ray integrates the 41 voxels it crosses: mu_water x 41 mm.
  EXPECT_NEAR(MuWater * 41, at(centre[0], centre[1]), 1e-6 * MuWater * 41);
  // Magnification: the support (+-21 mm) seen from 979 mm (its front face)
  // spans +-21 x 1500 / 979 = 32.18 mm on the detector, 40.22 pixels of
  // 0.8 mm: pixel 40 (39.5 .. 40.5, its centre ray inside) is not empty, 41
  // is. A parallel beam (the isocentre's magnification at every depth) puts
  // the edge at 21 x 1.5 / 0.8 = 39.38 pixels, pixel 40 empty.
  for (int d : { -1, 1 })
  {
    EXPECT_EQ(0.0, at(centre[0] + d * 41, centre[1]));
    EXPECT_GT(at(centre[0] + d * 40, centre[1]), 0.0);
    EXPECT_GT(at(centre[0] + d * 36, centre[1]), 0.0);
    EXPECT_EQ(0.0, at(centre[0], centre[1] + d * 41));
    EXPECT_GT(at(centre[0], centre[1] + d * 40), 0.0);
    EXPECT_GT(at(centre[0], centre[1] + d * 36), 0.0);
  }

  // Two cubes of 21 voxels (support +-11 mm) on the central ray at different
  // depths, through the central detector row alone (a 101 x 1 image: the
  // same pixels as row 50, checked first). Near the source (centre x = 307,
  // front face 682 mm from it) the edge is at 11 x 1500 / 682 / 0.8 = 30.24
  // pixels; far (x = -280, 1269 mm) at 16.25. A parallel beam would put both
  // at 20.6.
  vtkNew<vtkDoubleArray> full; // the 101 x 101 image, kept through the updates
  full->DeepCopy(values);
  values = full;
  exact->SetImageSize(101, 1);
  exact->Update();
  vtkDataArray* row = mcxtest::LineIntegral(exact->GetOutput());
  for (int column = 0; column < 101; ++column)
  {
    ASSERT_NEAR(at(column, centre[1]), row->GetTuple1(column), 1e-12) << column;
  }
  const struct
  {
    double X;
    int Edge;
  } depths[2] = { { 307, 30 }, { -280, 16 } };
  for (const auto& depth : depths)
  {
    const int side[3] = { 21, 21, 21 };
    const double unit[3] = { 1, 1, 1 };
    const double corner[3] = { depth.X - 10, -10, -10 };
    index->SetInputData(mcxtest::MakeVolume(
      VTK_SHORT, side, [](int, int, int) { return 0.0; }, unit, corner));
    exact->Update();
    row = mcxtest::LineIntegral(exact->GetOutput());
    for (int d : { -1, 1 })
    {
      EXPECT_GT(row->GetTuple1(centre[0] + d * depth.Edge), 0.0) << depth.X;
      EXPECT_EQ(0.0, row->GetTuple1(centre[0] + d * (depth.Edge + 1))) << depth.X;
    }
  }
  exact->SetImageSize(101, 101);

  // Orientation: a block at +y shows right of centre at gantry 0 (columns
  // along +y), a block at +z above (rows along +z).
  const int dims[3] = { 41, 41, 41 };
  const double spacing[3] = { 1, 1, 1 };
  const double origin[3] = { -20, -20, -20 };
  auto block = mcxtest::MakeVolume(
    VTK_SHORT, dims, [](int, int j, int k) { return j > 30 && k > 25 ? 1000.0 : -1000.0; }, spacing,
    origin);
  index->SetInputData(block);
  exact->Update();
  values = mcxtest::LineIntegral(exact->GetOutput());
  double right = 0, left = 0, up = 0, down = 0;
  for (int row = 0; row < 101; ++row)
  {
    for (int column = 0; column < 101; ++column)
    {
      const double v = values->GetTuple1(static_cast<vtkIdType>(row) * 101 + column);
      (column > centre[0] ? right : left) += v;
      (row > centre[1] ? up : down) += v;
    }
  }
  EXPECT_GT(right, 0.0);
  EXPECT_EQ(0.0, left);
  EXPECT_GT(up, 0.0);
  EXPECT_EQ(0.0, down);
}

TEST(Radiograph, RealCTAgreesWithPlastimatch)
{
  // The same cone-beam geometry and HU map as plastimatch drr (whose map is
  // mu = 0.0022 (1 + HU/1000) per mm, measured from its output): plastimatch
  // traces one ray per pixel centre through constant voxels, we average the
  // trilinear field over each pixel, so the images differ by modelling;
  // the accuracy report measures 1.9 % at 256^2. Stated bound: 3 %.
  const std::string path = mcxtest::SharedDataPath("ct_body_totalseg.nii.gz");
  MCXTEST_NEED_FILE(path);
  MCXTEST_NEED(std::system("plastimatch --version > /dev/null 2>&1") == 0, "plastimatch");
  std::string error;
  vtkSmartPointer<vtkImageData> volume = mcxio::ReadVolume(path, error);
  ASSERT_TRUE(volume) << error;
  const std::string work =
    vtksys::SystemTools::GetCurrentWorkingDirectory() + "/radiograph-plastimatch";
  vtksys::SystemTools::MakeDirectory(work);
  // plastimatch ignores a volume's direction cosines: it is given the
  // voxels axis-aligned at the origin (x = s * index) and the same view
  // turned into that frame, x' = D^T (x - origin) (D, here the patient
  // matrix of the NIfTI's RAS sform in LPS, diag(-1, -1, 1), is a rotation).
  vtkNew<vtkImageData> aligned;
  aligned->ShallowCopy(volume);
  aligned->SetOrigin(0, 0, 0);
  aligned->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, 1);
  vtkMatrix3x3* d = volume->GetDirectionMatrix();
  ASSERT_NEAR(1.0, d->Determinant(), 1e-9);
  vtkNew<vtkMetaImageWriter> writer;
  writer->SetInputData(aligned);
  writer->SetFileName((work + "/ct.mha").c_str());
  writer->SetCompression(false);
  writer->Write();

  const int pixels = 128;
  const double pitch = 600.0 / pixels;
  double bounds[6];
  volume->GetBounds(bounds);
  const double iso[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
    (bounds[4] + bounds[5]) / 2 };
  double turned[3], normal[3], up[3]; // D^T (iso - origin), D^T x, D^T z
  for (int a = 0; a < 3; ++a)
  {
    turned[a] = 0;
    for (int r = 0; r < 3; ++r)
    {
      turned[a] += d->GetElement(r, a) * (iso[r] - volume->GetOrigin()[r]);
    }
    normal[a] = d->GetElement(0, a);
    up[a] = d->GetElement(2, a);
  }
  std::ostringstream command;
  command << "plastimatch drr -I " << work << "/ct.mha -O " << work << "/drr_ -t pfm -i exact -r \""
          << pixels << " " << pixels << "\" -z \"600 600\" --sad 1000 --sid 1500 -o \"" << turned[0]
          << " " << turned[1] << " " << turned[2] << "\" --nrm \"" << normal[0] << " " << normal[1]
          << " " << normal[2] << "\" --vup \"" << up[0] << " " << up[1] << " " << up[2] << "\" > "
          << work << "/plastimatch.log 2>&1";
  ASSERT_EQ(0, std::system(command.str().c_str())) << command.str();
  std::ifstream in(work + "/drr_0000.pfm", std::ios::binary);
  std::string magic;
  int width = 0, height = 0;
  double scale = 0;
  in >> magic >> width >> height >> scale;
  in.get();
  ASSERT_EQ("Pf", magic);
  ASSERT_EQ(pixels, width);
  ASSERT_EQ(pixels, height);
  std::vector<float> theirs(static_cast<std::size_t>(pixels) * pixels);
  in.read(reinterpret_cast<char*>(theirs.data()),
    static_cast<std::streamsize>(theirs.size() * sizeof(float)));
  ASSERT_TRUE(in);

  vtkNew<vtkMCXRadiographGeometry> geometry;
  geometry->SetDetectorPixels(pixels, pixels);
  geometry->SetPixelPitch(pitch);
  geometry->SetIsocenter(iso);
  vtkNew<vtkCamera> camera;
  geometry->ConfigureCamera(camera);
  ExactAttenuation scene(volume, 0.0022);
  vtkMCXReferenceProjector* exact = scene.Projector;
  exact->SetCamera(camera);
  exact->SetImageSize(pixels, pixels);
  exact->SetPixelSpacing(geometry->GetPixelSpacingAtIsocenter());
  exact->Update();
  vtkDataArray* ours = mcxtest::LineIntegral(exact->GetOutput());
  double difference = 0, norm = 0;
  for (int row = 0; row < pixels; ++row) // plastimatch writes the top row first
  {
    for (int column = 0; column < pixels; ++column)
    {
      const double a = ours->GetTuple1(static_cast<vtkIdType>(pixels - 1 - row) * pixels + column);
      const double b = theirs[static_cast<std::size_t>(row) * pixels + column];
      difference += (a - b) * (a - b);
      norm += b * b;
    }
  }
  ASSERT_GT(norm, 0.0);
  const double relativeRMS = std::sqrt(difference / norm);
  RecordProperty("RelativeRMSFromPlastimatch", std::to_string(relativeRMS));
  std::cout << "relative RMS difference from plastimatch: " << relativeRMS << std::endl;
  EXPECT_LT(relativeRMS, 0.03);
}

TEST(Radiograph, AProjectionMatrixIsTheViewItDescribes)
{
  // The same cone-beam view as a camera and as the geometry's matrix: the
  // same image, and the output's ProjectionMatrix field is that matrix (up to
  // scale) whichever way the view was given.
  vtkNew<vtkMCXRadiographGeometry> geometry;
  geometry->SetDetectorPixels(48, 40);
  geometry->SetPixelPitch(2.0);
  geometry->SetGantryAngle(35);
  const double isocenter[3] = { 3, -2, 1 };
  geometry->SetIsocenter(isocenter);
  double P[12];
  ASSERT_TRUE(geometry->GetProjectionMatrix(P));
  vtkNew<vtkCamera> camera;
  ASSERT_TRUE(geometry->ConfigureCamera(camera));
  auto cube = WaterCube(30);
  ExactAttenuation scene(cube);
  vtkMCXReferenceProjector* exact = scene.Projector;
  exact->SetImageSize(48, 40);
  exact->SetCamera(camera);
  exact->SetPixelSpacing(geometry->GetPixelSpacingAtIsocenter());
  exact->Update();
  vtkNew<vtkImageData> byCamera;
  byCamera->DeepCopy(exact->GetOutput());
  exact->SetProjectionMatrix(P);
  exact->UseProjectionMatrixOn();
  exact->SetFocalPlaneDistance(geometry->GetSourceToAxisDistance());
  exact->Update();
  vtkImageData* byMatrix = exact->GetOutput();
  vtkDataArray* a = mcxtest::LineIntegral(byCamera);
  vtkDataArray* b = mcxtest::LineIntegral(byMatrix);
  ASSERT_EQ(48 * 40, b->GetNumberOfTuples());
  const double peak = a->GetRange()[1];
  ASSERT_GT(peak, 0.5 * MuWater * 30);
  for (vtkIdType p = 0; p < a->GetNumberOfTuples(); ++p)
  {
    ASSERT_NEAR(a->GetTuple1(p), b->GetTuple1(p), 1e-9 * peak) << "pixel " << p;
  }
  EXPECT_DOUBLE_EQ(byCamera->GetSpacing()[0], byMatrix->GetSpacing()[0]);
  for (vtkImageData* image : { static_cast<vtkImageData*>(byCamera), byMatrix })
  {
    vtkDataArray* field = image->GetFieldData()->GetArray(vtkMCXTypes::ProjectionMatrixName());
    ASSERT_NE(nullptr, field);
    ASSERT_EQ(12, field->GetNumberOfComponents());
    double written[12], norms[2] = { 0, 0 };
    field->GetTuple(0, written);
    for (int k = 0; k < 12; ++k)
    {
      norms[0] += P[k] * P[k];
      norms[1] += written[k] * written[k];
    }
    for (int k = 0; k < 12; ++k)
    {
      EXPECT_NEAR(P[k] / std::sqrt(norms[0]), written[k] / std::sqrt(norms[1]), 1e-12) << k;
    }
  }
  // An affine matrix is a parallel view: pixels of 1 / |row| world units.
  const double affine[12] = { 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0, 2 };
  exact->SetProjectionMatrix(affine);
  exact->Update();
  EXPECT_DOUBLE_EQ(4.0, exact->GetOutput()->GetSpacing()[0]);
  EXPECT_GT(mcxtest::LineIntegralSum(exact->GetOutput()), 0.0);
  // A matrix that is no camera fails the request with the reason.
  const std::pair<std::array<double, 12>, const char*> cases[] = {
    { { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0 }, "rank below 3" },
    { { 1, 2, 3, 0, 2, 4, 6, 0, 0, 0, 0, 1 }, "not independent" },
  };
  for (const auto& c : cases)
  {
    exact->SetProjectionMatrix(c.first.data());
    mcxtest::FirstError errors(exact);
    exact->Update();
    EXPECT_NE(std::string::npos, errors.Text.find(c.second)) << errors.Text;
  }
  // A camera cannot hold an off-centre image centre.
  geometry->UseImageCenterOn();
  vtkNew<vtkCamera> other;
  mcxtest::FirstError geometryErrors(geometry);
  EXPECT_FALSE(geometry->ConfigureCamera(other));
  EXPECT_NE(std::string::npos, geometryErrors.Text.find("GetProjectionMatrix"));
}
