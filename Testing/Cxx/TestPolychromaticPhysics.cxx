// The polychromatic physics without a pipeline: tube spectra against the IEC
// 61267 RQR qualities, half-value layers, materials from HU and the per-pixel
// model, each against values computed here from xraylib directly.
#include "mcxExecutor.h"
#include "mcxHalfValueLayer.h"
#include "mcxMaterialAttenuation.h"
#include "mcxMaterialDecomposition.h"
#include "mcxPolychromaticModel.h"
#include "mcxTubeSpectrum.h"
#include "mcxXraylibReference.h"

#include <gtest/gtest.h>
#include <xraylib.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace
{

using mcxtest::XrlTotal;

std::string WriteFile(const std::string& name, const std::string& text)
{
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

mcx::Spectrum OneLine(double energy)
{
  mcx::Spectrum spectrum;
  spectrum.Energies = { energy };
  spectrum.Photons = { 1.0 };
  return spectrum;
}

}

// The check against a standard nobody here wrote: the total filtration fitted
// once, at RQR 5, predicts the other eight first HVLs within 10 %. Prints the
// table of Documentation/polychromatic.md.
TEST(PolychromaticPhysics, RQRHalfValueLayersFromOneFiltration)
{
  mcx::TubeSettings settings;
  settings.Kilovolts = 70.0;
  const double filtration = mcx::FitFiltration(settings, 2.6);
  std::printf("Total filtration fitted at RQR 5: %.3f mm Al\n\n", filtration);
  std::printf("| quality | kV | IEC 61267 HVL (mm Al) | model HVL (mm Al) | deviation |\n");
  std::printf("|---|---|---|---|---|\n");
  for (const mcx::RadiationQuality& quality : mcx::RQRQualities)
  {
    mcx::TubeSettings tube;
    tube.Kilovolts = quality.Kilovolts;
    tube.Filters = { { "Al", filtration, 0.0 } };
    const double hvl = mcx::HalfValueLayer(mcx::TungstenSpectrum(tube));
    const double deviation = hvl / quality.HalfValueLayer - 1.0;
    std::printf("| %s | %.0f | %.1f | %.2f | %+.1f %% |\n", quality.Name, quality.Kilovolts,
      quality.HalfValueLayer, hvl, 100.0 * deviation);
    EXPECT_LT(std::abs(deviation), 0.10) << quality.Name;
  }
}

// Why the production depth is shallow: on a straight path to tungsten's CSDA
// range (mean depth 0.023 g/cm^2 at 100 kVp) the anode hardens the spectra so
// much that one filtration cannot give the RQR series. Prints the table of
// Documentation/polychromatic.md.
TEST(PolychromaticPhysics, StraightElectronPathsMissTheRQRSeries)
{
  mcx::TubeSettings settings;
  settings.Kilovolts = 70.0;
  settings.MeanProductionDepth = 2.0 / 3.0 * 0.035;
  const double filtration = mcx::FitFiltration(settings, 2.6);
  std::printf("Straight paths: filtration fitted at RQR 5: %.3f mm Al\n\n", filtration);
  std::printf("| quality | kV | IEC 61267 HVL (mm Al) | model HVL (mm Al) | deviation |\n");
  std::printf("|---|---|---|---|---|\n");
  double worst = 0.0;
  for (const mcx::RadiationQuality& quality : mcx::RQRQualities)
  {
    settings.Kilovolts = quality.Kilovolts;
    settings.Filters = { { "Al", filtration, 0.0 } };
    const double hvl = mcx::HalfValueLayer(mcx::TungstenSpectrum(settings));
    const double deviation = hvl / quality.HalfValueLayer - 1.0;
    std::printf("| %s | %.0f | %.1f | %.2f | %+.1f %% |\n", quality.Name, quality.Kilovolts,
      quality.HalfValueLayer, hvl, 100.0 * deviation);
    worst = std::max(worst, std::abs(deviation));
  }
  EXPECT_GT(worst, 0.2);
}

// A single energy's HVL is ln 2 / mu whatever the kerma weighting.
TEST(PolychromaticPhysics, MonoenergeticHalfValueLayerIsLn2OverMu)
{
  for (double energy : { 20.0, 45.0, 90.0 })
  {
    const double mu = XrlTotal("Al", energy) * ElementDensity(13, nullptr) * 0.1; // 1/mm
    EXPECT_NEAR(mcx::HalfValueLayer(OneLine(energy)), std::log(2.0) / mu, 1e-5) << energy;
  }
}

TEST(PolychromaticPhysics, SpectrumEndsAtTheTubeVoltageWithLinesAboveTheKEdge)
{
  mcx::TubeSettings tube;
  tube.Kilovolts = 60.0;
  tube.Filters = { { "Al", 2.5, 0.0 } };
  const mcx::Spectrum low = mcx::TungstenSpectrum(tube);
  EXPECT_LT(low.Energies.back(), 60.0);
  EXPECT_GT(low.Energies.back(), 59.0);
  // Below tungsten's K edge (69.5 keV) the spectrum is smooth near 59 keV.
  const auto bin = [](const mcx::Spectrum& s, double e)
  {
    for (std::size_t i = 0; i < s.Size(); ++i)
    {
      if (std::abs(s.Energies[i] - e) < 0.5)
      {
        return s.Photons[i];
      }
    }
    return -1.0;
  };
  EXPECT_LT(bin(low, 58.5), bin(low, 55.5));
  tube.Kilovolts = 100.0;
  const mcx::Spectrum high = mcx::TungstenSpectrum(tube);
  // K-alpha 1 (59.3 keV) and K-beta (67.2 keV) stand above their neighbours.
  EXPECT_GT(bin(high, 59.5), 1.2 * bin(high, 61.5));
  EXPECT_GT(bin(high, 67.5), 1.05 * bin(high, 65.5));
  // The filter's transmission is exp(-mu rho t) bin by bin.
  mcx::Spectrum filtered = high;
  mcx::FilterSpectrum(filtered, { "Cu", 0.1, 0.0 });
  for (std::size_t i = 0; i < high.Size(); i += 7)
  {
    const double mu = XrlTotal("Cu", high.Energies[i]) * ElementDensity(29, nullptr) * 0.01;
    EXPECT_NEAR(filtered.Photons[i], high.Photons[i] * std::exp(-mu), 1e-12 * high.Photons[i]);
  }
}

TEST(PolychromaticPhysics, SpectrumTextAndFileErrorsAreOneLine)
{
  const mcx::TubeSettings settings = mcx::ParseTubeSettings("80kVp,2.5mmAl,0.1mmCu,15deg,0.5keV");
  EXPECT_EQ(settings.Kilovolts, 80.0);
  ASSERT_EQ(settings.Filters.size(), 2u);
  EXPECT_EQ(settings.Filters[1].Material, "Cu");
  EXPECT_EQ(settings.Filters[1].Thickness, 0.1);
  EXPECT_EQ(settings.AnodeAngle, 15.0);
  EXPECT_EQ(settings.BinWidth, 0.5);
  EXPECT_THROW(mcx::ParseTubeSettings("2.5mmAl"), std::invalid_argument);
  EXPECT_THROW(mcx::ParseTubeSettings("70kVp,2.5mmUnobtainium"), std::invalid_argument);
  EXPECT_THROW(mcx::ParseTubeSettings("70kVp,thick"), std::invalid_argument);
  EXPECT_THROW(mcx::TungstenSpectrum(mcx::ParseTubeSettings("200kVp")), std::invalid_argument);
  const mcx::Spectrum spectrum =
    mcx::SpectrumFromText(WriteFile("spectrum.txt", "# keV photons\n30 1\n40, 2\n\n50 0.5\n"));
  ASSERT_EQ(spectrum.Size(), 3u);
  EXPECT_EQ(spectrum.Photons[1], 2.0);
  EXPECT_THROW(mcx::ReadSpectrumFile(WriteFile("bad1.txt", "30 1\n20 1\n")), std::invalid_argument);
  EXPECT_THROW(mcx::ReadSpectrumFile(WriteFile("bad2.txt", "30 -1\n")), std::invalid_argument);
  EXPECT_THROW(mcx::ReadSpectrumFile(WriteFile("bad3.txt", "30 1 2\n")), std::invalid_argument);
  EXPECT_THROW(mcx::ReadSpectrumFile(WriteFile("bad4.txt", "30 0\n")), std::invalid_argument);
  EXPECT_THROW(mcx::ReadSpectrumFile("/nonexistent/spectrum.txt"), std::invalid_argument);
}

TEST(PolychromaticPhysics, DefaultMaterialsMixLinearlyAndSumToOneExactly)
{
  const mcx::MaterialSet set = mcx::DefaultMaterials();
  ASSERT_EQ(set.Size(), 4u);
  // The anchors carry xraylib's densities.
  EXPECT_DOUBLE_EQ(set.Density.At(40.0), mcx::MaterialDensity(mcx::materials::SoftTissue));
  EXPECT_DOUBLE_EQ(set.Density.At(1400.0), mcx::MaterialDensity(mcx::materials::CorticalBone));
  double f[6];
  set.FixedFractionsAt(-30.0, f); // half way between adipose (-100) and soft tissue (40)
  EXPECT_NEAR(f[1], 0.5, 1e-9);
  EXPECT_NEAR(f[2], 0.5, 1e-9);
  // Materials absent there get exactly nothing (the rest goes to one present).
  EXPECT_EQ(f[0], 0.0);
  EXPECT_EQ(f[3], 0.0);
  for (double hu = -1200.0; hu < 3200.0; hu += 0.37)
  {
    set.FixedFractionsAt(hu, f);
    double sum = 0.0;
    for (std::size_t m = 0; m < set.Size(); ++m)
    {
      EXPECT_EQ(std::ldexp(f[m], 32), std::floor(std::ldexp(f[m], 32))); // multiples of 2^-32
      sum += f[m];
    }
    ASSERT_EQ(sum, 1.0) << hu;
  }
  const mcx::MaterialSet extra = mcx::MaterialsFromText("default,iodine=200,titanium=2500");
  ASSERT_EQ(extra.Size(), 6u);
  extra.FixedFractionsAt(500.0, f); // soft tissue, bone and iodine; no titanium below 2500
  EXPECT_EQ(f[5], 0.0);
  EXPECT_EQ(f[0] + f[1] + f[2] + f[3] + f[4], 1.0);
  EXPECT_EQ(extra.Materials[5].Name, "Ti");
  EXPECT_DOUBLE_EQ(extra.Density.At(3000.0), mcx::MaterialDensity("Ti"));
  // 1 mg/ml of iodine per 25 HU above the threshold at the curve's anchor,
  // 1000 HU: 32 mg/ml; none below the threshold.
  EXPECT_NEAR(extra.Materials[4].Fraction.At(1000.0) * extra.Density.At(1000.0), 0.032, 1e-12);
  EXPECT_EQ(extra.Materials[4].Fraction.At(150.0), 0.0);
  EXPECT_THROW(mcx::MaterialsFromText("default,iodine=-5"), std::invalid_argument);
  EXPECT_THROW(mcx::MaterialsFromText("default,gold=100"), std::invalid_argument);
}

TEST(PolychromaticPhysics, MaterialsFileAndItsErrors)
{
  const mcx::MaterialSet set = mcx::MaterialsFromText(WriteFile("materials.txt",
    "# water and aluminium\ndensity -1000 0 0 1 1000 2.699\n"
    "material Water, Liquid | 0 1 1000 0\nmaterial Al | 0 0 1000 1\n"));
  ASSERT_EQ(set.Size(), 2u);
  EXPECT_EQ(set.Materials[0].Name, "Water, Liquid");
  EXPECT_DOUBLE_EQ(set.Density.At(500.0), 1.8495);
  EXPECT_THROW(mcx::ReadMaterialsFile(WriteFile("m1.txt", "material Al | 0 1\n")),
    std::invalid_argument); // no density
  EXPECT_THROW(mcx::ReadMaterialsFile(WriteFile("m2.txt", "density 0 1\nmaterial Al | 0 0.5\n")),
    std::invalid_argument); // fractions sum to 0.5
  EXPECT_THROW(mcx::ReadMaterialsFile(WriteFile("m3.txt", "density 0 1\nmaterial Xx | 0 1\n")),
    std::invalid_argument); // unknown material
  EXPECT_THROW(mcx::ReadMaterialsFile(WriteFile("m4.txt", "density 0 1 -5 2\nmaterial Al | 0 1\n")),
    std::invalid_argument); // HU not increasing
  EXPECT_THROW(mcx::ReadMaterialsFile(WriteFile("m5.txt", "density 0 1 5\nmaterial Al | 0 1\n")),
    std::invalid_argument); // odd count
}

// One energy: exactly Beer-Lambert.
TEST(PolychromaticPhysics, OneEnergyIsBeerLambert)
{
  const mcx::PolychromaticModel model(
    OneLine(60.0), mcx::Detector{}, { mcx::materials::SoftTissue, "Al" });
  const double l[2] = { 3.0, 0.5 };
  const double expected =
    XrlTotal(mcx::materials::SoftTissue, 60.0) * 3.0 + XrlTotal("Al", 60.0) * 0.5;
  EXPECT_NEAR(model.EffectiveLineIntegral(l), expected, 1e-12 * expected);
}

// The model against the sum over the spectrum done here: an energy
// integrating CsI screen and a photon counter behind aluminium steps; the
// effective attenuation falls with thickness (beam hardening).
TEST(PolychromaticPhysics, StepWedgeTransmissionAndBeamHardening)
{
  mcx::TubeSettings tube;
  tube.Kilovolts = 80.0;
  tube.Filters = { { "Al", 2.5, 0.0 } };
  const mcx::Spectrum spectrum = mcx::TungstenSpectrum(tube);
  mcx::Detector screen = mcx::ParseDetector("integrating,CsI:0.6:4.51");
  const mcx::Detector counting = mcx::ParseDetector("counting");
  const mcx::PolychromaticModel integrating(spectrum, screen, { "Al" });
  const mcx::PolychromaticModel counter(spectrum, counting, { "Al" });
  const double density = ElementDensity(13, nullptr);
  double previous = HUGE_VAL;
  for (double mm : { 1.0, 2.0, 5.0, 10.0, 20.0, 40.0 })
  {
    double open = 0.0, behind = 0.0, openCount = 0.0, behindCount = 0.0;
    for (std::size_t e = 0; e < spectrum.Size(); ++e)
    {
      const double energy = spectrum.Energies[e];
      const double absorbed = 1.0 - std::exp(-XrlTotal("CsI", energy) * 4.51 * 0.06);
      const double transmitted = std::exp(-XrlTotal("Al", energy) * density * mm * 0.1);
      open += spectrum.Photons[e] * energy * absorbed;
      behind += spectrum.Photons[e] * energy * absorbed * transmitted;
      openCount += spectrum.Photons[e];
      behindCount += spectrum.Photons[e] * transmitted;
    }
    const double l = density * mm * 0.1; // g/cm^2
    EXPECT_NEAR(integrating.Transmission(&l), behind / open, 1e-12) << mm;
    EXPECT_NEAR(counter.Transmission(&l), behindCount / openCount, 1e-12) << mm;
    const double effectiveMu = integrating.EffectiveLineIntegral(&l) / mm;
    EXPECT_LT(effectiveMu, previous) << mm; // hardening
    previous = effectiveMu;
  }
  EXPECT_THROW(mcx::ParseDetector("scintillating"), std::invalid_argument);
  EXPECT_THROW(mcx::ParseDetector("integrating,CsI"), std::invalid_argument);
  EXPECT_THROW(
    mcx::ParseDetector("integrating,CsI:0.6"), std::invalid_argument); // formula: density
  EXPECT_THROW(mcx::ParseDetector("integrating,CsI:-1:4.5"), std::invalid_argument);
}

// The vectorisable exponential against the C library's, over the normal
// range, and 0 beyond it (exp(-745.2) is below 2^-1074).
TEST(PolychromaticPhysics, ExponentialMatchesTheLibrary)
{
  std::vector<double> a;
  for (double x = 0.0; x < 707.9; x += 0.0137)
  {
    a.push_back(x);
  }
  a.insert(a.end(), { 0.0, 745.2, 1e12, 1e-300 });
  std::vector<double> out(a.size()), work(a.size());
  mcx::PolychromaticModel::ExpOfNegative(a.data(), out.data(), work.data(), a.size());
  double worst = 0.0;
  for (std::size_t i = 0; i + 4 < a.size(); ++i)
  {
    worst = std::max(worst, std::abs(out[i] / std::exp(-a[i]) - 1.0));
  }
  EXPECT_LT(worst, 1e-15);
  const std::size_t last = a.size() - 4;
  EXPECT_EQ(out[last], 1.0);
  EXPECT_EQ(out[last + 1], 0.0);
  EXPECT_EQ(out[last + 2], 0.0);
  EXPECT_EQ(out[last + 3], 1.0);
}

// The image routine (its AVX2 version where the CPU has one) gives the very
// bits of the per-pixel sum compiled here for the baseline instruction set.
TEST(PolychromaticPhysics, ImageRoutineGivesTheBaselineBits)
{
  const mcx::Spectrum spectrum = mcx::TungstenSpectrum(mcx::ParseTubeSettings("101kVp,2.5mmAl"));
  const mcx::PolychromaticModel model(spectrum, mcx::Detector{},
    { mcx::materials::Air, mcx::materials::Adipose, mcx::materials::SoftTissue,
      mcx::materials::CorticalBone });
  constexpr int pixels = 4096;
  std::vector<double> channels[4];
  const double* pointers[4];
  for (int m = 0; m < 4; ++m)
  {
    for (int p = 0; p < pixels; ++p)
    {
      channels[m].push_back((m + 1) * 20.0 * (1.0 + (p % 97) / 97.0) * (p % 5 == m ? 0.0 : 1.0));
    }
    pointers[m] = channels[m].data();
  }
  std::vector<double> out(pixels);
  model.EffectiveImage(mcx::SerialExecutor(), pixels, pointers, 0.1, out.data());
  std::vector<double> scratch(model.ScratchSize());
  for (int p = 0; p < pixels; ++p)
  {
    const double l[4] = { channels[0][p] * 0.1, channels[1][p] * 0.1, channels[2][p] * 0.1,
      channels[3][p] * 0.1 };
    ASSERT_EQ(out[p], -std::log(model.Transmission(l, scratch.data()))) << p;
  }
}
