// vtkMCXProjector against vtkMCXReferenceProjector: convergence within the
// Monte Carlo bound, conservation of the integral, Halton prefixes,
// perspective views, and bit-identical images for any thread count.
#include "mcxTestHelpers.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXFirstErrorObserver.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"
#include "vtkMCXReferenceProjector.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMCXProjectorBase.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeUInt64Array.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
struct Scene
{
  vtkSmartPointer<vtkImageData> Volume;
  vtkNew<vtkMCXDensityIndex> Index;
  vtkNew<vtkPiecewiseFunction> TF;

  Scene()
  {
    const int dims[3] = { 24, 20, 16 };
    const double spacing[3] = { 1.0, 1.25, 1.5 };
    const double origin[3] = { -12, -12, -12 };
    this->Volume = mcxtest::MakeVolume(
      VTK_SHORT, dims, [&](int i, int j, int k) { return mcxtest::Phantom(i, j, k, dims) - 50; },
      spacing, origin);
    this->Index->SetInputData(this->Volume);
    this->TF->AddPoint(-50, 0);
    this->TF->AddPoint(50, 1);
    this->TF->AddPoint(400, 3);
  }

  template <typename Projector>
  void Configure(Projector* p, vtkCamera* camera, int size)
  {
    p->SetInputConnection(this->Index->GetOutputPort());
    p->SetTransferFunction(this->TF);
    p->SetCamera(camera);
    if (!camera)
    {
      p->SetDetectorAxisU(1, 0, 0);
      p->SetDetectorAxisV(0, 0, 1); // a view along -y
    }
    p->SetImageSize(size, size);
  }

  vtkSmartPointer<vtkImageData> Reference(vtkCamera* camera, int size)
  {
    vtkNew<vtkMCXReferenceProjector> reference;
    this->Configure(reference.Get(), camera, size);
    reference->SetRelativeTolerance(1e-4);
    reference->Update();
    EXPECT_LE(mcxtest::FieldValue(reference->GetOutput(), "EstimatedRelativeError"), 1e-3);
    return reference->GetOutput();
  }

  // The paper's point estimator (these tests hold its binomial bounds).
  vtkSmartPointer<vtkImageData> MonteCarlo(
    vtkCamera* camera, int size, int m, int strategy, vtkTypeUInt64 seed)
  {
    vtkNew<vtkMCXProjector> projector;
    projector->SetDeposit(vtkMCXTypes::POINT);
    this->Configure(projector.Get(), camera, size);
    projector->SetSampleExponent(m);
    projector->SetStrategy(strategy);
    projector->SetSeed(seed);
    projector->Update();
    return projector->GetOutput();
  }
};

vtkSmartPointer<vtkCamera> ObliqueParallelCamera()
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(80, 50, 60);
  camera->SetViewUp(0, 0, 1);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(20);
  return camera;
}

vtkSmartPointer<vtkCamera> PerspectiveCamera()
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(30, -40, 20);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(50);
  camera->SetClippingRange(1, 200);
  return camera;
}

double PixelArea(vtkImageData* image)
{
  return image->GetSpacing()[0] * image->GetSpacing()[1];
}

// Updates the algorithm; the text of the warnings it gave ("" for none).
std::string UpdateKeepingWarnings(vtkAlgorithm* algorithm)
{
  std::string warnings;
  vtkNew<vtkCallbackCommand> onWarning;
  onWarning->SetClientData(&warnings);
  onWarning->SetCallback([](vtkObject*, unsigned long, void* target, void* text)
    { *static_cast<std::string*>(target) += static_cast<const char*>(text); });
  const unsigned long tag = algorithm->AddObserver(vtkCommand::WarningEvent, onWarning);
  algorithm->Update();
  algorithm->RemoveObserver(tag);
  return warnings;
}
}

TEST(Projection, ParallelViewsConvergeWithinTheMonteCarloBound)
{
  Scene scene;
  auto camera = ObliqueParallelCamera();
  for (vtkCamera* view : { static_cast<vtkCamera*>(nullptr), camera.Get() })
  {
    auto reference = scene.Reference(view, 48);
    const double integral = mcxtest::FieldValue(reference, "Integral");
    for (int strategy : { vtkMCXTypes::MONTE_CARLO, vtkMCXTypes::HYBRID,
           vtkMCXTypes::QUASI_MONTE_CARLO })
    {
      for (int m : { 14, 18, 22 })
      {
        auto image = scene.MonteCarlo(view, 48, m, strategy, 1);
        const double bound = mcxtest::ExpectedRelativeRMS(
          reference, integral, PixelArea(reference), std::ldexp(1.0, m) - 1);
        const double error = mcxtest::RelativeRMS(image, reference);
        // The squared error is a sum over ~2000 pixels, so it stays close to its
        // expectation; 1.5x covers its spread plus the reference's own 1e-3.
        EXPECT_LT(error, 1.5 * bound + 1e-3)
          << "strategy " << strategy << " m " << m << (view ? " camera" : " axes");
      }
    }
  }
}

TEST(Projection, HybridIsMoreAccurateThanMonteCarlo)
{
  // Were the Halton voxel choice no better than plain Monte Carlo, each
  // seed's relative RMS error would spread by 1 / sqrt(2 n) (n effective
  // pixels), the mean of 16 seeds by 1 / sqrt(32 n), and the difference of
  // two such means by 1 / (4 sqrt(n)). Hybrid must beat Monte Carlo by four
  // of those, which a projector that ignored the strategy would not. Pixels
  // about 1.5 voxels wide, where the voxel choice is a large part of the
  // variance (at 48 x 48 the kernel offsets dominate and Hybrid gains 4 %).
  Scene scene;
  const int size = 16;
  const int seeds = 16;
  auto reference = scene.Reference(nullptr, size);
  const double n = mcxtest::EffectivePixelCount(mcxtest::ParallelPixelVariances(reference));
  const double margin = 4.0 / (4.0 * std::sqrt(n));
  EXPECT_LT(margin, 0.1);
  for (int m : { 16, 20 })
  {
    double hybrid = 0, plain = 0;
    for (vtkTypeUInt64 seed = 0; seed < seeds; ++seed)
    {
      auto h = scene.MonteCarlo(nullptr, size, m, vtkMCXTypes::HYBRID, seed);
      auto p = scene.MonteCarlo(nullptr, size, m, vtkMCXTypes::MONTE_CARLO, seed);
      EXPECT_GT(mcxtest::RelativeRMS(h, p), 0.0) << "the strategy changes the samples";
      hybrid += mcxtest::RelativeRMS(h, reference) / seeds;
      plain += mcxtest::RelativeRMS(p, reference) / seeds;
    }
    EXPECT_LT(hybrid, (1.0 - margin) * plain) << "m " << m;
  }
}

TEST(Projection, PixelSumTimesAreaIsTheIntegral)
{
  // The default framing covers the whole support, so no sample is lost:
  // nor any of every voxel's weighted points (EVERY_VOXEL), which carry the
  // integral together. Footprints conserve it to 1e-8 (measured: 3e-11; a
  // footprint's phase, rounded at random, may move a sliver of an edge
  // voxel's kernel past the framing, and weighted shares round to 2^-32 of
  // a count per pixel).
  Scene scene;
  for (int strategy : { vtkMCXTypes::HYBRID, vtkMCXTypes::EVERY_VOXEL })
  {
    for (int deposit : { vtkMCXTypes::POINT, vtkMCXTypes::FOOTPRINT })
    {
      vtkNew<vtkMCXProjector> projector;
      projector->SetInputConnection(scene.Index->GetOutputPort());
      projector->SetTransferFunction(scene.TF);
      projector->SetDetectorAxisU(0, 0.6, 0.8);
      projector->SetDetectorAxisV(1, 0, 0);
      projector->SetDefaultImageSize(37);
      projector->SetSampleExponent(18);
      projector->SetStrategy(strategy);
      projector->SetDeposit(deposit);
      projector->Update();
      vtkImageData* image = projector->GetOutput();
      const double sum = mcxtest::LineIntegralSum(image);
      const double integral = mcxtest::FieldValue(image, "Integral");
      const double tolerance = deposit == vtkMCXTypes::FOOTPRINT ? 1e-8 : 1e-12;
      std::cout << "strategy " << strategy << " deposit " << deposit << ": relative loss "
                << 1.0 - sum * PixelArea(image) / integral << std::endl;
      EXPECT_NEAR(integral, sum * PixelArea(image), tolerance * integral)
        << "strategy " << strategy << " deposit " << deposit;
      EXPECT_EQ(37, std::max(image->GetDimensions()[0], image->GetDimensions()[1]));
    }
  }
}

TEST(Projection, EveryVoxelTakesNoTarget)
{
  // Every voxel once leaves no sample count to choose: a target is one
  // error line, and no image.
  Scene scene;
  for (const bool quantization : { false, true })
  {
    vtkNew<vtkMCXProjector> projector;
    scene.Configure(projector.Get(), nullptr, 16);
    projector->SetStrategy(vtkMCXTypes::EVERY_VOXEL);
    projector->SetTargetRelativeError(quantization ? 0.0 : 0.02);
    projector->SetTargetQuantizationLevels(quantization ? 256 : 0);
    vtkNew<vtkMCXFirstErrorObserver> errors;
    errors->ObserveAlgorithm(projector);
    projector->Update();
    errors->StopObserving();
    EXPECT_EQ("Cannot project: every voxel is taken once (Strategy EVERY_VOXEL), so there is no "
              "sample count for TargetRelativeError or TargetQuantizationLevels to choose; set "
              "them to 0.",
      errors->GetErrorText())
      << quantization;
    EXPECT_EQ(0, projector->GetOutput()->GetNumberOfPoints()) << quantization;
  }
}

TEST(Projection, SettingsNoSetterCanClampAreErrors)
{
  // A NaN pixel spacing and a negative size are one error line each and no
  // image (a NaN passed through the clamp and meant "automatic"); the
  // sampler's VIEW_ORDERED is refused by the projector and leaves its
  // strategy as it was (it was clamped to EVERY_VOXEL).
  Scene scene;
  struct Case
  {
    double Spacing;
    int Size[2];
    const char* Expected;
  };
  const Case cases[] = {
    { std::nan(""), { 16, 16 }, "PixelSpacing must be a finite number (0: automatic)." },
    { 0.0, { -1, 5 }, "ImageSize must be 0 (automatic) or positive, not -1 x 5." },
  };
  for (const Case& c : cases)
  {
    vtkNew<vtkMCXProjector> projector;
    scene.Configure(projector.Get(), nullptr, 16);
    projector->SetPixelSpacing(c.Spacing);
    projector->SetImageSize(c.Size[0], c.Size[1]);
    vtkNew<vtkMCXFirstErrorObserver> errors;
    errors->ObserveAlgorithm(projector);
    projector->Update();
    errors->StopObserving();
    EXPECT_EQ(c.Expected, errors->GetErrorText());
    EXPECT_EQ(0, projector->GetOutput()->GetNumberOfPoints()) << c.Expected;
  }
  vtkNew<vtkMCXProjector> projector;
  projector->SetStrategy(vtkMCXTypes::QUASI_MONTE_CARLO);
  vtkNew<vtkMCXFirstErrorObserver> errors;
  errors->ObserveAlgorithm(projector);
  projector->SetStrategy(vtkMCXTypes::VIEW_ORDERED);
  errors->StopObserving();
  EXPECT_EQ("SetStrategy: VIEW_ORDERED sorts a vtkMCXPointSampler's cloud for one view; the "
            "projector's own samples cannot take it, so the strategy stays 2.",
    errors->GetErrorText());
  EXPECT_EQ(vtkMCXTypes::QUASI_MONTE_CARLO, projector->GetStrategy());
  projector->SetStrategy(99);
  EXPECT_EQ(vtkMCXTypes::EVERY_VOXEL, projector->GetStrategy());
}

TEST(Projection, EveryVoxelWarnsWhenItsImageHasRandomParts)
{
  // Every voxel once is exact only with whole footprints: the point
  // deposit's offsets and footprints split past FootprintReach are random,
  // and a warning says so (its error is not estimated).
  Scene scene;
  struct Case
  {
    int Deposit;
    double Reach;
    const char* Expected; // in the warning; nullptr: none
  };
  const Case cases[] = {
    { vtkMCXTypes::FOOTPRINT, 16.0, nullptr },
    { vtkMCXTypes::FOOTPRINT, 0.5, "footprints are split with a random part" },
    { vtkMCXTypes::POINT, 16.0, "the point deposit draws each kernel offset at random" },
  };
  for (const Case& c : cases)
  {
    vtkNew<vtkMCXProjector> projector;
    scene.Configure(projector.Get(), nullptr, 32);
    projector->SetStrategy(vtkMCXTypes::EVERY_VOXEL);
    projector->SetDeposit(c.Deposit);
    projector->SetFootprintReach(c.Reach);
    const std::string warnings = UpdateKeepingWarnings(projector);
    if (c.Expected)
    {
      EXPECT_NE(std::string::npos, warnings.find("Every voxel once, but not without noise: "))
        << warnings;
      EXPECT_NE(std::string::npos, warnings.find(c.Expected)) << warnings;
    }
    else
    {
      EXPECT_EQ("", warnings);
    }
    EXPECT_GT(mcxtest::LineIntegralSum(projector->GetOutput()), 0.0) << c.Deposit << " " << c.Reach;
  }
}

TEST(Projection, HaltonPrefixHasTheErrorOfItsOwnSize)
{
  Scene scene;
  auto reference = scene.Reference(nullptr, 48);
  const double integral = mcxtest::FieldValue(reference, "Integral");
  vtkNew<vtkMCXPointSampler> sampler;
  sampler->SetInputConnection(scene.Index->GetOutputPort());
  sampler->SetTransferFunction(scene.TF);
  sampler->SetSampleExponent(20);
  sampler->SetDeposit(vtkMCXTypes::POINT); // sample positions, copied without the field data
  sampler->Update();
  vtkPolyData* cloud = sampler->GetOutput();
  for (int k : { 12, 16, 20 })
  {
    const vtkIdType count = (vtkIdType(1) << k) - 1;
    vtkNew<vtkPoints> prefix;
    prefix->SetDataType(VTK_FLOAT);
    prefix->SetNumberOfPoints(count);
    for (vtkIdType i = 0; i < count; ++i)
    {
      prefix->SetPoint(i, cloud->GetPoint(i));
    }
    vtkNew<vtkPolyData> part;
    part->SetPoints(prefix);
    vtkNew<vtkDoubleArray> weight;
    weight->SetName("SampleWeight");
    weight->InsertNextValue(integral / count);
    part->GetFieldData()->AddArray(weight);
    vtkNew<vtkMCXProjector> projector;
    projector->SetInputData(part);
    projector->SetDetectorAxisU(1, 0, 0);
    projector->SetDetectorAxisV(0, 0, 1);
    projector->SetImageSize(48, 48);
    projector->SetPixelSpacing(reference->GetSpacing()[0]);
    projector->SetDetectorCenter(reference->GetOrigin()[0] + 23.5 * reference->GetSpacing()[0],
      reference->GetOrigin()[1] + 23.5 * reference->GetSpacing()[1]);
    projector->Update();
    vtkImageData* image = projector->GetOutput();
    // Same framing as the reference, and the error of a count-sample run.
    EXPECT_NEAR(reference->GetOrigin()[0], image->GetOrigin()[0], 1e-9);
    const double bound = mcxtest::ExpectedRelativeRMS(
      reference, integral, PixelArea(reference), static_cast<double>(count));
    const double error = mcxtest::RelativeRMS(image, reference);
    EXPECT_LT(error, 1.5 * bound + 1e-3) << "prefix 2^" << k << " - 1";
    EXPECT_GT(error, 0.3 * bound) << "prefix 2^" << k << " - 1"; // and not a larger sample
  }
}

TEST(Projection, PerspectiveViewConvergesWithinItsBound)
{
  // The bound of a perspective image comes from the weights f = D^2 s / z^3
  // of the samples themselves (their second moment, measured on a cloud of
  // the same distribution with VTK's own projection), not from their largest
  // value, so a wrong weight cannot hide inside it.
  Scene scene;
  auto camera = PerspectiveCamera();
  const int size = 40;
  auto reference = scene.Reference(camera, size);
  const double integral = mcxtest::FieldValue(reference, "Integral");
  const double area = PixelArea(reference);
  const mcxtest::WeightMoments moments =
    mcxtest::MeasureSampledWeights(scene.Index->GetOutputPort(), scene.TF, camera, size, size);
  const int exponent = 22;
  const double m = std::ldexp(1.0, exponent) - 1;
  const double bound =
    mcxtest::ExpectedRelativeRMSOfWeights(reference, integral, area, m, moments.MeanSquare);
  // The squared error sums ~1000 effective pixels (relative spread sqrt(2 /
  // n) < 5 %): 1.25 covers it, the bound's neglect of the squared mean and
  // the reference's 1e-3.
  const double spread =
    1.0 / std::sqrt(2.0 * mcxtest::EffectivePixelCount(moments.PixelMeanSquare));
  EXPECT_LT(spread, 0.05);

  // Off-axis rings: the ray through a pixel centre at angle theta from the
  // axis; the weight's s / z factor is 1 / cos(theta) there. The ring sum
  // S = A sum I over its pixels has variance at most W^2 E[f^2 1{ring}] / M.
  const double tanHalf = std::tan(vtkMath::RadiansFromDegrees(25.0));
  auto ringOf = [&](int i, int j)
  {
    const double x = (2.0 * (i + 0.5) / size - 1.0) * tanHalf;
    const double y = (2.0 * (j + 0.5) / size - 1.0) * tanHalf;
    const double degrees = vtkMath::DegreesFromRadians(std::atan(std::sqrt(x * x + y * y)));
    return degrees < 8 ? -1 : (degrees < 14 ? 0 : 1);
  };
  for (int strategy : { vtkMCXTypes::MONTE_CARLO, vtkMCXTypes::HYBRID })
  {
    auto image = scene.MonteCarlo(camera, size, exponent, strategy, 3);
    const double error = mcxtest::RelativeRMS(image, reference);
    EXPECT_LT(error, 1.25 * bound + 1e-3) << "strategy " << strategy;
    EXPECT_GT(error, 0.3 * bound) << "strategy " << strategy; // an image of M samples
    double estimated[2] = { 0, 0 }, exact[2] = { 0, 0 }, meanSquare[2] = { 0, 0 }, total = 0;
    vtkDataArray* a = mcxtest::LineIntegral(image);
    vtkDataArray* b = mcxtest::LineIntegral(reference);
    for (int j = 0; j < size; ++j)
    {
      for (int i = 0; i < size; ++i)
      {
        const int ring = ringOf(i, j);
        total += area * b->GetTuple1(i + size * j);
        if (ring >= 0)
        {
          estimated[ring] += area * a->GetTuple1(i + size * j);
          exact[ring] += area * b->GetTuple1(i + size * j);
          meanSquare[ring] += moments.PixelMeanSquare[i + size * j];
        }
      }
    }
    for (int ring = 0; ring < 2; ++ring)
    {
      // Five standard deviations (two-sided 6e-7), the reference's 1e-4 and
      // the moment's own sampling error (a few percent of the deviation).
      const double deviation = integral * std::sqrt(meanSquare[ring] / m);
      ASSERT_GT(exact[ring], 0.02 * total) << "ring " << ring;
      EXPECT_NEAR(exact[ring], estimated[ring], 5.5 * deviation + 1e-4 * exact[ring])
        << "strategy " << strategy << " ring " << ring;
    }
  }
}

TEST(Projection, ImagesAreBitIdenticalForOneAndTwoThreads)
{
  Scene scene;
  auto perspective = PerspectiveCamera();
  for (vtkCamera* camera : { static_cast<vtkCamera*>(nullptr), perspective.Get() })
  {
    vtkSmartPointer<vtkImageData> one, two;
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ 1 },
      [&]() { one = scene.MonteCarlo(camera, 64, 20, vtkMCXTypes::HYBRID, 9); });
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ 2 },
      [&]() { two = scene.MonteCarlo(camera, 64, 20, vtkMCXTypes::HYBRID, 9); });
    vtkDataArray* a = mcxtest::LineIntegral(one);
    vtkDataArray* b = mcxtest::LineIntegral(two);
    ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples());
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      ASSERT_EQ(a->GetTuple1(i), b->GetTuple1(i)) << i;
    }
  }
}

TEST(Projection, ConstantSlabHasAnalyticLineIntegrals)
{
  // A constant c on 8 x 6 x 10 voxels of spacing (2, 3, 0.5): a ray along z
  // through the interior sees c * nz * sz for both kernels (the tent's ramps
  // at both ends add up to one spacing).
  const int dims[3] = { 8, 6, 10 };
  const double spacing[3] = { 2, 3, 0.5 };
  auto volume = mcxtest::MakeVolume(
    VTK_UNSIGNED_SHORT, dims, [](int, int, int) { return 4.0; }, spacing);
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(volume);
  for (int kernel : { vtkMCXTypes::TENT, vtkMCXTypes::BOX })
  {
    vtkNew<vtkMCXReferenceProjector> reference;
    reference->SetInputConnection(index->GetOutputPort());
    reference->SetKernel(kernel);
    reference->SetImageSize(4, 3);
    reference->SetPixelSpacing(1.0);
    reference->Update();
    vtkImageData* image = reference->GetOutput();
    // Pixels centred on x in 5.5..8.5, y in 6.5..8.5: all inside the interior.
    vtkDataArray* values = mcxtest::LineIntegral(image);
    for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    {
      EXPECT_NEAR(4.0 * 10 * 0.5, values->GetTuple1(i), 1e-12);
    }
    EXPECT_NEAR(7.0, image->GetOrigin()[0] + 1.5, 1e-12);
    EXPECT_NEAR(7.5, image->GetOrigin()[1] + 1.0, 1e-12);
  }
}

namespace
{
// Passes its input image on but, like ParaView's input post filter
// (vtkPVPostFilter) and VTK 9.1's default information, leaves the
// DIRECTION key out of its output information.
class DirectionDroppingFilter : public vtkImageAlgorithm
{
public:
  static DirectionDroppingFilter* New();
  vtkTypeMacro(DirectionDroppingFilter, vtkImageAlgorithm);

protected:
  int RequestInformation(vtkInformation*, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override
  {
    vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
    vtkInformation* outInfo = outputVector->GetInformationObject(0);
    outInfo->CopyEntry(inInfo, vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
    outInfo->CopyEntry(inInfo, vtkDataObject::ORIGIN());
    outInfo->CopyEntry(inInfo, vtkDataObject::SPACING());
    outInfo->Remove(vtkDataObject::DIRECTION());
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override
  {
    vtkImageData::GetData(outputVector)->ShallowCopy(vtkImageData::GetData(inputVector[0]));
    return 1;
  }
};
vtkStandardNewMacro(DirectionDroppingFilter);
}

TEST(Projection, TheVolumeFramesTheImageWhereTheDataPlaceIt)
{
  // A volume turned by its direction matrix (x and y reversed, as a NIfTI
  // volume in LPS), its information stripped of DIRECTION on the way to
  // the index (ParaView inserts such a filter before every input): the
  // image is still framed on the volume, the same bit for bit as with the
  // full information, for the fused projector, a stored cloud and the exact
  // one. (Framed from the information alone, 21 of its 24 columns were
  // empty.)
  Scene scene;
  const double flip[9] = { -1, 0, 0, 0, -1, 0, 0, 0, 1 };
  scene.Volume->SetDirectionMatrix(flip);
  scene.Volume->SetOrigin(40, 30, -12);
  vtkNew<DirectionDroppingFilter> dropping;
  dropping->SetInputData(scene.Volume);
  vtkNew<vtkMCXDensityIndex> strippedIndex;
  strippedIndex->SetInputConnection(dropping->GetOutputPort());
  strippedIndex->UpdateInformation();
  ASSERT_FALSE(strippedIndex->GetOutputInformation(0)->Has(vtkDataObject::DIRECTION()));
  auto sampler = [&](vtkAlgorithm* index)
  {
    auto cloud = vtkSmartPointer<vtkMCXPointSampler>::New();
    cloud->SetInputConnection(index->GetOutputPort());
    cloud->SetTransferFunction(scene.TF);
    cloud->SetSampleExponent(14);
    return cloud;
  };
  auto fullCloud = sampler(scene.Index);
  auto strippedCloud = sampler(strippedIndex);
  for (int kind = 0; kind < 3; ++kind)
  {
    vtkSmartPointer<vtkImageData> images[2];
    for (int stripped = 0; stripped < 2; ++stripped)
    {
      vtkAlgorithm* index = stripped ? strippedIndex.Get() : scene.Index.Get();
      vtkSmartPointer<vtkMCXProjectorBase> projector;
      if (kind == 2)
      {
        auto exact = vtkSmartPointer<vtkMCXReferenceProjector>::New();
        exact->SetRelativeTolerance(1e-2);
        projector = exact;
      }
      else
      {
        auto monteCarlo = vtkSmartPointer<vtkMCXProjector>::New();
        monteCarlo->SetSampleExponent(14);
        projector = monteCarlo;
      }
      scene.Configure(projector.Get(), nullptr, 24);
      projector->SetInputConnection(kind == 1
          ? (stripped ? strippedCloud : fullCloud)->GetOutputPort()
          : index->GetOutputPort());
      projector->Update();
      images[stripped] = projector->GetOutput();
    }
    vtkDataArray* a = mcxtest::LineIntegral(images[0]);
    vtkDataArray* b = mcxtest::LineIntegral(images[1]);
    ASSERT_NE(nullptr, b) << "kind " << kind;
    for (vtkDataArray* values : { a, b })
    {
      int emptyColumns = 0;
      for (int column = 0; column < 24; ++column)
      {
        double sum = 0;
        for (int row = 0; row < 24; ++row)
        {
          sum += values->GetTuple1(row * 24 + column);
        }
        emptyColumns += sum == 0 ? 1 : 0;
      }
      EXPECT_EQ(0, emptyColumns) << "kind " << kind << (values == b ? " stripped" : " full");
    }
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      ASSERT_EQ(a->GetTuple1(i), b->GetTuple1(i)) << "kind " << kind << " pixel " << i;
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      EXPECT_EQ(images[0]->GetOrigin()[axis], images[1]->GetOrigin()[axis]) << "kind " << kind;
      EXPECT_EQ(images[0]->GetSpacing()[axis], images[1]->GetSpacing()[axis]) << "kind " << kind;
    }
  }
}

TEST(Projection, WideVoxelIdsGiveTheSameImage)
{
  // 64-bit ids (the path of volumes above 2^32 voxels) must change nothing.
  for (int strategy : { vtkMCXTypes::HYBRID, vtkMCXTypes::EVERY_VOXEL })
  {
    Scene scene;
    auto narrow = scene.MonteCarlo(nullptr, 32, 16, strategy, 2);
    scene.Index->AlwaysUseWideIdsOn();
    auto wide = scene.MonteCarlo(nullptr, 32, 16, strategy, 2);
    ASSERT_NE(nullptr,
      vtkTypeUInt64Array::SafeDownCast(scene.Index->GetOutput()->GetFieldData()->GetArray(
        vtkMCXTypes::SortedVoxelIdsName())));
    vtkDataArray* a = mcxtest::LineIntegral(narrow);
    vtkDataArray* b = mcxtest::LineIntegral(wide);
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      ASSERT_EQ(a->GetTuple1(i), b->GetTuple1(i)) << "strategy " << strategy;
    }
  }
}

TEST(Projection, ErrorEstimateTracksTheTrueError)
{
  // The estimate from the two half images against the error measured with
  // the exact reference. For independent halves (Monte Carlo) the half
  // difference D and the error S of the whole are uncorrelated in each pixel
  // with the same variance v, so estimate^2 / truth^2 = sum D^2 / sum S^2 is
  // a ratio of two independent sums whose logarithms spread by sqrt(2 / n)
  // each (n = (sum v)^2 / sum v^2 effective pixels): log(estimate / truth)
  // spreads by 1 / sqrt(n), and 4.5 of those bound it. Hybrid and QMC
  // halves are stratified alike: the whole converges faster than its
  // halves, so the estimate may only err on the safe side (no lower), and it
  // never claims more than plain Monte Carlo's error of the same size.
  Scene scene;
  auto camera = ObliqueParallelCamera();
  const int size = 64;
  auto reference = scene.Reference(camera, size);
  const double integral = mcxtest::FieldValue(reference, "Integral");
  const double n = mcxtest::EffectivePixelCount(mcxtest::ParallelPixelVariances(reference));
  const double window = std::exp(4.5 / std::sqrt(n));
  // Narrow enough that an estimate sqrt(2) too small fails.
  EXPECT_LT(window * window, std::sqrt(2.0));
  for (int strategy : { vtkMCXTypes::MONTE_CARLO, vtkMCXTypes::HYBRID,
         vtkMCXTypes::QUASI_MONTE_CARLO })
  {
    for (int m : { 14, 18, 22 })
    {
      auto image = scene.MonteCarlo(camera, size, m, strategy, 4);
      const double truth = mcxtest::RelativeRMS(image, reference);
      const double estimate = mcxtest::FieldValue(image, "EstimatedRelativeError");
      const double monteCarlo = mcxtest::ExpectedRelativeRMS(
        reference, integral, PixelArea(reference), std::ldexp(1.0, m) - 1);
      EXPECT_GT(estimate, truth / window) << "strategy " << strategy << " m " << m;
      if (strategy == vtkMCXTypes::MONTE_CARLO)
      {
        EXPECT_LT(estimate, truth * window) << "m " << m;
      }
      else
      {
        EXPECT_LT(estimate, monteCarlo * window) << "strategy " << strategy << " m " << m;
      }
    }
  }
}

TEST(Projection, PerspectiveErrorEstimateTracksTheTrueError)
{
  // As above for a perspective view, whose pixel variances W^2 E[f^2
  // 1{pixel}] / (A^2 M) come from the samples' measured weights.
  Scene scene;
  auto camera = PerspectiveCamera();
  const int size = 80;
  auto reference = scene.Reference(camera, size);
  const mcxtest::WeightMoments moments =
    mcxtest::MeasureSampledWeights(scene.Index->GetOutputPort(), scene.TF, camera, size, size);
  const double window =
    std::exp(4.5 / std::sqrt(mcxtest::EffectivePixelCount(moments.PixelMeanSquare)));
  EXPECT_LT(window * window, std::sqrt(2.0));
  for (int m : { 14, 18, 22 })
  {
    auto image = scene.MonteCarlo(camera, size, m, vtkMCXTypes::MONTE_CARLO, 6);
    const double truth = mcxtest::RelativeRMS(image, reference);
    const double estimate = mcxtest::FieldValue(image, "EstimatedRelativeError");
    EXPECT_GT(estimate, truth / window) << "m " << m;
    EXPECT_LT(estimate, truth * window) << "m " << m;
  }
}

TEST(Projection, ATargetsImageIsTheFixedRunOfItsSampleCountBitForBit)
{
  // The target control keeps the samples of its pilot and of each re-check
  // and draws only the rest (the first 2^j - 1 samples of a run are the
  // 2^j - 1 run): its image must be, bit for bit, the image of one run of
  // the count it chose, for every strategy and both deposits.
  Scene scene;
  for (int strategy :
    { vtkMCXTypes::HYBRID, vtkMCXTypes::MONTE_CARLO, vtkMCXTypes::QUASI_MONTE_CARLO })
  {
    for (int deposit : { vtkMCXTypes::POINT, vtkMCXTypes::FOOTPRINT })
    {
      vtkNew<vtkMCXProjector> targeted;
      scene.Configure(targeted.Get(), nullptr, 48);
      targeted->SetStrategy(strategy);
      targeted->SetDeposit(deposit);
      // Past the pilot of 65535 samples (about 1 % on this scene's point deposit).
      targeted->SetTargetRelativeError(deposit == vtkMCXTypes::POINT ? 0.004 : 0.002);
      targeted->Update();
      const double samples = mcxtest::FieldValue(targeted->GetOutput(), "SampleCount");
      ASSERT_GT(samples, 65535.0); // more than the pilot: at least one extension
      vtkNew<vtkMCXProjector> fixed;
      scene.Configure(fixed.Get(), nullptr, 48);
      fixed->SetStrategy(strategy);
      fixed->SetDeposit(deposit);
      fixed->SetSampleExponent(static_cast<int>(std::lround(std::log2(samples + 1))));
      fixed->Update();
      EXPECT_EQ(0.0, mcxtest::RelativeRMS(targeted->GetOutput(), fixed->GetOutput()))
        << "strategy " << strategy << ", deposit " << deposit;
      EXPECT_EQ(mcxtest::FieldValue(fixed->GetOutput(), "EstimatedRelativeError"),
        mcxtest::FieldValue(targeted->GetOutput(), "EstimatedRelativeError"))
        << "strategy " << strategy << ", deposit " << deposit;
    }
  }
}

TEST(Projection, TargetAccuracyControlsChooseEnoughSamples)
{
  Scene scene;
  auto reference = scene.Reference(nullptr, 48);
  for (double target : { 0.05, 0.01 })
  {
    vtkNew<vtkMCXProjector> projector;
    scene.Configure(projector.Get(), nullptr, 48);
    projector->SetTargetRelativeError(target);
    projector->SetSampleExponent(target > 0.02 ? 0 : 2); // ignored under a target, 0 too
    projector->Update();
    vtkImageData* image = projector->GetOutput();
    const double samples = mcxtest::FieldValue(image, "SampleCount");
    EXPECT_GE(samples, 65535.0);
    // The promise: the true error meets the target (2% slack for the
    // pilot's own estimate) with at most 4 times the samples it needs (one
    // power of two of rounding, one of M^-1/2 extrapolation).
    EXPECT_LT(mcxtest::RelativeRMS(image, reference), 1.02 * target) << target;
    const double integral = mcxtest::FieldValue(reference, "Integral");
    const double needed = std::pow(
      mcxtest::ExpectedRelativeRMS(reference, integral, PixelArea(reference), 1.0) / target, 2);
    EXPECT_LT(samples, 4.0 * needed) << target;
  }
  // The paper's criterion for 256 grey levels: M > (W H - 1) B^2 L^2.
  vtkNew<vtkMCXProjector> projector;
  scene.Configure(projector.Get(), nullptr, 48);
  projector->SetTargetQuantizationLevels(16);
  projector->Update();
  vtkImageData* image = projector->GetOutput();
  vtkDataArray* values = mcxtest::LineIntegral(image);
  double mean = 0;
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    mean += values->GetTuple1(i) / values->GetNumberOfTuples();
  }
  const double brightness = mean / values->GetRange()[1];
  const double criterion = (48.0 * 48.0 - 1) * brightness * brightness * 16 * 16;
  EXPECT_GT(mcxtest::FieldValue(image, "SampleCount"), 0.9 * criterion);
  EXPECT_LT(mcxtest::FieldValue(image, "SampleCount"), 2.2 * criterion);
}

TEST(Projection, ATargetThatTheLargestSampleCountMissesIsWarnedOf)
{
  // A target the run cannot reach within 2^MaximumSampleExponent - 1
  // samples ends with that many and a warning naming both; one it reaches,
  // or one within its last count, warns of nothing.
  Scene scene;
  struct Case
  {
    double Error;
    int Levels;
    int Maximum;
    const char* Expected; // nullptr: no warning
  };
  const Case cases[] = {
    { 1e-4, 0, 16,
      "The target relative error 0.0001 is not met: the error estimated at 2^16 - 1 "
      "samples, the most MaximumSampleExponent allows, is " },
    { 0, 4096, 16, "The target of 4096 quantization levels is not met: it asks for " },
    { 0.05, 0, 30, nullptr },
    { 0, 16, 30, nullptr },
  };
  for (const Case& c : cases)
  {
    vtkNew<vtkMCXProjector> projector;
    scene.Configure(projector.Get(), nullptr, 48);
    projector->SetTargetRelativeError(c.Error);
    projector->SetTargetQuantizationLevels(c.Levels);
    projector->SetMaximumSampleExponent(c.Maximum);
    const std::string warnings = UpdateKeepingWarnings(projector);
    const double samples = mcxtest::FieldValue(projector->GetOutput(), "SampleCount");
    if (c.Expected)
    {
      EXPECT_EQ(65535.0, samples);
      EXPECT_NE(std::string::npos, warnings.find(c.Expected)) << warnings;
    }
    else
    {
      EXPECT_LT(samples, 1073741823.0);
      EXPECT_EQ("", warnings) << c.Error << " " << c.Levels;
    }
  }
}
