// The mcxray command: real CT files from disk, the axis-view contract,
// output formats, and clear errors without partial output.
#include "mcxCommandLineRunner.h"
#include "mcxSharedData.h"
#include "mcxTestHelpers.h"

#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

using mcxtest::ExpectOneLineError;
using mcxtest::Read;
using mcxtest::Result;
using mcxtest::RunCLI;
using mcxtest::Slurp;
using mcxtest::Temporary;

namespace
{
std::string SharedData(const std::string& name)
{
  return mcxtest::SharedDataPath(name);
}

void WriteVolume(vtkImageData* volume, const std::string& path)
{
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(volume);
  writer->SetFileName(path.c_str());
  writer->Write();
}

// A PFM read by the format's definition (not the writer's code): "Pf",
// width, height, scale (negative: little endian), then float32 rows from
// the bottom row up, left to right.
bool ReadPFM(const std::string& path, int& width, int& height, std::vector<float>& values)
{
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  double scale = 0;
  in >> magic >> width >> height >> scale;
  in.get(); // the single whitespace after the scale
  if (magic != "Pf" || scale >= 0 || width <= 0 || height <= 0)
  {
    return false;
  }
  values.resize(static_cast<std::size_t>(width) * height);
  in.read(reinterpret_cast<char*>(values.data()),
    static_cast<std::streamsize>(values.size() * sizeof(float)));
  return static_cast<bool>(in) && in.peek() == std::char_traits<char>::eof();
}
}

TEST(CommandLine, RealCTFromDiskMatchesTheExactReference)
{
  const std::string input = SharedData("ct_body_totalseg.nii.gz");
  MCXTEST_NEED_FILE(input);
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

TEST(CommandLine, EveryVoxelIsNearTheExactReference)
{
  // --method every-voxel: each voxel of non-zero weight once, weighted, by
  // the off-line projector (fused: nothing stored) and as a stored cloud
  // (--stored-points). The error is the footprint's random rounding alone:
  // less than half that of a sampled footprint cloud of as many points
  // (measured: a tenth, 35 833 bone voxels at 64^2), either way; the log
  // says it is not estimated.
  const std::string input = SharedData("ct_body_totalseg.nii.gz");
  MCXTEST_NEED_FILE(input);
  const std::string every = Temporary("cli_body_every_voxel.vti");
  const std::string stored = Temporary("cli_body_every_voxel_stored.vti");
  const std::string sampled = Temporary("cli_body_every_voxel_sampled.vti");
  const std::string exact = Temporary("cli_body_every_voxel_reference.vti");
  const std::string common = " --view +y --tf bone --size 64x64 --output ";
  Result a = RunCLI("render " + input + " --method every-voxel" + common + every);
  ASSERT_EQ(0, a.Status) << a.Errors;
  const std::string said = "voxels, each once: no sampling error to estimate";
  const std::size_t at = a.Output.find(said);
  ASSERT_NE(std::string::npos, at) << a.Output;
  EXPECT_NE(std::string::npos, a.Output.find("(off-line, fused)")) << a.Output;
  Result d = RunCLI("render " + input + " --method every-voxel --stored-points" + common + stored);
  ASSERT_EQ(0, d.Status) << d.Errors;
  EXPECT_NE(std::string::npos, d.Output.find("stored points")) << d.Output;
  const std::size_t open = a.Output.rfind('(', at);
  const long long voxels = std::atoll(a.Output.c_str() + open + 1);
  ASSERT_GT(voxels, 1000) << a.Output;
  Result b = RunCLI(
    "render " + input + " --samples " + std::to_string(voxels) + " --quiet" + common + sampled);
  ASSERT_EQ(0, b.Status) << b.Errors;
  Result c =
    RunCLI("render " + input + " --method reference --tolerance 1e-4 --quiet" + common + exact);
  ASSERT_EQ(0, c.Status) << c.Errors;
  auto reference = Read(exact);
  const double sampledError = mcxtest::RelativeRMS(Read(sampled), reference);
  for (const std::string& file : { every, stored })
  {
    auto estimate = Read(file);
    const double error = mcxtest::RelativeRMS(estimate, reference);
    std::cout << file << ": " << voxels << " voxels once: " << error
              << "; as many sampled points: " << sampledError << std::endl;
    EXPECT_LT(error, 0.5 * sampledError) << file;
    EXPECT_EQ(voxels, mcxtest::FieldValue(estimate, "SampleCount")) << file;
    EXPECT_TRUE(std::isnan(mcxtest::FieldValue(estimate, "EstimatedRelativeError"))) << file;
  }
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
      // Exactly: the box voxel's footprint is a rectangle whose sides (two of
      // 2, 0.5, 1.5 mm) are whole numbers of 0.25 mm pixels, so the partly
      // covered pixels at its two opposite edges add up to one whole pixel,
      // centred. Hence the pixel-centre centroid is the voxel's centre and
      // sum x pixel area the voxel's integral, 200 x 2 x 0.5 x 1.5.
      double total = 0, moment[2] = { 0, 0 };
      for (vtkIdType p = 0; p < values->GetNumberOfTuples(); ++p)
      {
        const double value = values->GetTuple1(p);
        total += value;
        moment[0] +=
          value * (images[sign]->GetOrigin()[0] + (p % width) * images[sign]->GetSpacing()[0]);
        moment[1] +=
          value * (images[sign]->GetOrigin()[1] + (p / width) * images[sign]->GetSpacing()[1]);
      }
      ASSERT_GT(total, 0.0) << view;
      EXPECT_NEAR(world[first], moment[0] / total, 1e-9) << view;
      EXPECT_NEAR(world[second], moment[1] / total, 1e-9) << view;
      EXPECT_NEAR(
        300.0, total * images[sign]->GetSpacing()[0] * images[sign]->GetSpacing()[1], 1e-9 * 300)
        << view;
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

TEST(CommandLine, PNGAndPFMHoldTheValuesOfTheVTI)
{
  // One render (deterministic: fixed seed, results independent of threads)
  // written as .vti, .pfm and .png. Documented: PNG grey = (v - LO) x top /
  // (HI - LO), clamped to [0, top] (top 255 or 65535 for --bits 16), window
  // 0:maximum by default; PFM holds float32(v). Read back with vtkPNGReader
  // (VTK's row order: row 0 the bottom row) and a PFM reader of the format's
  // own definition, pixel (i, j) must match the .vti's pixel (i, j): a
  // flipped row order, a wrong scale or window fails.
  const std::string common = "render --samples 65535 --size 96x80 --quiet --output ";
  const std::string vti = Temporary("cli_values.vti");
  ASSERT_EQ(0, RunCLI(common + vti).Status);
  auto image = Read(vti);
  vtkDataArray* v = mcxtest::LineIntegral(image);
  ASSERT_EQ(96 * 80, v->GetNumberOfTuples());
  const double maximum = v->GetRange()[1];
  ASSERT_GT(maximum, 0.0);
  // The picture is not symmetric top to bottom, so a flip shows.
  double asymmetry = 0;
  for (int j = 0; j < 40; ++j)
  {
    for (int i = 0; i < 96; ++i)
    {
      asymmetry += std::abs(v->GetTuple1(j * 96 + i) - v->GetTuple1((79 - j) * 96 + i));
    }
  }
  ASSERT_GT(asymmetry, 0.01 * maximum * 96 * 80);

  int width = 0, height = 0;
  std::vector<float> pfm;
  const std::string pfmPath = Temporary("cli_values.pfm");
  ASSERT_EQ(0, RunCLI(common + pfmPath).Status);
  ASSERT_TRUE(ReadPFM(pfmPath, width, height, pfm));
  ASSERT_EQ(96, width);
  ASSERT_EQ(80, height);
  for (vtkIdType p = 0; p < v->GetNumberOfTuples(); ++p)
  {
    ASSERT_EQ(static_cast<float>(v->GetTuple1(p)), pfm[static_cast<std::size_t>(p)]) << p;
  }

  // The window as the command parses it (std::to_string's six decimals).
  const double low = std::stod(std::to_string(0.25 * maximum));
  const double high = std::stod(std::to_string(0.75 * maximum));
  struct Case
  {
    std::string Options;
    double Low, High, Top;
  };
  const Case cases[] = {
    { "", 0, maximum, 255 },
    { "--bits 16 ", 0, maximum, 65535 },
    // A window inside the range: both clamps are reached.
    { "--bits 16 --window " + std::to_string(low) + ":" + std::to_string(high) + " ", low, high,
      65535 },
  };
  for (const Case& c : cases)
  {
    const std::string png = Temporary("cli_values.png");
    Result r =
      RunCLI("render --samples 65535 --size 96x80 --quiet " + c.Options + "--output " + png);
    ASSERT_EQ(0, r.Status) << r.Errors;
    vtkNew<vtkPNGReader> reader;
    reader->SetFileName(png.c_str());
    reader->Update();
    vtkImageData* grey = reader->GetOutput();
    ASSERT_EQ(96, grey->GetDimensions()[0]) << c.Options;
    ASSERT_EQ(80, grey->GetDimensions()[1]) << c.Options;
    ASSERT_EQ(1, grey->GetNumberOfScalarComponents()) << c.Options;
    ASSERT_EQ(c.Top == 255 ? VTK_UNSIGNED_CHAR : VTK_UNSIGNED_SHORT, grey->GetScalarType());
    vtkDataArray* g = grey->GetPointData()->GetScalars();
    int clamped[2] = { 0, 0 };
    for (vtkIdType p = 0; p < v->GetNumberOfTuples(); ++p)
    {
      const double scaled =
        std::min(c.Top, std::max(0.0, (v->GetTuple1(p) - c.Low) * c.Top / (c.High - c.Low)));
      // vtkImageShiftScale truncates, after the clamp (its own product may
      // differ in the last bit: within 1e-9 of a whole number either side).
      const double grey = g->GetTuple1(p);
      ASSERT_TRUE(grey >= std::floor(scaled - 1e-9) && grey <= std::floor(scaled + 1e-9))
        << c.Options << " pixel " << p << ": " << grey << " for " << scaled;
      clamped[0] += grey == 0 ? 1 : 0;
      clamped[1] += grey == c.Top ? 1 : 0;
    }
    EXPECT_GT(clamped[1], 0) << c.Options;
    if (c.High < maximum)
    {
      EXPECT_GT(clamped[0], 0) << c.Options;
    }
  }
}

TEST(CommandLine, OtherFormatsFromSharedData)
{
  for (const char* name :
    { "ct_head_headsq_dicom", "mri_head_vtk_small.mhd", "ct_tooth.nrrd", "sci_ironprot.vtk" })
  {
    const std::string input = SharedData(name);
    MCXTEST_NEED_FILE(input);
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
    "render --samples 100 --samples 200 --output ",
    "render --tf 100:x --output ",
    "render --tf 1000:0,1000:1 --output ",
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
    "render --method every-voxel --samples 1000 --output ",
    "render --method every-voxel --target-error 0.02 --output ",
    "render --method view-ordered --output ",
    "frobnicate --output ",
    // Options that would change nothing: refused, not dropped in silence.
    "render --method reference --samples 1000 --output ",
    "render --method reference --deposit point --output ",
    "render --tolerance 0.01 --output ",
    "render --i0 5 --tf mu --output ",
    "render --target-error 0.05 --samples 1000 --output ",
  };
  for (const char* arguments : cases)
  {
    ExpectOneLineError(std::string(arguments) + output, output);
  }
  Result r = RunCLI("render --output /nonexistent-dir/x.png");
  EXPECT_EQ(2, r.Status);
  // An output that is a folder is refused before any work, not after the render.
  const std::string folder = Temporary("cli_folder.png");
  vtksys::SystemTools::MakeDirectory(folder);
  r = RunCLI("render --output " + folder);
  EXPECT_EQ(2, r.Status);
  EXPECT_EQ("mcxray: error: cannot write '" + folder + "': it is a directory\n", r.Errors);
  EXPECT_EQ(std::string::npos, r.Output.find("index:")) << r.Output;
  Result help = RunCLI("render --help");
  EXPECT_EQ(0, help.Status);
  EXPECT_NE(std::string::npos, help.Output.find("--pixel-spacing"));
}

TEST(CommandLine, ErrorsNameTheOptionGiven)
{
  // --detector and --isocenter share --size's and --camera's parsers; their
  // errors name the option the user gave.
  const std::pair<const char*, const char*> cases[] = {
    { "render --detector 0x5",
      "mcxray: error: bad value '0' for --detector (expected an integer >= 1)\n" },
    { "render --detector 5", "mcxray: error: bad --detector '5' (expected WxH, e.g. 512x512)\n" },
    { "render --detector 70000x5",
      "mcxray: error: --detector is limited to 65536 pixels per side\n" },
    { "render --isocenter 1,2",
      "mcxray: error: bad --isocenter '1,2' (expected 3 numbers separated by commas or spaces)\n" },
    { "render --isocenter 1,x,2", "mcxray: error: bad value 'x' for --isocenter\n" },
    { "render --size 0x5", "mcxray: error: bad value '0' for --size (expected an integer >= 1)\n" },
    { "render --camera 1,2:0,0,0:0,0,1:angle=30",
      "mcxray: error: bad --camera position '1,2' (expected x,y,z)\n" },
    // An angle past a million degrees: its own message, not --vup's.
    { "render --gantry 1e308",
      "mcxray: error: bad value '1e308' for --gantry (expected degrees from -1e6 to 1e6)\n" },
    { "render --gantry 0:2e6:3",
      "mcxray: error: bad value '2e6' for --gantry (expected degrees from -1e6 to 1e6)\n" },
  };
  for (const auto& c : cases)
  {
    const Result r = RunCLI(std::string(c.first) + " --output " + Temporary("cli_named.png"));
    EXPECT_EQ(2, r.Status) << c.first;
    EXPECT_EQ(c.second, r.Errors) << c.first;
  }
  // An option the command does not know is named as unknown wherever it
  // stands, last included (it once read as an option missing its value);
  // a known one left without its value says so.
  const std::pair<const char*, const char*> last[] = {
    { "render --frob", "mcxray: error: unknown option --frob (try: mcxray render --help)\n" },
    { "render --frob 3", "mcxray: error: unknown option --frob (try: mcxray render --help)\n" },
    { "view --stored-points",
      "mcxray: error: unknown option --stored-points (try: mcxray view --help)\n" },
    { "render --samples", "mcxray: error: option --samples needs a value\n" },
  };
  for (const auto& c : last)
  {
    const Result r = RunCLI(c.first);
    EXPECT_EQ(2, r.Status) << c.first;
    EXPECT_EQ(c.second, r.Errors) << c.first;
  }
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
    "view --method every-voxel --samples 1000 --screenshot ",
    "view --size 4x4 --screenshot ",
    "view --tf 1:x --screenshot ",
    "view --frames 3 --screenshot ",
    "view --screenshot /nonexistent-dir/x.png --tf raw --seed ",
  };
  for (const char* arguments : cases)
  {
    ExpectOneLineError(std::string(arguments) + output, output);
  }
  // --reorder-angle: a value out of 0..180, or a method without an order;
  // each error names the option.
  for (const char* arguments : { "view --method view-ordered --reorder-angle 181 --screenshot ",
         "view --method view-ordered --reorder-angle -1 --screenshot ",
         "view --method view-ordered --reorder-angle nan --screenshot ",
         "view --reorder-angle 10 --screenshot ", "render --reorder-angle 10 --output " })
  {
    ExpectOneLineError(std::string(arguments) + output, output);
    EXPECT_NE(
      std::string::npos, RunCLI(std::string(arguments) + output).Errors.find("--reorder-angle"))
      << arguments;
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
  vtkDataArray* lineIntegral = image->GetPointData()->GetArray("LineIntegral");
  ASSERT_NE(nullptr, lineIntegral);
  // Beer-Lambert per pixel, from the same run's line integral: I = I0 exp(-L).
  for (vtkIdType p = 0; p < intensity->GetNumberOfTuples(); ++p)
  {
    ASSERT_NEAR(100.0 * std::exp(-lineIntegral->GetTuple1(p)), intensity->GetTuple1(p), 1e-12 * 100)
      << p;
  }

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

TEST(CommandLine, PhotonsGivePoissonCounts)
{
  // --photons N --i0 I0: I = I0 k / N, k ~ Poisson(lambda), lambda = N exp(-L)
  // with L the run's own LineIntegral. So k is a whole number, and
  // z = (k - lambda)^2 / lambda has mean 1 and variance 2 + 1 / lambda
  // (Poisson: E(k - lambda)^4 = lambda + 3 lambda^2). The n pixels are
  // independent, so their mean z lies within 5 sqrt(sum(2 + 1/lambda)) / n
  // of 1. mu = 0.002 per mm keeps L below about 5, lambda above 6000.
  const double photons = 1e6, i0 = 3;
  const std::string output = Temporary("cli_photons.vti");
  Result r = RunCLI("render --tf mu=0.002 --view +x --size 64x64 --samples 65535 --photons 1e6 "
                    "--i0 3 --noise-seed 5 --quiet --output " +
    output);
  ASSERT_EQ(0, r.Status) << r.Errors;
  auto image = Read(output);
  vtkDataArray* intensity = image->GetPointData()->GetArray("Intensity");
  vtkDataArray* lineIntegral = image->GetPointData()->GetArray("LineIntegral");
  ASSERT_NE(nullptr, intensity);
  ASSERT_NE(nullptr, lineIntegral);
  const vtkIdType n = intensity->GetNumberOfTuples();
  ASSERT_EQ(64 * 64, n);
  ASSERT_GT(lineIntegral->GetRange()[1], 1.0); // the CT attenuates
  double sum = 0, variance = 0;
  for (vtkIdType p = 0; p < n; ++p)
  {
    const double k = intensity->GetTuple1(p) * photons / i0;
    ASSERT_NEAR(std::round(k), k, 1e-6 * k) << "pixel " << p << ": counts are whole photons";
    const double lambda = photons * std::exp(-lineIntegral->GetTuple1(p));
    sum += (k - lambda) * (k - lambda) / lambda;
    variance += 2 + 1 / lambda;
  }
  EXPECT_NEAR(1.0, sum / n, 5 * std::sqrt(variance) / n);
}

TEST(CommandLine, PhysicsOnValuesOfOtherUnitsWarns)
{
  // The bundled CT is stored from 0 (no air at or below -500): --tf mu and
  // --spectrum read its values as HU all the same (a phantom without air
  // stays exact) and say so, one line each after the image is written; a
  // radiograph of the raw TF's data values (a silhouette) says so too.
  const std::pair<const char*, const char*> cases[] = {
    { "render --beer-lambert --size 16x16 --samples 1023",
      "mcxray: warning: the radiograph takes line integrals of attenuation per mm (--tf mu): --tf "
      "raw weighs the values 0 .. 3926 as they are, so exp(-those) is near 0 in tissue, a "
      "silhouette\n" },
    { "render --tf mu --gantry 0 -r \"32 32\" --samples 1023",
      "mcxray: warning: --tf mu takes CT in HU, but the values 0 .. 3926 hold no air (none at or "
      "below -500): read as HU all the same\n" },
    { "render --spectrum 70kVp,2.5mmAl --view +y --size 16x16 --samples 1023",
      "mcxray: warning: --spectrum's materials take CT in HU, but the values 0 .. 3926 hold no air "
      "(none at or below -500): read as HU all the same\n" },
  };
  for (const auto& c : cases)
  {
    const std::string output = Temporary("cli_no_air.vti");
    const Result r = RunCLI(std::string(c.first) + " --quiet --output " + output);
    EXPECT_EQ(0, r.Status) << c.first;
    EXPECT_EQ(c.second, r.Errors) << c.first;
    EXPECT_TRUE(vtksys::SystemTools::FileExists(output)) << c.first;
  }
  // Values in attenuation per mm already (0 and 0.02): raw is their line
  // integral, and the radiograph says nothing.
  vtkNew<vtkImageData> mu;
  mu->SetDimensions(8, 8, 8);
  mu->AllocateScalars(VTK_DOUBLE, 1);
  for (vtkIdType v = 0; v < mu->GetNumberOfPoints(); ++v)
  {
    mu->GetPointData()->GetScalars()->SetTuple1(v, v % 3 == 0 ? 0.02 : 0.0);
  }
  const std::string input = Temporary("cli_mu_per_mm.vti");
  WriteVolume(mu, input);
  const Result r = RunCLI("render " + input +
    " --beer-lambert --size 16x16 --samples 1023 --quiet "
    "--output " +
    Temporary("cli_mu_per_mm_out.vti"));
  EXPECT_EQ(0, r.Status) << r.Errors;
  EXPECT_EQ("", r.Errors);
}

TEST(CommandLine, GantryTurnsTheSourceAboutZ)
{
  // A volume without symmetry about z, on a grid that a quarter turn about
  // the z axis through its centre maps onto itself (9 x 9 voxels of 2 mm
  // centred on x = y = 0). Gantry +90 degrees puts the source on -y (turned
  // clockwise about +z from +x, as plastimatch turns it): the image of V
  // then equals the gantry-0 image of V turned by +90 degrees, R(V)(x, y) =
  // V(y, -x), i.e. voxel (i, j) of R(V) is voxel (j, 8 - i) of V. Exact
  // reference method.
  const int dims[3] = { 9, 9, 5 };
  const double spacing[3] = { 2, 2, 2 };
  const double origin[3] = { -8, -8, -4 };
  auto value = [](int i, int j, int k)
  { return (i > 5 && j < 3 ? 400.0 : 0.0) + 40.0 * ((i + 2 * j + 3 * k) % 5); };
  const std::string inputs[3] = { Temporary("cli_gantry_v.vti"), Temporary("cli_gantry_r.vti"),
    Temporary("cli_gantry_w.vti") };
  WriteVolume(mcxtest::MakeVolume(VTK_SHORT, dims, value, spacing, origin), inputs[0]);
  WriteVolume(
    mcxtest::MakeVolume(
      VTK_SHORT, dims, [&](int i, int j, int k) { return value(j, 8 - i, k); }, spacing, origin),
    inputs[1]);
  // Turned the wrong way (what a gantry turning counterclockwise would show).
  WriteVolume(
    mcxtest::MakeVolume(
      VTK_SHORT, dims, [&](int i, int j, int k) { return value(8 - j, i, k); }, spacing, origin),
    inputs[2]);
  auto render = [&](const std::string& input, int gantry, const std::string& name)
  {
    const std::string output = Temporary(name);
    Result r = RunCLI("render " + input + " --sad 100 --sid 150 --detector 24x24 --pitch 1.5 " +
      "--gantry " + std::to_string(gantry) + " --method reference --quiet --output " + output);
    EXPECT_EQ(0, r.Status) << r.Errors;
    return Read(output);
  };
  auto turned = render(inputs[0], 90, "cli_gantry_90.vti");
  auto expected = render(inputs[1], 0, "cli_gantry_r0.vti");
  auto straight = render(inputs[0], 0, "cli_gantry_0.vti");
  auto wrongWay = render(inputs[2], 0, "cli_gantry_w0.vti");
  vtkDataArray* a = mcxtest::LineIntegral(turned);
  vtkDataArray* b = mcxtest::LineIntegral(expected);
  ASSERT_EQ(24 * 24, a->GetNumberOfTuples());
  ASSERT_EQ(24 * 24, b->GetNumberOfTuples());
  const double peak = b->GetRange()[1];
  ASSERT_GT(peak, 0.0);
  for (vtkIdType p = 0; p < a->GetNumberOfTuples(); ++p)
  {
    ASSERT_NEAR(b->GetTuple1(p), a->GetTuple1(p), 1e-9 * peak) << "pixel " << p;
  }
  // The check has power: ignoring --gantry, or turning the other way,
  // would give these images, far from the expected one.
  EXPECT_GT(mcxtest::RelativeRMS(straight, expected), 0.1);
  EXPECT_GT(mcxtest::RelativeRMS(wrongWay, expected), 0.1);
}

#ifdef MCXRAY_MPIEXEC
namespace
{
std::size_t Occurrences(const std::string& text, const std::string& part)
{
  std::size_t count = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1))
  {
    ++count;
  }
  return count;
}
}

TEST(CommandLine, UnderMpirunTheOutputFileIsTheSingleProcessOne)
{
  // mpirun -np N mcxray render ...: each process renders its z-slab and the
  // first writes the image, byte for byte the one process's file, for point
  // and footprint deposits in a parallel view and a cone-beam radiograph,
  // sampled and every voxel once, and a sweep's stack.
  // (No hwloc probing of X displays: the render tests' Xvfb servers come
  // and go, and one that goes kills the probing process. Open MPI's own
  // allocations show as leaks in a sanitized build.)
  const std::string launcher = "HWLOC_COMPONENTS=-gl ASAN_OPTIONS=detect_leaks=0 " +
    std::string(MCXRAY_MPIEXEC) + " --allow-run-as-root --oversubscribe -np ";
  const std::string runs[] = { "--samples 262143 --size 96x80",
    "--samples 262143 --size 96x80 --deposit point --view -y --tf bone",
    "--samples 131071 --sad 700 --sid 1100 --detector 90x70 --pitch 3 --gantry 30 --tf mu",
    "--method every-voxel --sad 700 --sid 1100 --detector 90x70 --tf mu",
    // A polychromatic radiograph: the deposit split into the materials' channels.
    "--samples 131071 --sad 700 --sid 1100 --detector 90x70 --pitch 3 --spectrum 70kVp,2.5mmAl",
    "--samples 131071 --size 96x80 --deposit point --spectrum 120kVp --negative-log",
    // A sweep: each pose as alone, on any number of processes.
    "--samples 131071 --sad 700 --sid 1100 --detector 60x50 --pitch 3 --gantry 0:90:3 --tf mu" };
  for (const std::string& arguments : runs)
  {
    const std::string single = Temporary("mpirun-single.vti");
    Result one = RunCLI("render " + arguments + " --quiet --output " + single);
    ASSERT_EQ(0, one.Status) << one.Errors;
    for (const int processes : { 2, 3 })
    {
      const std::string many = Temporary("mpirun-" + std::to_string(processes) + ".vti");
      Result r = RunCLI(
        "render " + arguments + " --output " + many, launcher + std::to_string(processes) + " ");
      ASSERT_EQ(0, r.Status) << arguments << "\n" << r.Errors;
      EXPECT_EQ(1u, Occurrences(r.Output, "output:")) << "one process logs:\n" << r.Output;
      EXPECT_EQ(Slurp(single), Slurp(many)) << arguments << " on " << processes << " processes";
    }
  }
  // An error is said once, by the first process, and ends every process.
  const std::string output = Temporary("mpirun-error.png");
  Result r = RunCLI("render /nonexistent/volume.vti --output " + output, launcher + "2 ");
  EXPECT_NE(0, r.Status);
  EXPECT_EQ(1u, Occurrences(r.Errors, "mcxray: error: ")) << r.Errors;
  EXPECT_FALSE(vtksys::SystemTools::FileExists(output));
}
#endif
