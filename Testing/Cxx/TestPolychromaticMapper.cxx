// vtkMCXXRayMapper's polychromatic mode: each material channel on screen is
// vtkMCXProjector's image of vtkMCXMaterialWeights's cloud for the same
// camera, bit for bit; the image is mcx::PolychromaticModel applied to the
// channels; a spectrum or detector change maps the same channels again
// (no restart, no sampling, the same count); a materials change samples
// again; a density index input (ParaView's) gives the volume's channels;
// clearing the spectrum gives the monochromatic image bit for bit; what
// cannot be polychromatic is refused in one line.
#include "mcxMaterialDecomposition.h"
#include "mcxPolychromaticModel.h"
#include "mcxTestHelpers.h"
#include "mcxTubeSpectrum.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXFirstErrorObserver.h"
#include "vtkMCXMaterialWeights.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"
#include "vtkMCXXRayMapper.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

namespace
{
constexpr int N = 40;        // voxels per side, 1 mm
constexpr int Size = 48;     // pixels per side
constexpr int Exponent = 18; // 2^18 - 1 points

// Air around a soft-tissue cylinder along y holding a bone core and a fat
// slab: every default material has voxels.
double HU(int i, int j, int k)
{
  const double dx = i - 19.5, dz = k - 19.5;
  const double r2 = dx * dx + dz * dz;
  if (j < 4 || j >= 36 || r2 > 16.0 * 16.0)
  {
    return -1000.0;
  }
  if (r2 <= 5.0 * 5.0)
  {
    return 1200.0 + 20.0 * (j % 5); // bone, several HU
  }
  return i < 12 ? -100.0 : 40.0;
}

std::vector<double> Values(vtkImageData* image)
{
  vtkDataArray* values = image->GetPointData()->GetScalars();
  std::vector<double> out(static_cast<std::size_t>(values ? values->GetNumberOfTuples() : 0));
  for (std::size_t p = 0; p < out.size(); ++p)
  {
    out[p] = values->GetTuple1(static_cast<vtkIdType>(p));
  }
  return out;
}

std::vector<double> LineIntegrals(vtkMCXXRayMapper* mapper)
{
  vtkNew<vtkImageData> image;
  mapper->GetLineIntegralImage(image);
  return Values(image);
}

std::vector<std::vector<double>> Channels(vtkMCXXRayMapper* mapper)
{
  std::vector<std::vector<double>> channels(mapper->GetNumberOfChannels());
  for (int m = 0; m < mapper->GetNumberOfChannels(); ++m)
  {
    vtkNew<vtkImageData> image;
    mapper->GetChannelImage(m, image);
    channels[m] = Values(image);
  }
  return channels;
}

// -ln T of the channels (g/cm^3 x mm) through the model of these texts.
std::vector<double> Model(const std::vector<std::vector<double>>& channels,
  const std::string& spectrum, const std::string& detector)
{
  const mcx::PolychromaticModel model(mcx::SpectrumFromText(spectrum), mcx::ParseDetector(detector),
    mcx::MaterialsFromText("default").Names());
  std::vector<double> out(channels.empty() ? 0 : channels[0].size());
  std::vector<double> l(channels.size());
  for (std::size_t p = 0; p < out.size(); ++p)
  {
    for (std::size_t m = 0; m < channels.size(); ++m)
    {
      l[m] = 0.1 * channels[m][p];
    }
    out[p] = model.EffectiveLineIntegral(l.data());
  }
  return out;
}

// The largest |a - b| over the largest |b|.
double RelativeDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double largest = 0.0, difference = 0.0;
  for (std::size_t p = 0; p < a.size() && p < b.size(); ++p)
  {
    largest = std::max(largest, std::fabs(b[p]));
    difference = std::max(difference, std::fabs(a[p] - b[p]));
  }
  return a.size() == b.size() && largest > 0 ? difference / largest : HUGE_VAL;
}

double Mean(const std::vector<double>& values)
{
  double sum = 0.0;
  for (double v : values)
  {
    sum += v;
  }
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

// The volume viewed along +z by a parallel camera, the mapper given the
// volume (or its density index) at 70 kVp.
struct Scene
{
  vtkSmartPointer<vtkImageData> Volume;
  vtkNew<vtkMCXXRayMapper> Mapper;
  vtkNew<vtkVolume> Prop;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;

  Scene()
  {
    const int dims[3] = { N, N, N };
    this->Volume = mcxtest::MakeVolume(VTK_SHORT, dims, HU);
    this->Mapper->SetInputData(this->Volume);
    this->Mapper->SetSampleExponent(Exponent);
    this->Mapper->ProgressiveRefinementOff();
    this->Mapper->SetSpectrum("70kVp,2.5mmAl");
    this->Prop->SetMapper(this->Mapper);
    this->Renderer->AddVolume(this->Prop);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(Size, Size);
    this->Window->AddRenderer(this->Renderer);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetFocalPoint(19.5, 19.5, 19.5);
    camera->SetPosition(19.5, 19.5, -200);
    camera->SetViewUp(0, 1, 0);
    camera->SetParallelScale(22);
    this->Renderer->ResetCameraClippingRange();
  }
};

// What vtkMCXProjector makes of channel m of the cloud the sampler draws
// under the default materials' density, for the scene's camera.
std::vector<double> ProjectedChannel(Scene& scene, int m)
{
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(scene.Volume);
  vtkNew<vtkMCXMaterialWeights> weights;
  vtkNew<vtkPiecewiseFunction> density;
  EXPECT_TRUE(weights->FillDensityFunction(density));
  vtkNew<vtkMCXPointSampler> sampler;
  sampler->SetInputConnection(index->GetOutputPort());
  sampler->SetTransferFunction(density);
  sampler->SetSampleExponent(Exponent);
  sampler->SetDepositToFootprint();
  weights->SetInputConnection(sampler->GetOutputPort());
  weights->SetInputData(1, scene.Volume);
  weights->SetChannel(m);
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(weights->GetOutputPort());
  projector->SetCamera(scene.Renderer->GetActiveCamera());
  projector->SetImageSize(Size, Size);
  projector->Update();
  return Values(projector->GetOutput());
}
}

TEST(PolychromaticMapper, ChannelsAreTheProjectorsAndTheImageIsTheModel)
{
  // The mapper splits each deposit of the one cloud into the channels: they
  // add up to the projector's image of the cloud (every weight 1), and each
  // is the projector's image of the cloud weighed by that material's
  // fractions but for rounding: a split part (the floor of the fraction of
  // the footprint table's integer increment) and the weighted deposit's
  // increment (round(2^32 x fraction x share)) differ by less than 2.5 in
  // 2^32 of one whole deposit, u, in each pixel a deposit reaches; at most
  // M deposits reach a pixel, and the image holds about M u in all, so a
  // pixel differs by less than 2.5 x 2^-32 of the image's sum.
  Scene scene;
  scene.Window->Render();
  vtkMCXXRayMapper* mapper = scene.Mapper;
  ASSERT_EQ(mapper->GetNumberOfChannels(), 4);
  EXPECT_TRUE(mapper->IsRefinementComplete());
  const std::vector<std::vector<double>> channels = Channels(mapper);
  const std::vector<double> total = ProjectedChannel(scene, -1);
  ASSERT_EQ(total.size(), static_cast<std::size_t>(Size * Size));
  const double largest = *std::max_element(total.begin(), total.end());
  ASSERT_GT(largest, 0.0);
  const double rounding = 2.5 * std::ldexp(std::accumulate(total.begin(), total.end(), 0.0), -32);
  for (std::size_t p = 0; p < total.size(); ++p)
  {
    double sum = 0.0;
    for (const std::vector<double>& channel : channels)
    {
      sum += channel[p];
    }
    ASSERT_LE(std::fabs(sum - total[p]), 1e-12 * largest) << "pixel " << p;
  }
  for (int m = 0; m < 4; ++m)
  {
    const std::vector<double> projected = ProjectedChannel(scene, m);
    ASSERT_EQ(projected.size(), total.size());
    for (std::size_t p = 0; p < total.size(); ++p)
    {
      ASSERT_LE(std::fabs(channels[m][p] - projected[p]), rounding + 1e-12 * largest)
        << "channel " << m << ", pixel " << p;
    }
    EXPECT_GT(Mean(channels[m]), 0.0) << "channel " << m;
  }
  const std::vector<double> shown = LineIntegrals(mapper);
  EXPECT_LT(RelativeDifference(shown, Model(channels, "70kVp,2.5mmAl", "integrating")), 1e-12);
  EXPECT_GT(mapper->GetEstimatedRelativeError(), 0.0);
  EXPECT_LT(mapper->GetEstimatedRelativeError(), 0.1);
}

TEST(PolychromaticMapper, ASpectrumOrDetectorChangeMapsTheSameChannelsAgain)
{
  Scene scene;
  vtkMCXXRayMapper* mapper = scene.Mapper;
  scene.Window->Render();
  const std::vector<std::vector<double>> channels = Channels(mapper);
  const std::vector<double> at70 = LineIntegrals(mapper);
  const vtkTypeInt64 restarts = mapper->GetNumberOfRestarts();
  const vtkTypeInt64 refinements = mapper->GetNumberOfRefinements();
  const vtkTypeInt64 uploads = mapper->GetNumberOfUploads();
  const vtkTypeInt64 count = mapper->GetNumberOfAccumulatedSamples();
  const vtkMTimeType sampled = mapper->GetPointSampler()->GetOutput()->GetMTime();

  mapper->SetSpectrum("120kVp,2.5mmAl");
  scene.Window->Render();
  EXPECT_EQ(mapper->GetNumberOfRestarts(), restarts);
  EXPECT_EQ(mapper->GetNumberOfRefinements(), refinements);
  EXPECT_EQ(mapper->GetNumberOfAccumulatedSamples(), count);
  EXPECT_EQ(mapper->GetPointSampler()->GetOutput()->GetMTime(), sampled);
  EXPECT_EQ(mapper->GetNumberOfUploads(), uploads + 1);
  EXPECT_TRUE(Channels(mapper) == channels);
  const std::vector<double> at120 = LineIntegrals(mapper);
  EXPECT_LT(RelativeDifference(at120, Model(channels, "120kVp,2.5mmAl", "integrating")), 1e-12);
  // The harder beam attenuates less.
  EXPECT_LT(Mean(at120), 0.9 * Mean(at70));

  mapper->SetDetector("counting,CsI:0.6:4.51");
  scene.Window->Render();
  EXPECT_EQ(mapper->GetNumberOfRestarts(), restarts);
  EXPECT_EQ(mapper->GetNumberOfAccumulatedSamples(), count);
  EXPECT_EQ(mapper->GetPointSampler()->GetOutput()->GetMTime(), sampled);
  EXPECT_LT(RelativeDifference(
              LineIntegrals(mapper), Model(channels, "120kVp,2.5mmAl", "counting,CsI:0.6:4.51")),
    1e-12);
  EXPECT_NE(LineIntegrals(mapper), at120);

  // Other materials: another density curve, sampled again.
  mapper->SetMaterials("default,iodine=100");
  scene.Window->Render();
  EXPECT_EQ(mapper->GetNumberOfRestarts(), restarts + 1);
  EXPECT_GT(mapper->GetPointSampler()->GetOutput()->GetMTime(), sampled);
  EXPECT_EQ(mapper->GetNumberOfChannels(), 5);
}

TEST(PolychromaticMapper, ProgressiveRefinementEndsAtTheImageOfAllPoints)
{
  // Frames of a small time budget add prefixes to every channel; the sums are
  // exact, so the last frame is the image of all points drawn at once.
  Scene all;
  all.Window->Render();
  Scene progressive;
  vtkMCXXRayMapper* mapper = progressive.Mapper;
  mapper->ProgressiveRefinementOn();
  mapper->SetInitialSampleExponent(10);
  mapper->SetMaximumRenderTime(1e-6);
  int frames = 0;
  while (!mapper->IsRefinementComplete() && frames < 100)
  {
    progressive.Window->Render();
    ++frames;
    EXPECT_EQ(mapper->GetNumberOfChannels(), 4);
  }
  EXPECT_GT(mapper->GetNumberOfRefinements(), 2);
  EXPECT_EQ(mapper->GetNumberOfRestarts(), 1);
  EXPECT_TRUE(Channels(mapper) == Channels(all.Mapper));
  EXPECT_TRUE(LineIntegrals(mapper) == LineIntegrals(all.Mapper));
  EXPECT_EQ(mapper->GetEstimatedRelativeError(), all.Mapper->GetEstimatedRelativeError());
}

TEST(PolychromaticMapper, AViewThatComesBackTakesBackItsRefinedChannels)
{
  // ParaView's screenshot dialog lays the view out at another size and
  // back: the refined image comes back with its channels, not restarted.
  Scene scene;
  vtkMCXXRayMapper* mapper = scene.Mapper;
  mapper->AutomaticWindowLevelOff();
  mapper->ProgressiveRefinementOn();
  mapper->SetInitialSampleExponent(10);
  scene.Window->SetDesiredUpdateRate(0.0001); // a still render: every point
  scene.Window->Render();
  ASSERT_TRUE(mapper->IsRefinementComplete());
  const std::vector<std::vector<double>> channels = Channels(mapper);
  const std::vector<double> refined = LineIntegrals(mapper);
  scene.Window->SetDesiredUpdateRate(1e6); // interactive: the first prefix
  scene.Window->SetSize(Size - 8, Size - 4);
  scene.Window->Render();
  EXPECT_EQ((1 << 10) - 1, mapper->GetNumberOfAccumulatedSamples());
  EXPECT_EQ(mapper->GetNumberOfChannels(), 4);
  scene.Window->SetSize(Size, Size);
  scene.Window->Render();
  EXPECT_TRUE(mapper->IsRefinementComplete());
  EXPECT_EQ(2, mapper->GetNumberOfRestarts()) << "the view's own size restarted";
  EXPECT_TRUE(Channels(mapper) == channels);
  EXPECT_TRUE(LineIntegrals(mapper) == refined);
  // A spectrum change while another size is shown (whose prefix came back
  // from the shelf in turn) maps the kept channels too.
  scene.Window->SetSize(Size - 8, Size - 4);
  scene.Window->Render();
  mapper->SetSpectrum("120kVp,2.5mmAl");
  scene.Window->SetSize(Size, Size);
  scene.Window->Render();
  EXPECT_EQ(2, mapper->GetNumberOfRestarts());
  EXPECT_TRUE(Channels(mapper) == channels);
  EXPECT_LT(
    RelativeDifference(LineIntegrals(mapper), Model(channels, "120kVp,2.5mmAl", "integrating")),
    1e-12);
}

TEST(PolychromaticMapper, ADensityIndexInputGivesTheVolumesChannels)
{
  // ParaView's representation hands the mapper the volume's density index:
  // the voxels' HU come from its levels (exact for integer data).
  Scene scene;
  scene.Window->Render();
  const std::vector<std::vector<double>> fromVolume = Channels(scene.Mapper);
  const std::vector<double> shown = LineIntegrals(scene.Mapper);
  vtkNew<vtkMCXDensityIndex> index;
  index->SetInputData(scene.Volume);
  scene.Mapper->SetInputConnection(index->GetOutputPort());
  scene.Window->Render();
  EXPECT_TRUE(Channels(scene.Mapper) == fromVolume);
  EXPECT_TRUE(LineIntegrals(scene.Mapper) == shown);
}

TEST(PolychromaticMapper, NoSpectrumIsTheMonochromaticImageBitForBit)
{
  Scene scene;
  vtkNew<vtkPiecewiseFunction> tf;
  tf->AddPoint(-1000, 0);
  tf->AddPoint(2000, 1);
  scene.Prop->GetProperty()->SetScalarOpacity(tf);
  scene.Window->Render();
  scene.Mapper->SetSpectrum(nullptr);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfChannels(), 0);
  const std::vector<double> cleared = LineIntegrals(scene.Mapper);

  Scene monochromatic;
  monochromatic.Mapper->SetSpectrum("");
  monochromatic.Prop->GetProperty()->SetScalarOpacity(tf);
  monochromatic.Window->Render();
  EXPECT_EQ(monochromatic.Mapper->GetNumberOfChannels(), 0);
  EXPECT_TRUE(LineIntegrals(monochromatic.Mapper) == cleared);
  EXPECT_GT(Mean(cleared), 0.0);
}

TEST(PolychromaticMapper, RefusesWhatCannotBePolychromaticInOneLine)
{
  const auto firstError = [](Scene& scene)
  {
    vtkNew<vtkMCXFirstErrorObserver> errors;
    scene.Mapper->AddObserver(vtkCommand::ErrorEvent, errors);
    scene.Window->Render();
    return errors->GetErrorText();
  };
  {
    Scene scene;
    scene.Mapper->SetDeposit(vtkMCXTypes::POINT);
    const std::string error = firstError(scene);
    EXPECT_NE(error.find("footprint deposit"), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_EQ(scene.Mapper->GetNumberOfChannels(), 0);
  }
  {
    Scene scene;
    scene.Mapper->SetSpectrum("20kVp");
    const std::string error = firstError(scene);
    EXPECT_NE(error.find("polychromatic"), std::string::npos) << error;
    EXPECT_EQ(scene.Mapper->GetNumberOfChannels(), 0);
  }
  {
    Scene scene;
    scene.Mapper->SetMaterials("no such materials");
    EXPECT_FALSE(firstError(scene).empty());
  }
  {
    // A point cloud carries no voxels' materials.
    Scene scene;
    vtkNew<vtkMCXDensityIndex> index;
    index->SetInputData(scene.Volume);
    vtkNew<vtkMCXPointSampler> sampler;
    sampler->SetInputConnection(index->GetOutputPort());
    sampler->SetSampleExponent(10);
    scene.Mapper->SetInputConnection(sampler->GetOutputPort());
    const std::string error = firstError(scene);
    EXPECT_NE(error.find("point cloud"), std::string::npos) << error;
  }
}
