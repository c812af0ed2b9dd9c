// Polychromatic radiographs through the pipeline: one cloud drawn under the
// total density, its material channels, and the radiograph filter, against
// line integrals counted from the volume and transmissions summed over the
// spectrum here with xraylib values.
#include "mcxHalfValueLayer.h"
#include "mcxPolychromaticModel.h"
#include "mcxTestHelpers.h"
#include "mcxTubeSpectrum.h"
#include "mcxXraylibReference.h"
#include "vtkMCXDensityIndex.h"
#include "vtkMCXMaterialWeights.h"
#include "vtkMCXPointSampler.h"
#include "vtkMCXPolychromaticRadiograph.h"
#include "vtkMCXProjector.h"
#include "vtkMCXTypes.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>
#include <xraylib.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace
{

constexpr int N = 48; // voxels and pixels per side, 1 mm
constexpr int SampleExponent = 22;
constexpr double AlDensity = 2.699;

// Water (0 HU) and aluminium (1000 HU) in air (-1000 HU, density 0).
std::string MaterialsFile()
{
  const std::string path = testing::TempDir() + "water-aluminium.txt";
  std::ofstream(path) << "density -1000 0 0 1 1000 " << AlDensity << "\n"
                      << "material Water, Liquid | 0 1 1000 0\n"
                      << "material Al | 0 0 1000 1\n";
  return path;
}

// Rays along z. Rows y 4-19: an aluminium step wedge, steps of 6, 12, 18 and
// 24 mm in x bands of 10 voxels from x = 4. Rows y 26-43: a water cylinder of
// radius 14 mm along y, centred at x = z = 23.5.
int Band(int i)
{
  return i >= 4 && i < 44 ? (i - 4) / 10 : -1;
}
double HU(int i, int j, int k)
{
  if (j >= 4 && j < 20 && Band(i) >= 0 && k >= 12 && k < 12 + 6 * (Band(i) + 1))
  {
    return 1000.0;
  }
  const double dx = i - 23.5, dz = k - 23.5;
  if (j >= 26 && j < 44 && dx * dx + dz * dz <= 14.0 * 14.0)
  {
    return 0.0;
  }
  return -1000.0;
}

struct Pipeline
{
  vtkSmartPointer<vtkImageData> Volume;
  vtkNew<vtkMCXDensityIndex> Index;
  vtkNew<vtkMCXPointSampler> Sampler;
  vtkNew<vtkPiecewiseFunction> Density;
  std::string Materials = MaterialsFile();

  Pipeline()
  {
    const int dims[3] = { N, N, N };
    this->Volume = mcxtest::MakeVolume(VTK_SHORT, dims, HU);
    this->Index->SetInputData(this->Volume);
    vtkNew<vtkMCXMaterialWeights> describe;
    describe->SetMaterials(this->Materials.c_str());
    EXPECT_TRUE(describe->FillDensityFunction(this->Density));
    EXPECT_EQ(describe->GetNumberOfMaterials(), 2);
    EXPECT_STREQ(describe->GetMaterialName(1), "Al");
    EXPECT_EQ(describe->GetMaterialName(2), nullptr);
    this->Sampler->SetInputConnection(this->Index->GetOutputPort());
    this->Sampler->SetTransferFunction(this->Density);
    this->Sampler->SetSampleExponent(SampleExponent);
    this->Sampler->SetKernel(vtkMCXTypes::BOX);
    this->Sampler->SetDepositToFootprint();
  }

  // A projector of samples drawn from the index under the density, each
  // deposit split into the materials' channels (ChannelLineIntegral) when
  // `split`.
  vtkSmartPointer<vtkMCXProjector> IndexProjector(bool split = true)
  {
    auto projector = vtkSmartPointer<vtkMCXProjector>::New();
    projector->SetInputConnection(this->Index->GetOutputPort());
    projector->SetTransferFunction(this->Density);
    vtkNew<vtkMCXMaterialWeights> describe;
    describe->SetMaterials(this->Materials.c_str());
    projector->SetNumberOfChannels(split ? describe->GetNumberOfMaterials() : 0);
    for (int m = 0; m < projector->GetNumberOfChannels(); ++m)
    {
      vtkNew<vtkPiecewiseFunction> fraction;
      EXPECT_TRUE(describe->FillFractionFunction(m, fraction));
      projector->SetChannelFraction(m, fraction);
    }
    projector->SetKernel(vtkMCXTypes::BOX);
    return projector;
  }

  // The N x N image of 1 mm pixels of `projector`, a copy.
  static vtkSmartPointer<vtkImageData> Image(vtkMCXProjector* projector)
  {
    projector->SetImageSize(N, N);
    projector->SetPixelSpacing(1.0);
    projector->Update();
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->DeepCopy(projector->GetOutput());
    return image;
  }

  // One projection split into the materials' channels.
  vtkSmartPointer<vtkImageData> Split(int sampleExponent = SampleExponent)
  {
    auto projector = this->IndexProjector();
    projector->SetSampleExponent(sampleExponent);
    return Image(projector);
  }

  // The projection of channel (-1: every weight 1) of the one cloud.
  vtkSmartPointer<vtkImageData> Channel(int channel)
  {
    vtkNew<vtkMCXMaterialWeights> weights;
    weights->SetMaterials(this->Materials.c_str());
    weights->SetInputConnection(this->Sampler->GetOutputPort());
    weights->SetInputData(1, this->Volume);
    weights->SetChannel(channel);
    vtkNew<vtkMCXProjector> projector;
    projector->SetInputConnection(weights->GetOutputPort());
    projector->SetKernel(vtkMCXTypes::BOX);
    return Image(projector);
  }
};

// Line integral of material m's density along the column (i, j), g/cm^3 x mm.
double ColumnIntegral(int m, int i, int j)
{
  double sum = 0.0;
  for (int k = 0; k < N; ++k)
  {
    const double hu = HU(i, j, k);
    sum += hu == 1000.0 ? (m == 1 ? AlDensity : 0.0) : hu == 0.0 ? (m == 0 ? 1.0 : 0.0) : 0.0;
  }
  return sum;
}

double TotalMass()
{
  double mass = 0.0;
  for (int j = 0; j < N; ++j)
  {
    for (int i = 0; i < N; ++i)
    {
      mass += ColumnIntegral(0, i, j) + ColumnIntegral(1, i, j);
    }
  }
  return mass;
}

double Pixel(vtkImageData* image, const char* array, int i, int j, int component = 0)
{
  return image->GetPointData()->GetArray(array)->GetComponent(i + N * j, component);
}

// -ln of the detected fraction behind water and aluminium line integrals
// (g/cm^2), summed over the spectrum here from xraylib's coefficients.
double DirectEffectiveLineIntegral(
  const mcx::Spectrum& spectrum, const std::vector<double>& response, double water, double al)
{
  double open = 0.0, behind = 0.0;
  for (std::size_t e = 0; e < spectrum.Size(); ++e)
  {
    const double energy = spectrum.Energies[e];
    const double w = spectrum.Photons[e] * response[e];
    open += w;
    behind += w *
      std::exp(-mcxtest::XrlTotal("Water, Liquid", energy) * water -
        CS_Total_CP("Al", energy, nullptr) * al);
  }
  return -std::log(behind / open);
}

}

TEST(PolychromaticRadiograph, ChannelsSumToTheTotalImage)
{
  Pipeline pipeline;
  auto total = pipeline.Channel(-1);
  auto water = pipeline.Channel(0);
  auto al = pipeline.Channel(1);
  const char* name = vtkMCXTypes::LineIntegralName();
  double largest = 0.0, worst = 0.0;
  for (int j = 0; j < N; ++j)
  {
    for (int i = 0; i < N; ++i)
    {
      const double t = Pixel(total, name, i, j);
      largest = std::max(largest, t);
      worst = std::max(worst, std::abs(Pixel(water, name, i, j) + Pixel(al, name, i, j) - t));
    }
  }
  ASSERT_GT(largest, 20.0); // the 24 mm step: 2.699 x 24
  // The fixed-point sums add up exactly; only the three images' final
  // conversions to doubles round.
  EXPECT_LE(worst, 1e-12 * largest);
  // Each channel holds its material alone: no water under the wedge.
  EXPECT_EQ(Pixel(water, name, 30, 10), 0.0);
  EXPECT_EQ(Pixel(al, name, 23, 35), 0.0);

  // The same of one projection split into channels, whose total is the
  // image of the density without channels, bit for bit.
  auto split = pipeline.Split();
  const char* channels = vtkMCXTypes::ChannelLineIntegralName();
  ASSERT_NE(split->GetPointData()->GetArray(channels), nullptr);
  ASSERT_EQ(split->GetPointData()->GetArray(channels)->GetNumberOfComponents(), 2);
  auto unsplit = pipeline.IndexProjector(false);
  unsplit->SetSampleExponent(SampleExponent);
  auto plain = Pipeline::Image(unsplit);
  worst = 0.0;
  for (int j = 0; j < N; ++j)
  {
    for (int i = 0; i < N; ++i)
    {
      const double t = Pixel(split, name, i, j);
      ASSERT_EQ(t, Pixel(plain, name, i, j)) << i << " " << j;
      worst = std::max(
        worst, std::abs(Pixel(split, channels, i, j, 0) + Pixel(split, channels, i, j, 1) - t));
    }
  }
  EXPECT_LE(worst, 1e-12 * largest);
  EXPECT_EQ(Pixel(split, channels, 30, 10, 0), 0.0);
  EXPECT_EQ(Pixel(split, channels, 23, 35, 1), 0.0);
  EXPECT_GT(Pixel(split, channels, 30, 10, 1), 0.0);
  EXPECT_GT(Pixel(split, channels, 23, 35, 0), 0.0);
  vtkDataArray* estimates =
    split->GetFieldData()->GetArray(vtkMCXTypes::ChannelEstimatedRelativeErrorName());
  ASSERT_NE(estimates, nullptr);
  ASSERT_EQ(estimates->GetNumberOfTuples(), 2);
  EXPECT_GT(estimates->GetComponent(0, 0), 0.0);
  EXPECT_LT(estimates->GetComponent(1, 0), 0.05);
}

// The product's effective line integral of each wedge step and cylinder
// column, against the sum over the spectrum with the exact line integrals;
// the bound is 5 standard deviations of the region's sample count (binomial:
// relative 1 / sqrt(expected samples)), which bounds the relative error of a
// line integral and, -ln T being concave in it, of -ln T too.
TEST(PolychromaticRadiograph, StepWedgeAndWaterCylinderAgreeWithSpectrumSums)
{
  Pipeline pipeline;
  // One projection split into channels, and one image per channel of a stored cloud.
  for (const bool split : { true, false })
  {
    SCOPED_TRACE(split ? "split" : "a stored cloud's channels");
    vtkNew<vtkMCXPolychromaticRadiograph> radiograph;
    radiograph->SetMaterials(pipeline.Materials.c_str());
    radiograph->SetSpectrum("80kVp,2.5mmAl");
    radiograph->SetDetector("integrating,CsI:0.6:4.51");
    if (split)
    {
      radiograph->SetInputData(pipeline.Split());
    }
    else
    {
      radiograph->AddInputData(pipeline.Channel(0));
      radiograph->AddInputData(pipeline.Channel(1));
    }
    radiograph->Update();
    vtkImageData* image = radiograph->GetOutput();
    // The channels come out with the image, named by their materials.
    vtkDataArray* channels =
      image->GetPointData()->GetArray(vtkMCXTypes::ChannelLineIntegralName());
    ASSERT_NE(channels, nullptr);
    EXPECT_STREQ(channels->GetComponentName(1), "Al");
    EXPECT_GT(Pixel(image, vtkMCXTypes::ChannelLineIntegralName(), 40, 10, 1), 20.0); // 24 mm Al
    EXPECT_EQ(Pixel(image, vtkMCXTypes::ChannelLineIntegralName(), 40, 10, 0), 0.0);
    mcx::TubeSettings tube = mcx::ParseTubeSettings("80kVp,2.5mmAl");
    const mcx::Spectrum spectrum = mcx::TungstenSpectrum(tube);
    std::vector<double> response; // E x CsI's absorbed fraction, from xraylib here
    for (double energy : spectrum.Energies)
    {
      response.push_back(
        energy * (1.0 - std::exp(-CS_Total_CP("CsI", energy, nullptr) * 4.51 * 0.06)));
    }
    const double samples = std::ldexp(1.0, SampleExponent) - 1.0;
    const double mass = TotalMass();
    double previousMu = HUGE_VAL;
    for (int band = 0; band < 4; ++band)
    {
      double sum = 0.0, regionMass = 0.0;
      int count = 0;
      for (int j = 6; j < 18; ++j)
      {
        for (int i = 4 + 10 * band + 2; i < 4 + 10 * band + 8; ++i)
        {
          sum += Pixel(image, "EffectiveLineIntegral", i, j);
          regionMass += ColumnIntegral(1, i, j);
          ++count;
        }
      }
      const double thickness = 6.0 * (band + 1); // mm
      const double reference =
        DirectEffectiveLineIntegral(spectrum, response, 0.0, AlDensity * thickness * 0.1);
      const double bound = 5.0 / std::sqrt(samples * regionMass / mass) * reference;
      EXPECT_NEAR(sum / count, reference, bound) << thickness << " mm Al";
      // Beam hardening: the effective attenuation per mm falls with thickness.
      const double mu = sum / count / thickness;
      EXPECT_LT(mu, previousMu) << thickness << " mm Al";
      previousMu = mu;
    }
    for (int i = 12; i < 36; ++i)
    {
      const double chord = ColumnIntegral(0, i, 30);
      double sum = 0.0;
      int count = 0;
      for (int j = 28; j < 42; ++j)
      {
        sum += Pixel(image, "EffectiveLineIntegral", i, j);
        ++count;
      }
      const double reference = DirectEffectiveLineIntegral(spectrum, response, chord * 0.1, 0.0);
      const double bound = 5.0 / std::sqrt(samples * chord * count / mass) * reference;
      EXPECT_NEAR(sum / count, reference, bound) << "column " << i;
    }
    // A spectrum change re-maps the same channels: harder beam, less attenuation.
    const double at80 = Pixel(image, "EffectiveLineIntegral", 40, 10);
    radiograph->SetSpectrum("120kVp,2.5mmAl");
    radiograph->Update();
    EXPECT_LT(Pixel(radiograph->GetOutput(), "EffectiveLineIntegral", 40, 10), at80);
  }
}

// One energy: the polychromatic image is the monochromatic Beer-Lambert image
// of mu = density x (mu/rho) per mm, projected as today with that TF (another
// draw of samples, so within both images' Monte Carlo bounds).
TEST(PolychromaticRadiograph, OneEnergyIsTheMonochromaticImage)
{
  Pipeline pipeline;
  const std::string line = testing::TempDir() + "60keV.txt";
  std::ofstream(line) << "60 1\n";
  vtkNew<vtkMCXPolychromaticRadiograph> radiograph;
  radiograph->SetMaterials(pipeline.Materials.c_str());
  radiograph->SetSpectrum(line.c_str());
  auto water = pipeline.Channel(0);
  auto al = pipeline.Channel(1);
  radiograph->AddInputData(water);
  radiograph->AddInputData(al);
  radiograph->SetNegativeLog(true);
  radiograph->Update();
  vtkImageData* poly = radiograph->GetOutput();
  const double muWater = mcxtest::XrlTotal("Water, Liquid", 60.0) * 0.1; // per mm at 1 g/cm^3
  const double muAl = CS_Total_CP("Al", 60.0, nullptr) * AlDensity * 0.1;
  // The final image's error estimate: with one energy -ln T = sum mu_m L_m,
  // so the propagation adds mu_m L_m times each channel's estimate.
  {
    const char* name = vtkMCXTypes::EstimatedRelativeErrorName();
    const double ew = mcxtest::FieldValue(water, name), ea = mcxtest::FieldValue(al, name);
    ASSERT_GT(ew, 0.0);
    ASSERT_GT(ea, 0.0);
    double errors = 0.0, values = 0.0;
    for (int p = 0; p < N * N; p += mcx::PolychromaticModel::ErrorStride)
    {
      // Channels in g/cm^3 x mm, attenuations per mm at 1 g/cm^3.
      const double lw = Pixel(water, vtkMCXTypes::LineIntegralName(), p, 0) * muWater;
      const double la = Pixel(al, vtkMCXTypes::LineIntegralName(), p, 0) * muAl / AlDensity;
      errors += (lw * ew + la * ea) * (lw * ew + la * ea);
      values += (lw + la) * (lw + la);
    }
    EXPECT_NEAR(mcxtest::FieldValue(poly, name), std::sqrt(errors / values), 1e-9);
  }
  vtkNew<vtkPiecewiseFunction> mu;
  mu->AddPoint(-1000, 0.0);
  mu->AddPoint(0, muWater);
  mu->AddPoint(1000, muAl);
  vtkNew<vtkMCXProjector> projector;
  projector->SetInputConnection(pipeline.Index->GetOutputPort());
  projector->SetTransferFunction(mu);
  projector->SetKernel(vtkMCXTypes::BOX);
  projector->SetSampleExponent(SampleExponent);
  projector->SetImageSize(N, N);
  projector->SetPixelSpacing(1.0);
  projector->Update();
  vtkImageData* mono = projector->GetOutput();
  const double samples = std::ldexp(1.0, SampleExponent) - 1.0;
  double muMass = 0.0, densityMass = TotalMass();
  for (int j = 0; j < N; ++j)
  {
    for (int i = 0; i < N; ++i)
    {
      muMass += ColumnIntegral(0, i, j) * muWater + ColumnIntegral(1, i, j) * muAl / AlDensity;
    }
  }
  for (int band = 0; band < 4; ++band)
  {
    double a = 0.0, b = 0.0, regionMu = 0.0, regionDensity = 0.0;
    for (int j = 6; j < 18; ++j)
    {
      for (int i = 4 + 10 * band + 2; i < 4 + 10 * band + 8; ++i)
      {
        a += Pixel(poly, vtkMCXTypes::AttenuationName(), i, j);
        b += Pixel(mono, vtkMCXTypes::LineIntegralName(), i, j);
        regionMu += ColumnIntegral(1, i, j) * muAl / AlDensity;
        regionDensity += ColumnIntegral(1, i, j);
      }
    }
    // Both estimates' 5-sigma binomial bounds added.
    const double exact = regionMu / 72.0;
    const double bound = 5.0 * exact *
      (1.0 / std::sqrt(samples * regionDensity / densityMass) +
        1.0 / std::sqrt(samples * regionMu / muMass));
    EXPECT_NEAR(a / 72.0, exact, 5.0 * exact / std::sqrt(samples * regionDensity / densityMass));
    EXPECT_NEAR(a / 72.0, b / 72.0, bound) << "step " << band;
  }
}

// The filter alone, on exact channels (the columns' line integrals): every
// pixel is the sum over the spectrum, for both detectors.
TEST(PolychromaticRadiograph, ExactChannelsGiveTheSpectrumSumInEveryPixel)
{
  std::vector<vtkSmartPointer<vtkImageData>> channels;
  for (int m = 0; m < 2; ++m)
  {
    const int dims[3] = { N, N, 1 };
    auto image = mcxtest::MakeVolume(
      VTK_DOUBLE, dims, [m](int i, int j, int) { return ColumnIntegral(m, i, j); });
    image->GetPointData()->GetScalars()->SetName(vtkMCXTypes::LineIntegralName());
    channels.push_back(image);
  }
  const mcx::Spectrum spectrum = mcx::TungstenSpectrum(mcx::ParseTubeSettings("100kVp,3mmAl"));
  for (const char* detector : { "integrating,CsI:0.6:4.51", "counting" })
  {
    vtkNew<vtkMCXPolychromaticRadiograph> radiograph;
    radiograph->SetMaterials(MaterialsFile().c_str());
    radiograph->SetSpectrum("100kVp,3mmAl");
    radiograph->SetDetector(detector);
    radiograph->SetIncidentIntensity(1000.0);
    radiograph->AddInputData(channels[0]);
    radiograph->AddInputData(channels[1]);
    radiograph->Update();
    vtkImageData* image = radiograph->GetOutput();
    // The responses from xraylib here: E x CsI's absorbed fraction, or 1.
    std::vector<double> response;
    for (double energy : spectrum.Energies)
    {
      response.push_back(detector[0] == 'c'
          ? 1.0
          : energy * (1.0 - std::exp(-CS_Total_CP("CsI", energy, nullptr) * 4.51 * 0.06)));
    }
    for (int j = 0; j < N; j += 3)
    {
      for (int i = 0; i < N; ++i)
      {
        const double l = DirectEffectiveLineIntegral(
          spectrum, response, ColumnIntegral(0, i, j) * 0.1, ColumnIntegral(1, i, j) * 0.1);
        ASSERT_NEAR(Pixel(image, "EffectiveLineIntegral", i, j), l, 1e-12 * (1.0 + l)) << detector;
        ASSERT_NEAR(Pixel(image, vtkMCXTypes::IntensityName(), i, j), 1000.0 * std::exp(-l), 1e-9)
          << detector;
      }
    }
  }
}

// Channels of one split projection, radiograph, noise and error estimate:
// bit for bit the same on one thread and on two.
TEST(PolychromaticRadiograph, BitIdenticalForOneAndTwoThreads)
{
  std::vector<vtkSmartPointer<vtkImageData>> images;
  for (int threads : { 1, 2 })
  {
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads },
      [&]()
      {
        Pipeline pipeline;
        vtkNew<vtkMCXPolychromaticRadiograph> radiograph;
        radiograph->SetMaterials(pipeline.Materials.c_str());
        radiograph->SetSpectrum("90kVp,3mmAl");
        radiograph->SetPhotonsPerPixel(1e4);
        radiograph->SetNoiseSeed(7);
        radiograph->SetInputData(pipeline.Split(18));
        radiograph->Update();
        auto image = vtkSmartPointer<vtkImageData>::New();
        image->DeepCopy(radiograph->GetOutput());
        images.push_back(image);
      });
  }
  for (const char* name : { "EffectiveLineIntegral", vtkMCXTypes::IntensityName() })
  {
    for (int p = 0; p < N * N; ++p)
    {
      ASSERT_EQ(Pixel(images[0], name, p, 0), Pixel(images[1], name, p, 0)) << name << " " << p;
    }
  }
  const char* estimate = vtkMCXTypes::EstimatedRelativeErrorName();
  EXPECT_EQ(mcxtest::FieldValue(images[0], estimate), mcxtest::FieldValue(images[1], estimate));
}

TEST(PolychromaticRadiograph, BadSettingsAreOneLineErrors)
{
  Pipeline pipeline;
  vtkNew<vtkMCXPolychromaticRadiograph> radiograph;
  radiograph->SetMaterials(pipeline.Materials.c_str());
  radiograph->AddInputData(pipeline.Channel(0));
  radiograph->SetSpectrum("70kVp");
  {
    mcxtest::FirstError error(radiograph);
    radiograph->Update(); // one channel for two materials
    EXPECT_NE(error.Text.find("1 channel images for 2 materials"), std::string::npos) << error.Text;
  }
  radiograph->AddInputData(pipeline.Channel(1));
  radiograph->SetSpectrum("300kVp");
  mcxtest::FirstError error(radiograph);
  radiograph->Update();
  EXPECT_NE(error.Text.find("outside 40-150 kVp"), std::string::npos) << error.Text;
  vtkNew<vtkMCXMaterialWeights> weights;
  weights->SetMaterials("/nonexistent/materials.txt");
  mcxtest::FirstError unreadable(weights);
  EXPECT_EQ(weights->GetNumberOfMaterials(), 0);
  EXPECT_NE(unreadable.Text.find("cannot be read"), std::string::npos) << unreadable.Text;
  // A cloud of the point deposit (kernel offsets) has no voxel per point.
  pipeline.Sampler->SetDepositToPoint();
  vtkNew<vtkMCXMaterialWeights> offsets;
  offsets->SetMaterials(pipeline.Materials.c_str());
  offsets->SetInputConnection(pipeline.Sampler->GetOutputPort());
  offsets->SetInputData(1, pipeline.Volume);
  offsets->SetChannel(0);
  mcxtest::FirstError between(offsets);
  offsets->Update();
  EXPECT_NE(between.Text.find("is not at a voxel centre"), std::string::npos) << between.Text;
}

TEST(PolychromaticRadiograph, UnusableChannelFractionsAreOneLineErrors)
{
  Pipeline pipeline;
  auto projector = pipeline.IndexProjector(false);
  projector->SetSampleExponent(12);
  projector->SetImageSize(8, 8);
  projector->SetNumberOfChannels(2);
  vtkNew<vtkPiecewiseFunction> one, negative, zero;
  one->AddPoint(-1000, 1);
  negative->AddPoint(-1000, -0.5);
  zero->AddPoint(-1000, 0);
  projector->SetChannelFraction(0, one);
  {
    mcxtest::FirstError error(projector);
    projector->Update();
    EXPECT_NE(error.Text.find("channel 1 has no fraction function"), std::string::npos)
      << error.Text;
  }
  projector->SetChannelFraction(1, negative);
  {
    mcxtest::FirstError error(projector);
    projector->Update();
    EXPECT_NE(error.Text.find("the channel fractions are 1 -0.5"), std::string::npos) << error.Text;
  }
  projector->SetChannelFraction(0, zero);
  projector->SetChannelFraction(1, zero);
  {
    mcxtest::FirstError error(projector);
    projector->Update();
    EXPECT_NE(error.Text.find("one > 0"), std::string::npos) << error.Text;
  }
  {
    mcxtest::FirstError error(projector);
    projector->SetChannelFraction(2, one);
    EXPECT_NE(error.Text.find("channel 2 is not one of the 2 channels"), std::string::npos)
      << error.Text;
  }
  projector->SetChannelFraction(1, one);
  projector->Update();
  EXPECT_NE(
    projector->GetOutput()->GetPointData()->GetArray(vtkMCXTypes::ChannelLineIntegralName()),
    nullptr);
  // A stored cloud is not split: said, not ignored.
  projector->SetInputConnection(pipeline.Sampler->GetOutputPort());
  {
    mcxtest::FirstError error(projector);
    projector->Update();
    EXPECT_NE(error.Text.find("the input is a stored point cloud"), std::string::npos)
      << error.Text;
  }
  // Split projections go into the radiograph alone.
  vtkNew<vtkMCXPolychromaticRadiograph> radiograph;
  radiograph->SetMaterials(pipeline.Materials.c_str());
  radiograph->SetSpectrum("70kVp");
  radiograph->AddInputData(pipeline.Split(12));
  radiograph->AddInputData(pipeline.Split(12));
  mcxtest::FirstError error(radiograph);
  radiograph->Update();
  EXPECT_NE(error.Text.find("Input 0 is a projection split into channels"), std::string::npos)
    << error.Text;
}

TEST(PolychromaticRadiograph, ATargetsChannelsAreTheFixedRunOfItsSampleCountBitForBit)
{
  // A target error refines from its pilot, keeping the pilot's sums
  // (prefixes): its channels are those of a fixed run of the sample count it
  // chose, bit for bit, as its total is.
  Pipeline pipeline;
  auto run = [&](double target, int exponent)
  {
    auto projector = pipeline.IndexProjector();
    projector->SetKernel(vtkMCXTypes::TENT);
    projector->SetDeposit(vtkMCXTypes::POINT);
    projector->SetTargetRelativeError(target);
    projector->SetSampleExponent(exponent);
    return Pipeline::Image(projector);
  };
  auto targeted = run(0.02, 0);
  const double count = mcxtest::FieldValue(targeted, vtkMCXTypes::SampleCountName());
  ASSERT_GT(count, 65535.0); // refined beyond the pilot
  auto fixed = run(0.0, static_cast<int>(std::log2(count + 1.0)));
  ASSERT_EQ(count, mcxtest::FieldValue(fixed, vtkMCXTypes::SampleCountName()));
  for (const char* name :
    { vtkMCXTypes::LineIntegralName(), vtkMCXTypes::ChannelLineIntegralName() })
  {
    for (int p = 0; p < N * N; ++p)
    {
      for (int c = 0; c < (name == vtkMCXTypes::LineIntegralName() ? 1 : 2); ++c)
      {
        ASSERT_EQ(Pixel(targeted, name, p, 0, c), Pixel(fixed, name, p, 0, c)) << name << " " << p;
      }
    }
  }
}
