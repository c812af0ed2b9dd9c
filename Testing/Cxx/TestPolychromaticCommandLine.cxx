// mcxray render --spectrum: a cube of soft tissue against the sum over the
// spectrum done here with xraylib, and the options' one-line errors (also
// those of mcxray view, checked before it opens a window).
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

TEST(PolychromaticCommandLine, SoftTissueCubeAgreesWithTheSpectrumSum)
{
  const std::string input = SoftTissueCube();
  const std::string output = mcxtest::Temporary("soft-tissue-cube-70kVp.vti");
  const mcxtest::Result r = mcxtest::RunCLI("render " + input +
    " --spectrum 70kVp,2.5mmAl --view +z --size " + std::to_string(N) + "x" + std::to_string(N) +
    " --pixel-spacing 1 --samples 1048575 --negative-log --output " + output);
  ASSERT_EQ(0, r.Status) << r.Errors;
  EXPECT_NE(r.Output.find("channel:     Tissue, Soft (ICRP)"), std::string::npos) << r.Output;
  auto image = mcxtest::Read(output);
  vtkDataArray* values = image->GetPointData()->GetArray("Attenuation");
  ASSERT_NE(values, nullptr);
  // 32 mm of soft tissue at xraylib's density in every interior column.
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
  const double reference = -std::log(behind / open);
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
  // 5 binomial standard deviations of the region's samples (its share of
  // the cube's mass, 24^2 / 32^2 of 2^20 - 1).
  const double samples = 1048575.0 * count / (N * N);
  EXPECT_NEAR(sum / count, reference, 5.0 / std::sqrt(samples) * reference);
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
  mcxtest::ExpectOneLineError("render --spectrum 70kVp --deposit point" + quiet, output);
  mcxtest::ExpectOneLineError(
    "render --spectrum 70kVp --detector-material CsI:0.6" + quiet, output);
  mcxtest::ExpectOneLineError("render --spectrum 70kVp --beer-lambert" + quiet, output);
  mcxtest::ExpectOneLineError("render --spectrum 70kVp --tf mu" + quiet, output);
  // A stored cloud per material has no target control (it crashed before it was refused).
  mcxtest::ExpectOneLineError("render --spectrum 70kVp --target-error 0.05" + quiet, output);
  mcxtest::ExpectOneLineError("render --spectrum 70kVp --quantization-levels 64" + quiet, output);
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
