// The mcxray command: real CT files from disk, the axis-view contract,
// output formats, and clear errors without partial output.
#include "mcxTestHelpers.h"

#include "vtkNew.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>

namespace
{
struct Result
{
  int Status;
  std::string Output; // stdout
  std::string Errors; // stderr
};

std::string Slurp(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

Result RunCLI(const std::string& arguments, const std::string& environment = "")
{
  // One log per test: ctest may run the tests of this file in parallel.
  const std::string log = vtksys::SystemTools::GetCurrentWorkingDirectory() + "/mcxray-" +
    ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const std::string command = environment + std::string(MCXRAY_CLI) + " " + arguments + " > " +
    log + ".out 2> " + log + ".err";
  const int raw = std::system(command.c_str());
  return { WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, Slurp(log + ".out"), Slurp(log + ".err") };
}

vtkSmartPointer<vtkImageData> Read(const std::string& path)
{
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

std::string Temporary(const std::string& name)
{
  const std::string path = vtksys::SystemTools::GetCurrentWorkingDirectory() + "/" + name;
  vtksys::SystemTools::RemoveFile(path);
  return path;
}

// Exit status 2, one line on stderr, nothing on stdout, no output file.
void ExpectOneLineError(const std::string& arguments, const std::string& output)
{
  Result r = RunCLI(arguments);
  EXPECT_EQ(2, r.Status) << arguments << "\n" << r.Errors;
  EXPECT_EQ(0u, r.Errors.find("mcxray: error: ")) << arguments << "\n" << r.Errors;
  EXPECT_EQ(r.Errors.size() - 1, r.Errors.find('\n')) << arguments << "\n" << r.Errors;
  EXPECT_EQ("", r.Output) << arguments;
  EXPECT_FALSE(vtksys::SystemTools::FileExists(output)) << arguments;
}

std::string SharedData(const std::string& name)
{
  return std::string(MCXRAY_SHARED_DATA_DIR) + "/" + name;
}
}

TEST(CommandLine, RealCTFromDiskMatchesTheExactReference)
{
  const std::string input = SharedData("ct_body_totalseg.nii.gz");
  if (!vtksys::SystemTools::FileExists(input))
  {
    GTEST_SKIP() << "shared data not found: " << input;
  }
  const std::string hybrid = Temporary("cli_body_hybrid.vti");
  const std::string exact = Temporary("cli_body_reference.vti");
  const std::string common = " --view +y --tf bone --size 64x64 --quiet --output ";
  Result a = RunCLI("render " + input + " --samples 4194303" + common + hybrid);
  ASSERT_EQ(0, a.Status) << a.Errors;
  Result b = RunCLI("render " + input + " --method reference --tolerance 1e-3" + common + exact);
  ASSERT_EQ(0, b.Status) << b.Errors;
  auto estimate = Read(hybrid);
  auto reference = Read(exact);
  ASSERT_EQ(64 * 64, mcxtest::LineIntegral(reference)->GetNumberOfTuples());
  const double integral = mcxtest::FieldValue(reference, "Integral");
  const double area = reference->GetSpacing()[0] * reference->GetSpacing()[1];
  const double bound = mcxtest::ExpectedRelativeRMS(reference, integral, area, 4194303.0);
  EXPECT_LT(mcxtest::RelativeRMS(estimate, reference), 1.5 * bound + 2e-3);
  // Bone is tens of mm of unit TF along a ray through the pelvis.
  EXPECT_GT(mcxtest::LineIntegral(reference)->GetRange()[1], 10.0);
}

TEST(CommandLine, AxisViewsFollowTheContract)
{
  // One bright voxel at world (x, y, z) = (1 + 2*3, -4 + 0.5*5, 10 + 1.5*2):
  // every axis view must peak at the pixel whose centre has those world
  // coordinates along the two remaining axes, and + and - views must agree.
  const int dims[3] = { 10, 12, 6 };
  const double spacing[3] = { 2.0, 0.5, 1.5 };
  const double origin[3] = { 1.0, -4.0, 10.0 };
  auto volume = mcxtest::MakeVolume(
    VTK_UNSIGNED_CHAR, dims,
    [](int i, int j, int k) { return i == 3 && j == 5 && k == 2 ? 200.0 : 0.0; }, spacing, origin);
  const std::string input = Temporary("cli_point.vti");
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(volume);
  writer->SetFileName(input.c_str());
  writer->Write();
  const double world[3] = { 7.0, -1.5, 13.0 };
  for (int axis = 0; axis < 3; ++axis)
  {
    const int first = axis == 0 ? 1 : 0, second = axis == 2 ? 1 : 2;
    vtkSmartPointer<vtkImageData> images[2];
    for (int sign = 0; sign < 2; ++sign)
    {
      const std::string view = std::string(sign ? "-" : "+") + "xyz"[axis];
      const std::string output =
        Temporary("cli_point_" + std::to_string(axis) + std::to_string(sign) + ".vti");
      Result r = RunCLI("render " + input + " --view " + view +
        " --method reference --kernel box --pixel-spacing 0.25 --quiet --output " + output);
      ASSERT_EQ(0, r.Status) << r.Errors;
      images[sign] = Read(output);
      vtkDataArray* values = mcxtest::LineIntegral(images[sign]);
      vtkIdType best = 0;
      for (vtkIdType p = 0; p < values->GetNumberOfTuples(); ++p)
      {
        best = values->GetTuple1(p) > values->GetTuple1(best) ? p : best;
      }
      const int width = images[sign]->GetDimensions()[0];
      const double centre[2] = { images[sign]->GetOrigin()[0] +
          (best % width) * images[sign]->GetSpacing()[0],
        images[sign]->GetOrigin()[1] + (best / width) * images[sign]->GetSpacing()[1] };
      // The box voxel covers +-spacing/2 around its centre; the peak plateau lies inside it.
      EXPECT_NEAR(world[first], centre[0], spacing[first] / 2) << view;
      EXPECT_NEAR(world[second], centre[1], spacing[second] / 2) << view;
      // The plateau value is the voxel's value times its depth along the view axis.
      EXPECT_NEAR(200.0 * spacing[axis], values->GetTuple1(best), 1e-9) << view;
    }
    vtkDataArray* plus = mcxtest::LineIntegral(images[0]);
    vtkDataArray* minus = mcxtest::LineIntegral(images[1]);
    ASSERT_EQ(plus->GetNumberOfTuples(), minus->GetNumberOfTuples());
    for (vtkIdType p = 0; p < plus->GetNumberOfTuples(); ++p)
    {
      ASSERT_EQ(plus->GetTuple1(p), minus->GetTuple1(p));
    }
  }
}

TEST(CommandLine, BundledCTAndEveryOutputFormat)
{
  for (const char* name : { "cli_default.png", "cli_default.pfm", "cli_default.vti" })
  {
    const std::string output = Temporary(name);
    Result r = RunCLI("render --samples 65535 --size 96x80 --bits 16 --output " + output);
    ASSERT_EQ(0, r.Status) << r.Errors;
    EXPECT_NE(std::string::npos, r.Output.find("65535 samples")) << r.Output;
    EXPECT_NE(std::string::npos, r.Output.find("index:")) << r.Output;
    EXPECT_TRUE(vtksys::SystemTools::FileExists(output));
  }
  // The stored-point pipeline times sampling and projection apart.
  Result stored =
    RunCLI("render --samples 65535 --stored-points --output " + Temporary("cli_stored.vti"));
  ASSERT_EQ(0, stored.Status) << stored.Errors;
  EXPECT_NE(std::string::npos, stored.Output.find("sampling:")) << stored.Output;
  EXPECT_NE(std::string::npos, stored.Output.find("projection:")) << stored.Output;
  // A target error chooses the sample count and reports the estimate.
  const std::string targetOutput = Temporary("cli_target.vti");
  Result targeted = RunCLI("render --target-error 0.05 --size 64x64 --output " + targetOutput);
  ASSERT_EQ(0, targeted.Status) << targeted.Errors;
  auto image = Read(targetOutput);
  EXPECT_LT(mcxtest::FieldValue(image, "EstimatedRelativeError"), 0.05);
  EXPECT_NE(std::string::npos, targeted.Output.find("estimated relative RMS error"))
    << targeted.Output;
  // PFM: header plus 96 * 80 float32 values.
  EXPECT_EQ(std::string("Pf\n96 80\n-1.0\n").size() + 96 * 80 * 4,
    vtksys::SystemTools::FileLength(
      vtksys::SystemTools::GetCurrentWorkingDirectory() + "/cli_default.pfm"));
}

TEST(CommandLine, OtherFormatsFromSharedData)
{
  for (const char* name :
    { "ct_head_headsq_dicom", "mri_head_vtk_small.mhd", "ct_tooth.nrrd", "sci_ironprot.vtk" })
  {
    const std::string input = SharedData(name);
    if (!vtksys::SystemTools::FileExists(input))
    {
      GTEST_SKIP() << "shared data not found: " << input;
    }
    const std::string output = Temporary("cli_format.vti");
    Result r =
      RunCLI("render " + input + " --samples 65535 --size 32x32 --quiet --output " + output);
    ASSERT_EQ(0, r.Status) << name << ": " << r.Errors;
    auto image = Read(output);
    EXPECT_GT(mcxtest::LineIntegral(image)->GetRange()[1], 0.0) << name;
  }
}

TEST(CommandLine, BadInputGivesOneLineErrorAndNoOutput)
{
  const std::string output = Temporary("cli_never.png");
  const char* cases[] = {
    "render /nonexistent/volume.nii.gz --output ",
    "render --tf 100:x --output ",
    "render --samples -5 --output ",
    "render --view +w --output ",
    "render --method fast --output ",
    "render --camera 0,0,0:0,0,0:0,0,1:angle=30 --output ",
    "render --camera 0,0,100:0,0,0:0,0,1:parallel=0 --output ",
    "render --size 0x10 --output ",
    "render --target-error 2 --output ",
    "render --target-error 0.1 --method reference --output ",
    "render --tf 0:inf --output ",
    "render --tf mu=x --output ",
    "render --tf mu=-0.02 --output ",
    "render --sad 0 --output ",
    "render --sid -5 --output ",
    "render --detector 0x10 --output ",
    "render --pitch nan --output ",
    "render --isocenter 1,2 --output ",
    "render --sad 1000 --view +y --output ",
    "render --gantry 10 --size 64x64 --output ",
    "render --photons -1 --output ",
    "render --photons 1e16 --output ",
    "render --i0 0 --output ",
    "render --noise-seed -3 --output ",
    "frobnicate --output ",
  };
  for (const char* arguments : cases)
  {
    ExpectOneLineError(std::string(arguments) + output, output);
  }
  Result r = RunCLI("render --output /nonexistent-dir/x.png");
  EXPECT_EQ(2, r.Status);
  Result help = RunCLI("render --help");
  EXPECT_EQ(0, help.Status);
  EXPECT_NE(std::string::npos, help.Output.find("--pixel-spacing"));
}

TEST(CommandLine, ViewerBadInputGivesOneLineErrorAndNoOutput)
{
  const std::string output = Temporary("cli_view_never.png");
  const char* cases[] = {
    "view /nonexistent/volume.nii.gz --screenshot ",
    "view --samples 0 --screenshot ",
    "view --samples 2000000000 --screenshot ",
    "view --method reference --screenshot ",
    "view --kernel cubic --screenshot ",
    "view --size 4x4 --screenshot ",
    "view --tf 1:x --screenshot ",
    "view --frames 3 --screenshot ",
    "view --screenshot /nonexistent-dir/x.png --tf raw --seed ",
  };
  for (const char* arguments : cases)
  {
    ExpectOneLineError(std::string(arguments) + output, output);
  }
  Result jpeg = RunCLI("view --screenshot " + Temporary("cli_view.jpg"));
  EXPECT_EQ(2, jpeg.Status);
  EXPECT_NE(std::string::npos, jpeg.Errors.find(".png")) << jpeg.Errors;
  // Without a display the interactive viewer says so instead of crashing.
  Result headless = RunCLI("view", "env -u DISPLAY ");
  EXPECT_EQ(2, headless.Status);
  EXPECT_NE(std::string::npos, headless.Errors.find("no display")) << headless.Errors;
  Result help = RunCLI("view --help");
  EXPECT_EQ(0, help.Status);
  EXPECT_NE(std::string::npos, help.Output.find("--screenshot"));
}

TEST(CommandLine, RadiographGeometryAndPhysics)
{
  // A cone-beam radiograph of the bundled CT: 64 x 48 detector pixels of
  // 2 mm at SID 800, i.e. 1.25 mm at the isocentre (SAD 500), intensities
  // I0 exp(-line integral) in (0, I0].
  const std::string output = Temporary("cli_radiograph.vti");
  Result r = RunCLI(
    "render --tf mu --sad 500 --sid 800 --detector 64x48 --pitch 2 --gantry 30 --samples 65535 "
    "--beer-lambert --i0 100 --output " +
    output);
  ASSERT_EQ(0, r.Status) << r.Errors;
  EXPECT_NE(std::string::npos, r.Output.find("radiograph:")) << r.Output;
  auto image = Read(output);
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(64, dims[0]);
  EXPECT_EQ(48, dims[1]);
  EXPECT_NEAR(1.25, image->GetSpacing()[0], 1e-12);
  vtkDataArray* intensity = image->GetPointData()->GetArray("Intensity");
  ASSERT_NE(nullptr, intensity);
  double range[2];
  intensity->GetRange(range);
  EXPECT_GT(range[0], 0.0);
  EXPECT_LE(range[1], 100.0);
  EXPECT_LT(range[0], 100.0);
  ASSERT_NE(nullptr, image->GetPointData()->GetArray("LineIntegral"));

  // Noise and the negative log: seeded, so the same command gives the same file.
  const std::string noisy[2] = { Temporary("cli_noisy_a.vti"), Temporary("cli_noisy_b.vti") };
  for (const std::string& path : noisy)
  {
    Result n = RunCLI(
      "render --tf mu --detector 32x32 --samples 65535 --photons 500 --noise-seed 9 --negative-log "
      "--output " +
      path);
    ASSERT_EQ(0, n.Status) << n.Errors;
  }
  auto first = Read(noisy[0]);
  auto second = Read(noisy[1]);
  vtkDataArray* a = first->GetPointData()->GetArray("Attenuation");
  vtkDataArray* b = second->GetPointData()->GetArray("Attenuation");
  ASSERT_NE(nullptr, a);
  ASSERT_NE(nullptr, b);
  for (vtkIdType p = 0; p < a->GetNumberOfTuples(); ++p)
  {
    ASSERT_EQ(a->GetTuple1(p), b->GetTuple1(p)) << p;
  }
}
