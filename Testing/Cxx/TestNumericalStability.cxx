// The hard cases: every input a user can produce gives a correct, finite
// result or a clear error. Each test asserts the value it must produce.
#include "mcxTestHelpers.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"
#include "vtkMCXReferenceProjector.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace
{
// Collects the warnings and errors an algorithm reports.
struct Messages
{
  std::string Warnings;
  std::string Errors;
  vtkNew<vtkCallbackCommand> OnWarning;
  vtkNew<vtkCallbackCommand> OnError;

  explicit Messages(vtkObject* object)
  {
    this->OnWarning->SetClientData(&this->Warnings);
    this->OnError->SetClientData(&this->Errors);
    auto append = [](vtkObject*, unsigned long, void* target, void* text)
    { *static_cast<std::string*>(target) += static_cast<const char*>(text); };
    this->OnWarning->SetCallback(append);
    this->OnError->SetCallback(append);
    object->AddObserver(vtkCommand::WarningEvent, this->OnWarning);
    object->AddObserver(vtkCommand::ErrorEvent, this->OnError);
  }
};

struct Outcome
{
  vtkSmartPointer<vtkImageData> Image;
  std::string Warnings;
  std::string Errors;
};

// An exact or a Monte Carlo projector (2^m - 1 samples).
// The reference projector's relative tolerance in NewProjector (its own
// default unless a test lowers it).
double ReferenceTolerance = 1e-3;

vtkSmartPointer<vtkMCXProjectorBase> NewProjector(bool reference, int m = 18)
{
  if (reference)
  {
    auto exact = vtkSmartPointer<vtkMCXReferenceProjector>::New();
    exact->SetRelativeTolerance(ReferenceTolerance);
    return exact;
  }
  auto monteCarlo = vtkSmartPointer<vtkMCXProjector>::New();
  monteCarlo->SetDeposit(vtkMCXTypes::POINT); // the paper's estimator: one sample, one pixel
  monteCarlo->SetSampleExponent(m);
  return monteCarlo;
}

// Index -> projector (Monte Carlo or reference) with an explicit parallel
// detector along -y (U = x, V = z), framed on the volume.
Outcome Project(vtkImageData* volume, vtkPiecewiseFunction* tf, bool reference, int m = 18,
  int size = 24, vtkCamera* camera = nullptr, int strategy = vtkMCXTypes::HYBRID)
{
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  vtkSmartPointer<vtkMCXProjectorBase> projector;
  if (reference)
  {
    auto exact = vtkSmartPointer<vtkMCXReferenceProjector>::New();
    exact->SetRelativeTolerance(std::min(1e-4, ReferenceTolerance));
    projector = exact;
  }
  else
  {
    auto monteCarlo = vtkSmartPointer<vtkMCXProjector>::New();
    monteCarlo->SetDeposit(vtkMCXTypes::POINT); // as NewProjector
    monteCarlo->SetSampleExponent(m);
    monteCarlo->SetStrategy(strategy);
    projector = monteCarlo;
  }
  projector->SetInputConnection(index->GetOutputPort());
  projector->SetTransferFunction(tf);
  projector->SetDetectorAxisU(1, 0, 0);
  projector->SetDetectorAxisV(0, 0, 1);
  projector->SetCamera(camera);
  projector->SetImageSize(size, size);
  Messages messages(projector);
  projector->Update();
  return { projector->GetOutput(), messages.Warnings, messages.Errors };
}

bool AllFinite(vtkImageData* image)
{
  vtkDataArray* values = mcxtest::LineIntegral(image);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    if (!std::isfinite(values->GetTuple1(i)))
    {
      return false;
    }
  }
  return values->GetNumberOfTuples() > 0;
}

double PixelArea(vtkImageData* image)
{
  return image->GetSpacing()[0] * image->GetSpacing()[1];
}

// The Monte Carlo image agrees with the exact one within the binomial bound;
// for a camera, within the bound of its samples' weights (their second
// moment on a cloud of the same distribution, pixels found by VTK's own
// projection).
void ExpectAgreement(
  vtkImageData* volume, vtkPiecewiseFunction* tf, const char* what, vtkCamera* camera = nullptr)
{
  const Outcome exact = Project(volume, tf, true, 0, 24, camera);
  const Outcome estimate = Project(volume, tf, false, 18, 24, camera);
  ASSERT_TRUE(exact.Errors.empty()) << what << ": " << exact.Errors;
  ASSERT_TRUE(AllFinite(exact.Image) && AllFinite(estimate.Image)) << what;
  const double integral = mcxtest::FieldValue(exact.Image, "Integral");
  const double samples = std::ldexp(1.0, 18) - 1;
  const double error = mcxtest::RelativeRMS(estimate.Image, exact.Image);
  if (!camera)
  {
    const double bound =
      mcxtest::ExpectedRelativeRMS(exact.Image, integral, PixelArea(exact.Image), samples);
    EXPECT_LT(error, 1.5 * bound + 1e-3) << what;
    return;
  }
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  const mcxtest::WeightMoments moments =
    mcxtest::MeasureSampledWeights(index->GetOutputPort(), tf, camera, 24, 24, 20);
  const double bound = mcxtest::ExpectedRelativeRMSOfWeights(
    exact.Image, integral, PixelArea(exact.Image), samples, moments.MeanSquare);
  // The squared error sums n effective pixels: relative spread sqrt(2 / n).
  const double spread = std::sqrt(2.0 / mcxtest::EffectivePixelCount(moments.PixelMeanSquare));
  EXPECT_LT(error, (1.0 + 4.0 * spread) * bound + 1e-3) << what;
}

vtkSmartPointer<vtkPiecewiseFunction> Ramp(double x0, double y0, double x1, double y1)
{
  auto tf = vtkSmartPointer<vtkPiecewiseFunction>::New();
  tf->AddPoint(x0, y0);
  tf->AddPoint(x1, y1);
  return tf;
}

const int Dims[3] = { 10, 9, 8 };

vtkSmartPointer<vtkImageData> Phantom(int type = VTK_SHORT)
{
  return mcxtest::MakeVolume(
    type, Dims, [](int i, int j, int k) { return mcxtest::Phantom(i, j, k, Dims); });
}
}

// ---- Transfer functions ----------------------------------------------------

TEST(TransferFunctions, ZeroEverywhereGivesAnEmptyImageAndAWarning)
{
  // Sampled, exact, and every voxel once (which then keeps no voxel).
  auto zero = Ramp(-1e6, 0, 1e6, 0);
  for (int variant = 0; variant < 3; ++variant)
  {
    const Outcome run = Project(Phantom(), zero, variant == 1, 18, 24, nullptr,
      variant == 2 ? vtkMCXTypes::EVERY_VOXEL : vtkMCXTypes::HYBRID);
    EXPECT_TRUE(run.Errors.empty());
    EXPECT_NE(std::string::npos, run.Warnings.find("zero over the whole volume")) << run.Warnings;
    EXPECT_EQ(0.0, mcxtest::LineIntegral(run.Image)->GetRange()[1]);
    EXPECT_EQ(0.0, mcxtest::LineIntegral(run.Image)->GetRange()[0]);
    // An empty image is exactly known: its error is 0, not NaN.
    EXPECT_EQ(0.0, mcxtest::FieldValue(run.Image, "EstimatedRelativeError"));
  }
}

TEST(TransferFunctions, NonZeroAtOneLevelOnly)
{
  // Only voxels of value 400 (the core) contribute.
  auto tf = vtkSmartPointer<vtkPiecewiseFunction>::New();
  tf->AddPoint(399, 0);
  tf->AddPoint(400, 5);
  tf->AddPoint(401, 0);
  auto volume = mcxtest::MakeVolume(VTK_SHORT, Dims,
    [](int i, int j, int k) { return mcxtest::Phantom(i, j, k, Dims) >= 400 ? 400 : 100; });
  ExpectAgreement(volume, tf, "one level");
  const Outcome run = Project(volume, tf, false);
  double count = 0;
  for (int k = 0; k < Dims[2]; ++k)
    for (int j = 0; j < Dims[1]; ++j)
      for (int i = 0; i < Dims[0]; ++i)
        count += mcxtest::Phantom(i, j, k, Dims) >= 400 ? 1 : 0;
  ASSERT_GT(count, 0);
  EXPECT_DOUBLE_EQ(5.0 * count, mcxtest::FieldValue(run.Image, "Integral"));
}

TEST(TransferFunctions, NegativeValuesCountAsZeroWithAWarningNaNIsAnError)
{
  // g = max(0, f - 200): the negative part is clamped, as the reference with
  // an explicitly clamped TF shows. A NaN point defines no image: an error
  // and an empty output, not an image of what the rest would give.
  auto negative = Ramp(0, -200, 400, 200);
  auto clamped = vtkSmartPointer<vtkPiecewiseFunction>::New();
  clamped->AddPoint(0, 0);
  clamped->AddPoint(200, 0);
  clamped->AddPoint(400, 200);
  const Outcome a = Project(Phantom(), negative, false);
  const Outcome b = Project(Phantom(), clamped, false);
  EXPECT_NE(std::string::npos, a.Warnings.find("negative")) << a.Warnings;
  EXPECT_DOUBLE_EQ(
    mcxtest::FieldValue(b.Image, "Integral"), mcxtest::FieldValue(a.Image, "Integral"));
  EXPECT_EQ(0.0, mcxtest::RelativeRMS(a.Image, b.Image));

  auto withNaN = Ramp(0, 1, 400, 1);
  withNaN->AddPoint(100, std::nan(""));
  for (bool reference : { false, true })
  {
    const Outcome c = Project(Phantom(), withNaN, reference);
    EXPECT_NE(std::string::npos, c.Errors.find("NaN")) << c.Errors;
    EXPECT_EQ(0, c.Image->GetNumberOfPoints()) << (reference ? "reference" : "Monte Carlo");
  }
}

TEST(TransferFunctions, WeightsFrom1e300To1eMinus300)
{
  // Level weights 1e-300 and 1e300 in one volume: the integral is exact in
  // double and the image is the 1e300 part alone, finite.
  auto volume =
    mcxtest::MakeVolume(VTK_UNSIGNED_CHAR, Dims, [](int i, int, int) { return i < 5 ? 1 : 2; });
  auto tf = vtkSmartPointer<vtkPiecewiseFunction>::New();
  tf->AddPoint(1, 1e-300);
  tf->AddPoint(2, 1e300);
  tf->ClampingOn();
  const Outcome run = Project(volume, tf, false);
  const double voxels = 5.0 * Dims[1] * Dims[2];
  EXPECT_DOUBLE_EQ(voxels * 1e300 + voxels * 1e-300, mcxtest::FieldValue(run.Image, "Integral"));
  EXPECT_TRUE(AllFinite(run.Image));
  EXPECT_NEAR(
    1.0, mcxtest::LineIntegralSum(run.Image) * PixelArea(run.Image) / mcxtest::FieldValue(run.Image, "Integral"), 1e-12);
  ExpectAgreement(volume, tf, "1e-300..1e300");
}

TEST(TransferFunctions, InfiniteWeightIsAnError)
{
  auto tf = Ramp(0, 0, 400, 1);
  tf->AddPoint(200, std::numeric_limits<double>::infinity());
  const Outcome run = Project(Phantom(), tf, false);
  EXPECT_NE(std::string::npos, run.Errors.find("infinite")) << run.Errors;
}

// ---- Data ------------------------------------------------------------------

TEST(Data, NaNAndInfVoxelsAreLeftOut)
{
  auto volume = mcxtest::MakeVolume(VTK_DOUBLE, Dims,
    [](int i, int j, int k)
    {
      if ((i + j + k) % 7 == 0)
        return std::nan("");
      if ((i + j + k) % 11 == 0)
        return (i % 2 ? 1.0 : -1.0) * std::numeric_limits<double>::infinity();
      return 1.0 + 0.25 * ((i * j + k) % 5);
    });
  // The same volume with those voxels at 0 under a TF that is 0 there.
  auto zeroed = mcxtest::MakeVolume(VTK_DOUBLE, Dims,
    [](int i, int j, int k)
    {
      if ((i + j + k) % 7 == 0 || (i + j + k) % 11 == 0)
        return 0.0;
      return 1.0 + 0.25 * ((i * j + k) % 5);
    });
  auto tf = Ramp(0, 0, 2, 2);
  const Outcome a = Project(volume, tf, true);
  const Outcome b = Project(zeroed, tf, true);
  EXPECT_TRUE(AllFinite(a.Image));
  EXPECT_NEAR(0.0, mcxtest::RelativeRMS(a.Image, b.Image), 1e-12);
  EXPECT_NEAR(
    mcxtest::FieldValue(b.Image, "Integral"), mcxtest::FieldValue(a.Image, "Integral"), 1e-9);
  ExpectAgreement(volume, tf, "NaN/Inf voxels");
}

TEST(Data, SingleNonZeroVoxel)
{
  // One voxel of value 8 at (4, 3, 5), unit spacing, tent kernel: the pixel
  // at its centre, averaged over its unit area, sees
  // 8 * (integral over the pixel of (1 - |x|)(1 - |z|)) = 8 * 0.75^2.
  auto volume = mcxtest::MakeVolume(VTK_UNSIGNED_CHAR, Dims,
    [](int i, int j, int k) { return i == 4 && j == 3 && k == 5 ? 8 : 0; });
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  vtkNew<vtkMCXReferenceProjector> exact;
  exact->SetInputConnection(index->GetOutputPort());
  exact->SetImageSize(3, 3);
  exact->SetPixelSpacing(1.0);
  exact->CenterOnVolumeOff();
  exact->SetDetectorCenter(4, 5);
  exact->SetDetectorAxisU(1, 0, 0);
  exact->SetDetectorAxisV(0, 0, 1);
  exact->SetRelativeTolerance(1e-6);
  exact->SetMaximumSubdivision(243);
  Messages messages(exact);
  exact->Update();
  // Stopped short of 1e-6 (the tent's kinks), it says so.
  const double error = mcxtest::FieldValue(exact->GetOutput(), "EstimatedRelativeError");
  EXPECT_EQ(error > 1e-6,
    messages.Warnings.find("stopped at 243^2 rays per pixel (MaximumSubdivision)") !=
      std::string::npos)
    << error << " " << messages.Warnings;
  vtkDataArray* values = mcxtest::LineIntegral(exact->GetOutput());
  EXPECT_NEAR(8 * 0.75 * 0.75, values->GetTuple1(4), 1e-4);
  EXPECT_NEAR(
    8 * 0.75 * 0.125, values->GetTuple1(1), 1e-4); // below: 0.125 of the tent's area per axis
  EXPECT_NEAR(8 * 0.125 * 0.125, values->GetTuple1(0), 1e-4);
  ExpectAgreement(volume, nullptr, "single voxel");
}

TEST(Data, DegenerateShapes)
{
  // 1x1x1, 1x1xN and Nx1x1 volumes of constant 3 with spacing (2, 3, 4):
  // the integral is 3 * voxels * 24, and a ray along y through a voxel
  // centre sees 3 * 3 (the tent along y spans one spacing each side).
  const int shapes[][3] = { { 1, 1, 1 }, { 1, 1, 7 }, { 7, 1, 1 } };
  const double spacing[3] = { 2, 3, 4 };
  for (const auto& shape : shapes)
  {
    auto volume = mcxtest::MakeVolume(
      VTK_FLOAT, shape, [](int, int, int) { return 3.0; }, spacing);
    for (bool reference : { false, true })
    {
      const Outcome run = Project(volume, nullptr, reference, 16, 9);
      ASSERT_TRUE(run.Errors.empty()) << run.Errors;
      ASSERT_TRUE(AllFinite(run.Image));
      const double voxels = static_cast<double>(shape[0]) * shape[1] * shape[2];
      EXPECT_DOUBLE_EQ(3 * voxels * 24, mcxtest::FieldValue(run.Image, "Integral"));
      if (!reference)
      {
        EXPECT_NEAR(3 * voxels * 24, mcxtest::LineIntegralSum(run.Image) * PixelArea(run.Image), 1e-9 * voxels);
      }
    }
    ExpectAgreement(volume, nullptr, "degenerate shape");
  }
  // The line integral at the centre of a single voxel, exactly.
  auto single = mcxtest::MakeVolume(
    VTK_FLOAT, shapes[0], [](int, int, int) { return 3.0; }, spacing);
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(single);
  vtkNew<vtkMCXReferenceProjector> exact;
  exact->SetInputConnection(index->GetOutputPort());
  exact->SetImageSize(1, 1);
  exact->SetPixelSpacing(1e-9);
  exact->SetDetectorAxisU(1, 0, 0);
  exact->SetDetectorAxisV(0, 0, 1);
  exact->Update();
  EXPECT_NEAR(3.0 * 3.0, mcxtest::LineIntegral(exact->GetOutput())->GetTuple1(0), 1e-6);
}

TEST(Data, ExtentNotAtZeroAndDirectionMatrixMoveTheImageRigidly)
{
  // A volume with extent starting at (5, -3, 2) is the same volume as one at
  // extent 0 with its origin moved; a rotated direction matrix viewed along
  // the rotated axes gives the unrotated image.
  const double spacing[3] = { 1.5, 1.0, 2.0 };
  auto plain = mcxtest::MakeVolume(
    VTK_SHORT, Dims, [](int i, int j, int k) { return mcxtest::Phantom(i, j, k, Dims); }, spacing);
  auto shifted = mcxtest::MakeVolume(
    VTK_SHORT, Dims, [](int i, int j, int k) { return mcxtest::Phantom(i, j, k, Dims); }, spacing);
  shifted->SetExtent(5, 5 + Dims[0] - 1, -3, -3 + Dims[1] - 1, 2, 2 + Dims[2] - 1);
  shifted->SetOrigin(-5 * 1.5, 3 * 1.0, -2 * 2.0);
  const Outcome a = Project(plain, nullptr, false);
  const Outcome b = Project(shifted, nullptr, false);
  EXPECT_EQ(0.0, mcxtest::RelativeRMS(b.Image, a.Image));
  EXPECT_NEAR(a.Image->GetOrigin()[0], b.Image->GetOrigin()[0], 1e-12);

  // Rotate by 90 degrees about y: grid x -> world -z, grid z -> world x.
  // The reference is compared at a tolerance far below the bound (the frame
  // leaves mcx::FrameMargin around the support, so edge pixels hold part of
  // it, where the adaptive integration of two equal scenes may differ by up
  // to its tolerance).
  ReferenceTolerance = 1e-11;
  auto rotated = mcxtest::MakeVolume(
    VTK_SHORT, Dims, [](int i, int j, int k) { return mcxtest::Phantom(i, j, k, Dims); }, spacing);
  rotated->SetDirectionMatrix(0, 0, 1, 0, 1, 0, -1, 0, 0);
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(rotated);
  for (bool reference : { false, true })
  {
    vtkSmartPointer<vtkMCXProjectorBase> projector = NewProjector(reference);
    projector->SetInputConnection(index->GetOutputPort());
    projector->SetDetectorAxisU(0, 0, -1); // world -z is grid x
    projector->SetDetectorAxisV(1, 0, 0);  // world x is grid z
    projector->SetImageSize(24, 24);
    projector->Update();
    const Outcome unrotated = Project(plain, nullptr, reference);
    const double difference = mcxtest::RelativeRMS(projector->GetOutput(), unrotated.Image);
    if (reference)
      EXPECT_LT(difference, 1e-9);
    else
      EXPECT_EQ(0.0, difference); // same samples, same pixels
  }
  ReferenceTolerance = 1e-3;
}

TEST(Data, TinyAndHugeSpacings)
{
  // Line integrals scale with the spacing; the estimate stays within its bound.
  for (double s : { 1e-6, 1e6 })
  {
    const double spacing[3] = { s, s, s };
    auto volume = mcxtest::MakeVolume(
      VTK_SHORT, Dims, [](int i, int j, int k) { return mcxtest::Phantom(i, j, k, Dims); },
      spacing);
    auto unit = Phantom();
    const Outcome scaled = Project(volume, nullptr, true);
    const Outcome reference = Project(unit, nullptr, true);
    vtkDataArray* a = mcxtest::LineIntegral(scaled.Image);
    vtkDataArray* b = mcxtest::LineIntegral(reference.Image);
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      ASSERT_NEAR(b->GetTuple1(i) * s, a->GetTuple1(i), 1e-9 * (b->GetRange()[1] * s));
    }
    ExpectAgreement(volume, nullptr, s < 1 ? "spacing 1e-6" : "spacing 1e6");
  }
}

TEST(Data, TheReferenceFindsASlabThinnerThanAPixelOrSaysItStoppedShort)
{
  // 10 voxels of 0.01 along U (a slab of about a tenth of a pixel) lie
  // between one ray per pixel and the 3 x 3 of the next step: both images
  // empty, which is no convergence. The exact image carries the volume's
  // integral over the detector, to its estimated error, or warns.
  const double spacing[3] = { 0.01, 1.0, 1.0 };
  auto volume = mcxtest::MakeVolume(
    VTK_SHORT, Dims, [](int i, int j, int k) { return mcxtest::Phantom(i, j, k, Dims); }, spacing);
  const Outcome exact = Project(volume, nullptr, true);
  vtkDataArray* values = mcxtest::LineIntegral(exact.Image);
  double total = 0.0;
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    total += values->GetTuple1(i);
  }
  const double* pixel = exact.Image->GetSpacing();
  const double integral = mcxtest::FieldValue(exact.Image, "Integral");
  const double error = mcxtest::FieldValue(exact.Image, "EstimatedRelativeError");
  ASSERT_GT(integral, 0.0);
  EXPECT_GT(total, 0.0) << "an empty image for a volume in view";
  const bool short_ = error > 1e-4; // Project's tolerance
  EXPECT_EQ(short_, exact.Warnings.find("above its RelativeTolerance") != std::string::npos)
    << error << " " << exact.Warnings;
  if (!short_)
  {
    EXPECT_NEAR(integral, total * pixel[0] * pixel[1], 1e-3 * integral);
  }
  EXPECT_EQ("", exact.Errors);
}

// ---- Types and ranges ------------------------------------------------------

TEST(TypesAndRanges, IntegersAtTheLimitsOfTheirTypes)
{
  const double limits32[] = { static_cast<double>(std::numeric_limits<int>::min()), 0.0,
    static_cast<double>(std::numeric_limits<int>::max()) };
  const long long limits64[] = { std::numeric_limits<long long>::min(), -1, 0,
    std::numeric_limits<long long>::max() };
  auto int32 = mcxtest::MakeVolume(
    VTK_INT, Dims, [&](int i, int j, int k) { return limits32[(i + j + k) % 3]; });
  auto int64 = vtkSmartPointer<vtkImageData>::New();
  int64->SetDimensions(Dims[0], Dims[1], Dims[2]);
  int64->AllocateScalars(VTK_LONG_LONG, 1);
  auto* values = static_cast<long long*>(int64->GetScalarPointer());
  for (vtkIdType n = 0; n < int64->GetNumberOfPoints(); ++n)
  {
    values[n] = limits64[n % 4];
  }
  for (vtkImageData* volume : { int32.Get(), int64.Get() })
  {
    vtkNew<vtkMCXDensityIndex> index;
    index->SetInputData(volume);
    index->Update();
    const vtkIdType levels = index->GetOutput()
                               ->GetFieldData()
                               ->GetArray(vtkMCXTypes::LevelValuesName())
                               ->GetNumberOfTuples();
    EXPECT_EQ(volume == int32.Get() ? 3 : 4, levels);
    // g = 1 where the value is at the maximum of the type, else 0.
    auto tf = Ramp(0.99 * VTK_INT_MAX, 0, VTK_INT_MAX, 1);
    if (volume == int64.Get())
    {
      tf = Ramp(0.99 * 9.2e18, 0, 9.2e18, 1);
    }
    ExpectAgreement(volume, tf, volume == int32.Get() ? "int32 limits" : "int64 limits");
  }
}

TEST(TypesAndRanges, FloatFrom1eMinus30To1e30)
{
  auto volume = mcxtest::MakeVolume(VTK_FLOAT, Dims,
    [](int i, int j, int k)
    { return std::pow(10.0, -30 + 60.0 * ((i + 2 * j + 3 * k) % 13) / 12.0); });
  auto tf = Ramp(0, 0, 1e30, 1);
  const Outcome run = Project(volume, tf, false);
  EXPECT_TRUE(run.Errors.empty()) << run.Errors;
  EXPECT_TRUE(AllFinite(run.Image));
  ExpectAgreement(volume, tf, "1e-30..1e30");
}

TEST(TypesAndRanges, NegativeHounsfieldUnits)
{
  auto volume = mcxtest::MakeVolume(VTK_SHORT, Dims,
    [](int i, int j, int k) { return mcxtest::Phantom(i, j, k, Dims) * 5 - 1024; });
  ExpectAgreement(volume, Ramp(-1024, 0, 1000, 1.5), "HU");
}

// ---- Sample counts ---------------------------------------------------------

TEST(SampleCounts, ZeroAndOneSample)
{
  auto volume = Phantom();
  const Outcome none = Project(volume, nullptr, false, 0);
  EXPECT_EQ(0, mcxtest::FieldValue(none.Image, "SampleCount"));
  EXPECT_EQ(0.0, mcxtest::LineIntegral(none.Image)->GetRange()[1]);
  const Outcome one = Project(volume, nullptr, false, 1);
  EXPECT_EQ(1, mcxtest::FieldValue(one.Image, "SampleCount"));
  const double integral = mcxtest::FieldValue(one.Image, "Integral");
  EXPECT_NEAR(integral, mcxtest::LineIntegralSum(one.Image) * PixelArea(one.Image), 1e-12 * integral);
  vtkDataArray* values = mcxtest::LineIntegral(one.Image);
  int lit = 0;
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    lit += values->GetTuple1(i) > 0 ? 1 : 0;
  }
  EXPECT_EQ(1, lit);
}

// ---- Accumulation ----------------------------------------------------------

TEST(Accumulation, PointsOutsideTheImageAreDiscarded)
{
  // An image covering only the middle of the volume: its pixels agree with
  // the same pixels of the full image (nothing is clamped into edge pixels).
  auto volume = Phantom();
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  double values[2][2];
  for (int crop = 0; crop < 2; ++crop)
  {
    vtkNew<vtkMCXProjector> projector;
    projector->SetInputConnection(index->GetOutputPort());
    projector->SetDetectorAxisU(1, 0, 0);
    projector->SetDetectorAxisV(0, 0, 1);
    projector->SetSampleExponent(16);
    projector->CenterOnVolumeOff();
    projector->SetDetectorCenter(4.5, 3.5);
    projector->SetPixelSpacing(1.0);
    projector->SetImageSize(crop ? 2 : 40, crop ? 2 : 40);
    projector->Update();
    vtkImageData* image = projector->GetOutput();
    const int width = image->GetDimensions()[0];
    const int first = crop ? 0 : 19;
    for (int e = 0; e < 2; ++e)
    {
      values[crop][e] = mcxtest::LineIntegral(image)->GetTuple1((first + e) + width * first);
    }
    if (crop)
    {
      const double integral = mcxtest::FieldValue(image, "Integral");
      EXPECT_LT(mcxtest::LineIntegralSum(image) * PixelArea(image), 0.5 * integral);
    }
  }
  EXPECT_EQ(values[1][0], values[0][0]);
  EXPECT_EQ(values[1][1], values[0][1]);
}

TEST(Accumulation, PointsOnPixelBordersAreBinnedOnceAndDeterministically)
{
  // Points exactly on the borders of a 4 x 4 image of unit pixels over
  // [0, 4) x [0, 4): each lands in the pixel whose lower edges it lies on;
  // points on the image's upper edges (x = 4 or z = 4) are outside.
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int j = 0; j <= 4; ++j)
  {
    for (int i = 0; i <= 4; ++i)
    {
      points->InsertNextPoint(i, 0.5, j);
    }
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<vtkDoubleArray> weight;
  weight->SetName("SampleWeight");
  weight->InsertNextValue(1.0);
  cloud->GetFieldData()->AddArray(weight);
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputData(cloud);
  projector->SetDetectorAxisU(1, 0, 0);
  projector->SetDetectorAxisV(0, 0, 1);
  projector->SetImageSize(4, 4);
  projector->SetPixelSpacing(1.0);
  projector->SetDetectorCenter(2, 2); // pixel (i, j) covers [i, i + 1) x [j, j + 1)
  projector->Update();
  vtkDataArray* values = mcxtest::LineIntegral(projector->GetOutput());
  for (vtkIdType p = 0; p < 16; ++p)
  {
    EXPECT_EQ(1.0, values->GetTuple1(p)) << p;
  }
}

// ---- Perspective -----------------------------------------------------------

TEST(Perspective, CameraInsideTheVolume)
{
  // The eye in the middle of a constant block: samples behind it, on it and
  // before the near plane are dropped; the rest agree with the exact image.
  const int dims[3] = { 16, 16, 16 };
  auto volume = mcxtest::MakeVolume(
    VTK_UNSIGNED_CHAR, dims, [](int i, int j, int k) { return 10 + (i + j + k) % 3; });
  vtkNew<vtkCamera> camera;
  camera->SetPosition(7.5, 7.5, 7.5);
  camera->SetFocalPoint(7.5, 20, 7.5);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(60);
  camera->SetClippingRange(2.0, 100);
  ExpectAgreement(volume, nullptr, "camera inside", camera);
  const Outcome run = Project(volume, nullptr, false, 16, 24, camera);
  EXPECT_TRUE(AllFinite(run.Image));
}

// ---- Long: every sample of M = 2^33 - 1 in one pixel ------------------------

TEST(LongAccumulation, MoreThan2To32SamplesInOnePixelStayExact)
{
  // A 1 x 1 image wider than the volume's support receives all 2^33 - 1
  // samples; a 32-bit count would have wrapped and lost 2^32 of them.
  const int dims[3] = { 4, 4, 4 };
  auto volume = mcxtest::MakeVolume(
    VTK_UNSIGNED_CHAR, dims, [](int i, int j, int k) { return 1 + (i + j + k) % 3; });
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(index->GetOutputPort());
  projector->SetSampleExponent(33);
  projector->SetImageSize(1, 1);
  projector->SetPixelSpacing(100.0);
  projector->Update();
  vtkImageData* image = projector->GetOutput();
  EXPECT_EQ((std::int64_t(1) << 33) - 1,
    static_cast<std::int64_t>(mcxtest::FieldValue(image, "SampleCount")));
  const double integral = mcxtest::FieldValue(image, "Integral");
  EXPECT_NEAR(
    integral, mcxtest::LineIntegral(image)->GetTuple1(0) * PixelArea(image), 1e-12 * integral);
}

// ---- A corrupt index -------------------------------------------------------

TEST(Data, ACorruptIndexIsAnErrorNotACrash)
{
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(Phantom());
  index->Update();
  for (int damage = 0; damage < 3; ++damage)
  {
    vtkNew<vtkImageData> broken;
    broken->DeepCopy(index->GetOutput());
    vtkFieldData* fd = broken->GetFieldData();
    vtkDataArray* offsets = fd->GetArray(vtkMCXTypes::LevelOffsetsName());
    vtkDataArray* ids = fd->GetArray(vtkMCXTypes::SortedVoxelIdsName());
    if (damage == 0)
      offsets->SetTuple1(1, offsets->GetTuple1(2) + 1); // decreasing offsets
    else if (damage == 1)
      ids->SetTuple1(0, 4000000000.0); // an id far outside the volume
    else
      fd->RemoveArray(vtkMCXTypes::LevelValuesName());
    for (bool reference : { false, true })
    {
      vtkSmartPointer<vtkMCXProjectorBase> projector = NewProjector(reference);
      projector->SetInputData(broken);
      projector->SetImageSize(8, 8);
      Messages messages(projector);
      projector->Update();
      if (damage == 1 && !reference)
      {
        // Sampling never dereferences an id: a bad one only moves a point.
        EXPECT_TRUE(messages.Errors.empty()) << messages.Errors;
        continue;
      }
      EXPECT_NE(std::string::npos, messages.Errors.find("Cannot project"))
        << damage << " " << reference;
    }
    if (damage == 1)
    {
      // The view order locates every id before it samples: the bad one
      // falls off the image, and nothing is read past the volume (which a
      // sanitizer build would abort on).
      vtkNew<vtkPiecewiseFunction> flat;
      flat->AddPoint(-1e9, 1.0);
      flat->AddPoint(1e9, 1.0);
      double b[6];
      broken->GetBounds(b);
      vtkNew<vtkCamera> camera;
      camera->SetFocalPoint((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2);
      camera->SetPosition((b[0] + b[1]) / 2, b[2] - 10 * (b[3] - b[2] + 1), (b[4] + b[5]) / 2);
      camera->SetViewUp(0, 0, 1);
      vtkNew<vtkMCXPointSampler> sampler;
      sampler->SetInputData(broken);
      sampler->SetTransferFunction(flat);
      sampler->SetStrategyToViewOrdered();
      sampler->SetSampleExponent(10);
      sampler->SetOrderingView(camera, 8, 8);
      Messages messages(sampler);
      sampler->Update();
      EXPECT_TRUE(messages.Errors.empty()) << messages.Errors;
      EXPECT_EQ(1023, sampler->GetOutput()->GetNumberOfPoints());
    }
  }
}
