// mcxray render --spectrum: a cube of soft tissue against the sum over the
// spectrum done here with xraylib, by every sampling, and the options'
// one-line errors (also those of mcxray view, checked before it opens a
// window).
#include "mcxCommandLineRunner.h"
#include "mcxTestHelpers.h"
#include "mcxTubeSpectrum.h"
#include "mcxXraylibReference.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkXMLImageDataWriter.h"

#include <xraylib.h>

#include <cmath>

namespace
{
constexpr int N = 32;

std::string SoftTissueCube()
{
  const std::string path = mcxtest::Temporary("soft-tissue-cube.vti");
  const int dims[3] = { N, N, N };
  // 40 HU: the default materials' soft tissue anchor, all of it soft tissue.
  auto volume = mcxtest::MakeVolume(VTK_SHORT, dims, [](int, int, int) { return 40.0; });
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(volume);
  writer->SetFileName(path.c_str());
  writer->Write();
  return path;
}
}

namespace
{
// -ln(I / I0) behind 32 mm of soft tissue at xraylib's density, summed over
// the spectrum here (an ideal detector integrating energy).
double SoftTissueReference()
{
  const double density = mcxtest::NistDensity("Tissue, Soft (ICRP)");
  const mcx::Spectrum spectrum = mcx::TungstenSpectrum(mcx::ParseTubeSettings("70kVp,2.5mmAl"));
  double open = 0.0, behind = 0.0;
  for (std::size_t e = 0; e < spectrum.Size(); ++e)
  {
    const double energy = spectrum.Energies[e];
    const double mu = mcxtest::XrlTotal("Tissue, Soft (ICRP)", energy);
    open += spectrum.Photons[e] * energy;
    behind += spectrum.Photons[e] * energy * std::exp(-mu * density * 3.2);
  }
  return -std::log(behind / open);
}
}

TEST(PolychromaticCommandLine, SoftTissueCubeAgreesWithTheSpectrumSum)
{
  // Every way of sampling splits its deposit into the materials' channels:
  // the footprint and point deposits, every voxel once and a target error.
  const std::string input = SoftTissueCube();
  const double reference = SoftTissueReference();
  // The interior columns' mean: 5 binomial standard deviations of the
  // region's samples (its share of the cube's mass, 24^2 / 32^2 of M) for a
  // sampled image; every voxel once is exact but for fixed-point rounding;
  // a target of 1 % per pixel bounds the mean at 1 %.
  const double samples = 1048575.0 * 24 * 24 / (N * N);
  const struct
  {
    std::string Options;
    double Bound;
  } runs[] = { { "--samples 1048575", 5.0 / std::sqrt(samples) },
    { "--samples 1048575 --deposit point", 5.0 / std::sqrt(samples) },
    { "--method every-voxel", 1e-9 }, { "--target-error 0.01", 0.01 } };
  for (const auto& run : runs)
  {
    const std::string output = mcxtest::Temporary("soft-tissue-cube-70kVp.vti");
    const mcxtest::Result r = mcxtest::RunCLI("render " + input +
      " --spectrum 70kVp,2.5mmAl --view +z --size " + std::to_string(N) + "x" + std::to_string(N) +
      " --pixel-spacing 1 --negative-log " + run.Options + " --output " + output);
    ASSERT_EQ(0, r.Status) << r.Errors;
    EXPECT_NE(r.Output.find("(polychromatic, 4 channels;"), std::string::npos) << r.Output;
    EXPECT_EQ(r.Output.find("nan"), std::string::npos) << r.Output; // every voxel: no estimate
    auto image = mcxtest::Read(output);
    vtkDataArray* values = image->GetPointData()->GetArray("Attenuation");
    ASSERT_NE(values, nullptr);
    double sum = 0.0;
    int count = 0;
    for (int j = 4; j < N - 4; ++j)
    {
      for (int i = 4; i < N - 4; ++i)
      {
        sum += values->GetComponent(i + N * j, 0);
        ++count;
      }
    }
    EXPECT_NEAR(sum / count, reference, run.Bound * reference) << run.Options;
  }
}

TEST(PolychromaticCommandLine, BadOptionsAreOneLineErrors)
{
  const std::string output = mcxtest::Temporary("polychromatic-error.png");
  const std::string quiet = " --samples 1000 --output " + output;
  mcxtest::ExpectOneLineError("render --spectrum 300kVp" + quiet, output);
  mcxtest::ExpectOneLineError("render --spectrum 70kVp,2mmUnobtainium" + quiet, output);
  mcxtest::ExpectOneLineError("render --spectrum /nonexistent/spectrum.txt" + quiet, output);
  mcxtest::ExpectOneLineError("render --materials default" + quiet, output);
  mcxtest::ExpectOneLineError("render --spectrum 70kVp --materials default,gold=3" + quiet, output);
  mcxtest::ExpectOneLineError("render --spectrum 70kVp --method reference" + quiet, output);
  mcxtest::ExpectOneLineError("render --spectrum 70kVp --method view-ordered" + quiet, output);
  mcxtest::ExpectOneLineError("render --spectrum 70kVp --stored-points" + quiet, output);
  mcxtest::ExpectOneLineError(
    "render --spectrum 70kVp --detector-material CsI:0.6" + quiet, output);
  mcxtest::ExpectOneLineError("render --spectrum 70kVp --beer-lambert" + quiet, output);
  mcxtest::ExpectOneLineError("render --spectrum 70kVp --tf mu" + quiet, output);
}

TEST(PolychromaticCommandLine, ViewRefusesWhatCannotBePolychromatic)
{
  const std::string output = mcxtest::Temporary("polychromatic-view-error.png");
  const std::string quiet = " --samples 1000 --screenshot " + output;
  mcxtest::ExpectOneLineError("view --spectrum 300kVp" + quiet, output);
  mcxtest::ExpectOneLineError("view --materials default" + quiet, output);
  mcxtest::ExpectOneLineError("view --photon-counting" + quiet, output);
  mcxtest::ExpectOneLineError("view --spectrum 70kVp --materials default,gold=3" + quiet, output);
  mcxtest::ExpectOneLineError("view --spectrum 70kVp --method every-voxel" + quiet, output);
  mcxtest::ExpectOneLineError("view --spectrum 70kVp --deposit point" + quiet, output);
  mcxtest::ExpectOneLineError("view --spectrum 70kVp --detector-material CsI:0.6" + quiet, output);
  mcxtest::ExpectOneLineError("view --spectrum 70kVp --tf bone" + quiet, output);
}
