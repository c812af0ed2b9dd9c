// The text formats (MetaImage, NRRD, legacy VTK) against hostile input
// (issue 39): keys in another letter case, patterns without a range,
// literal names with '%', corrupt or short compressed data, text data with
// too few values, attributes that would make VTK's reader allocate before
// the scalars, a sparse file of one endless token. The command line refuses
// each with one line and exit status 2, writes nothing, and never
// overwrites a data file a header names; the format readers refuse the same
// files with one error and print nothing themselves.
#include "mcxCommandLineRunner.h"
#include "mcxHeaderCheck.h"

#include "vtkCallbackCommand.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMCXMetaImageReader.h"
#include "vtkMCXNrrdReader.h"
#include "vtkNew.h"
#include "vtkNrrdReader.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"
#include "vtkStructuredPoints.h"
#include "vtkStructuredPointsReader.h"
#include "vtkStructuredPointsWriter.h"
#include "vtk_zlib.h"
#include "vtkmetaio/metaImage.h"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

using mcxtest::Result;
using mcxtest::RunCLI;
using mcxtest::Slurp;
using mcxtest::Temporary;

namespace
{
std::string Folder()
{
  const std::string folder = Temporary("hostile_text");
  vtksys::SystemTools::MakeDirectory(folder);
  return folder;
}

void WriteBytes(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// bytes deflated: gzip (windowBits 31) or zlib (15).
std::string Deflated(const std::string& bytes, int windowBits)
{
  z_stream stream{};
  deflateInit2(&stream, Z_DEFAULT_COMPRESSION, Z_DEFLATED, windowBits, 8, Z_DEFAULT_STRATEGY);
  std::string out(deflateBound(&stream, bytes.size()) + 32, '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  stream.avail_in = static_cast<uInt>(bytes.size());
  stream.next_out = reinterpret_cast<Bytef*>(&out[0]);
  stream.avail_out = static_cast<uInt>(out.size());
  deflate(&stream, Z_FINISH);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

std::string Random(std::size_t size)
{
  std::mt19937 random(39);
  std::string bytes(size, '\0');
  for (char& c : bytes)
  {
    c = static_cast<char>(random());
  }
  return bytes;
}

// 4 x 4 x 4 voxels of one byte: a little volume with structure.
std::string Voxels()
{
  std::string bytes(64, '\0');
  for (int i = 0; i < 64; ++i)
  {
    bytes[i] = static_cast<char>(i * 3);
  }
  return bytes;
}

const std::string Mha = "NDims = 3\nDimSize = 4 4 4\nElementType = MET_UCHAR\n";
// 16 along the first axis: more than 9, which vtkNrrdReader would take for components.
const std::string Nrrd = "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 16 1 4\n";
const std::string Vtk = "# vtk DataFile Version 3.0\nhostile\nBINARY\nDATASET STRUCTURED_POINTS\n";

// A VTI of 2 x 2 x 2 voxels placed by `placement`: VTK's reader takes an
// Origin, Spacing or Direction it cannot parse as its default.
std::string Vti(const std::string& placement)
{
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\">\n"
         "<ImageData WholeExtent=\"0 1 0 1 0 1\" " +
    placement +
    ">\n<Piece Extent=\"0 1 0 1 0 1\"><PointData Scalars=\"v\">"
    "<DataArray type=\"UInt8\" Name=\"v\" format=\"ascii\">1 2 3 4 5 6 7 8</DataArray>"
    "</PointData></Piece>\n</ImageData>\n</VTKFile>\n";
}

struct Hostile
{
  std::string Name;  // the file, in the test's folder
  std::string Bytes; // its content
  std::string Why;   // what the one line says
};

// The hostile shapes, each with what refuses it.
std::vector<Hostile> Shapes(const std::string& folder)
{
  const std::string z = Deflated(Voxels(), 15), gz = Deflated(Voxels(), 31);
  WriteBytes(folder + "/voxels.raw", Voxels());
  WriteBytes(folder + "/garbage.raw.gz", Random(200));
  WriteBytes(folder + "/few.txt", "1 2 3 4 5 6 7\n");
  return {
    // A lower-case data-file line that MetaIO skips, hiding a LIST.
    { "hidden-list.mhd", Mha + "elementdatafile = voxels.raw\nElementDataFile = LIST\nvoxels.raw\n",
      "'elementdatafile' is 'ElementDataFile' in another letter case" },
    // Two ElementTypes by case (MetaIO's warning and an error before).
    { "type-case.mha",
      "NDims = 3\nDimSize = 4 4 4\nelementtype = MET_DOUBLE\nElementType = MET_UCHAR\n"
      "ElementDataFile = LOCAL\n" +
        Voxels(),
      "'elementtype' is 'ElementType' in another letter case" },
    { "z-random.mha",
      Mha + "CompressedData = True\nCompressedDataSize = 200\nElementDataFile = LOCAL\n" +
        Random(200),
      "do not inflate" },
    { "z-short.mha",
      Mha + "CompressedData = True\nCompressedDataSize = " + std::to_string(z.size() / 2) +
        "\nElementDataFile = LOCAL\n" + z.substr(0, z.size() / 2),
      "inflate to" },
    { "z-devzero.mhd", Mha + "CompressedData = True\nElementDataFile = /dev/zero\n",
      "is not a regular file" },
    { "ascii-few.mha", Mha + "BinaryData = False\nElementDataFile = LOCAL\n1 2 3\n",
      "hold 3 values as text, the header claims 64" },
    { "step-zero.mhd", Mha + "ElementDataFile = s%d.raw 0 3 0\n", "steps by 0" },
    { "data-file-case.nhdr", Nrrd + "encoding: raw\nData File: voxels.raw\n",
      "'Data File' is 'data file' in another letter case" },
    { "gz-garbage.nhdr", Nrrd + "encoding: gzip\ndata file: garbage.raw.gz\n", "do not inflate" },
    { "gz-short.nrrd", Nrrd + "encoding: gzip\n\n" + gz.substr(0, gz.size() / 2), "inflate to" },
    { "gz-devzero.nhdr", Nrrd + "encoding: gzip\ndata file: /dev/zero\n", "is not a regular file" },
    { "ascii-few.nhdr",
      "NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 2\nencoding: ascii\ndata file: few.txt\n",
      "hold 7 values as text, the header claims 8" },
    { "ascii-attached.nrrd",
      "NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 2\nencoding: ascii\n\n1 2 3 4 5 6 7 8\n",
      "ASCII NRRD data attached" },
    { "two-data-files.nhdr", Nrrd + "encoding: raw\ndata file: voxels.raw\ndatafile: voxels.raw\n",
      "names its data file 2 times" },
    { "nan-spacing.vti", Vti("Spacing=\"NaN 3.2 1.5\""),
      "Spacing 'NaN 3.2 1.5' is not 3 finite numbers" },
    { "text-spacing.vti", Vti("Spacing=\"abc 1.5 2\""), "Spacing 'abc 1.5 2' is not 3" },
    { "two-spacings.vti", Vti("Spacing=\"1 1.5\""), "Spacing '1 1.5' is not 3" },
    { "infinite-origin.vti", Vti("Origin=\"1e999 0 0\""), "Origin '1e999 0 0' is not 3" },
    { "six-direction.vti", Vti("Direction=\"1 0 0 0 1 0\""), "Direction '1 0 0 0 1 0' is not 9" },
    { "nan-direction.vti", Vti("Direction=\"nan 0 0 0 1 0 0 0 1\""),
      "Direction 'nan 0 0 0 1 0 0 0 1' is not 9 finite numbers" },
    // Attributes VTK's reader allocates for before the scalars.
    { "color-first.vtk",
      Vtk + "DIMENSIONS 1000 1000 1000\nPOINT_DATA 1000000000\nCOLOR_SCALARS c 4\n" +
        std::string(100, '\0'),
      "COLOR_SCALARS of 1000000000 x 4 values need 4000000000 bytes" },
    { "lut-first.vtk",
      Vtk + "DIMENSIONS 2 2 2\nPOINT_DATA 8\nLOOKUP_TABLE t 1000000000\n" + std::string(10, '\0'),
      "LOOKUP_TABLE of 1000000000 x 4 values" },
    { "field-first.vtk",
      Vtk + "DIMENSIONS 2 2 2\nPOINT_DATA 8\nFIELD f 1\nbig 4 1000000000 double\n" +
        std::string(10, '\0'),
      "FIELD array of 1000000000 x 4 values" },
    { "ascii-few.vtk",
      "# vtk DataFile Version 3.0\nhostile\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n"
      "POINT_DATA 8\nSCALARS s short\nLOOKUP_TABLE default\n1 2 3 4 5 6 7\n",
      "SCALARS of 8 x 1 values as text hold 7 numbers" },
    // Another format's bytes under the extension: named as such, not by
    // what the parser met further in (a NUL byte, a header past 1 MiB).
    { "gzip-named.nrrd", gz + std::string(2 << 20, '\0'), "not a NRRD file (no NRRD magic)" },
    { "nifti-named.mha", std::string("\x5c\x01\x00\x00", 4) + std::string(2 << 20, 'x'),
      "not a MetaImage header (it does not begin with a 'Key = Value' line)" },
    { "dicom-named.mha", std::string(128, '\0') + "DICM" + std::string(100, 'y'),
      "not a MetaImage header (it does not begin with a 'Key = Value' line)" },
  };
}

// Exit status 2, one line naming why, no output written.
void ExpectRefused(const std::string& input, const std::string& why)
{
  const std::string output = Temporary("hostile_text_never.pfm");
  const Result r = RunCLI("render " + input + " --samples 1023 --output " + output);
  EXPECT_EQ(2, r.Status) << input << "\n" << r.Errors;
  EXPECT_EQ(0u, r.Errors.find("mcxray: error: cannot read '")) << input << "\n" << r.Errors;
  EXPECT_EQ(r.Errors.size() - 1, r.Errors.find('\n')) << input << "\n" << r.Errors;
  EXPECT_NE(std::string::npos, r.Errors.find(why)) << input << "\n" << r.Errors;
  EXPECT_FALSE(vtksys::SystemTools::FileExists(output)) << input;
}

// What a reader class says on Update: its error events, and what anything
// (MetaIO) wrote to std::cerr meanwhile.
struct Said
{
  std::vector<std::string> Errors;
  std::string Cerr;
  long long Points = 0;
  std::string Bytes; // the scalars' bytes
};

template <class Reader>
Said UpdateReader(const std::string& path)
{
  vtkNew<Reader> reader;
  reader->SetFileName(path.c_str());
  Said said;
  vtkNew<vtkCallbackCommand> errors;
  errors->SetClientData(&said.Errors);
  errors->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      static_cast<std::vector<std::string>*>(clientData)
        ->push_back(callData ? static_cast<const char*>(callData) : "");
    });
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  std::stringstream cerr;
  std::streambuf* saved = std::cerr.rdbuf(cerr.rdbuf());
  reader->Update();
  std::cerr.rdbuf(saved);
  said.Cerr = cerr.str();
  said.Points = reader->GetOutput()->GetNumberOfPoints();
  if (vtkDataArray* scalars = reader->GetOutput()->GetPointData()->GetScalars())
  {
    said.Bytes.assign(static_cast<const char*>(scalars->GetVoidPointer(0)),
      static_cast<std::size_t>(scalars->GetNumberOfValues() * scalars->GetDataTypeSize()));
  }
  return said;
}
}

TEST(HostileTextFormats, EachShapeIsOneLineAndExitStatusTwo)
{
  const std::string folder = Folder();
  for (const Hostile& shape : Shapes(folder))
  {
    const std::string path = folder + "/" + shape.Name;
    WriteBytes(path, shape.Bytes);
    ExpectRefused(path, shape.Why);
  }
}

TEST(HostileTextFormats, TheFormatReadersRefuseTheSameFilesWithOneError)
{
  const std::string folder = Folder();
  for (const Hostile& shape : Shapes(folder))
  {
    const std::string path = folder + "/" + shape.Name;
    WriteBytes(path, shape.Bytes);
    const bool meta = vtksys::SystemTools::GetFilenameLastExtension(path).compare(0, 3, ".mh") == 0;
    const bool nrrd = !meta && path.find(".n") != std::string::npos;
    if (!meta && !nrrd)
    {
      continue; // legacy VTK: mcxray's reader, checked by the command line above
    }
    const Said said =
      meta ? UpdateReader<vtkMCXMetaImageReader>(path) : UpdateReader<vtkMCXNrrdReader>(path);
    ASSERT_EQ(1u, said.Errors.size()) << path;
    EXPECT_EQ(0, said.Points) << path;
    EXPECT_NE(std::string::npos, said.Errors[0].find("cannot read '" + path + "': "))
      << said.Errors[0];
    EXPECT_NE(std::string::npos, said.Errors[0].find(shape.Why)) << said.Errors[0];
    EXPECT_EQ("", said.Cerr) << path;
  }
}

TEST(HostileTextFormats, ADataFileGivenAsOutputIsRefusedAndLeftIntact)
{
  // Each way a header names its data: the guard must protect what the
  // reader opens, by the reader's own rules.
  const std::string folder = Folder();
  struct Form
  {
    std::string Header, Text;
    std::vector<std::string> Files; // what the reader reads (one slice each if several)
    std::string Target;
  };
  const std::vector<Form> forms = {
    { "colon.mhd", Mha + "ElementDataFile: colon.pfm\n", { "colon.pfm" }, "colon.pfm" },
    { "indented.mhd", Mha + "   ElementDataFile   =   indented.pfm\n", { "indented.pfm" },
      "indented.pfm" },
    // No range: MetaIO reads 1 to 4 (the last axis' size), not 0.
    { "norange.mhd", Mha + "ElementDataFile = norange%d.pfm\n",
      { "norange1.pfm", "norange2.pfm", "norange3.pfm", "norange4.pfm" }, "norange4.pfm" },
    // A first number alone: four from it.
    { "first.mhd", Mha + "ElementDataFile = first%02d.pfm 7\n",
      { "first07.pfm", "first08.pfm", "first09.pfm", "first10.pfm" }, "first10.pfm" },
    { "range.mhd", Mha + "ElementDataFile = range%d.pfm 2 8 2\n",
      { "range2.pfm", "range4.pfm", "range6.pfm", "range8.pfm" }, "range8.pfm" },
    { "datafile.nhdr", Nrrd + "encoding: raw\ndatafile: datafile.pfm\n", { "datafile.pfm" },
      "datafile.pfm" },
    // Fewer than four words: vtkNrrdReader opens the name as it is.
    { "percent.nhdr", Nrrd + "encoding: raw\ndata file: percent%d.pfm\n", { "percent%d.pfm" },
      "percent%d.pfm" },
    { "pattern.nhdr", Nrrd + "encoding: raw\ndata file: pattern%03d.pfm 1 4 1 2\n",
      { "pattern001.pfm", "pattern002.pfm", "pattern003.pfm", "pattern004.pfm" },
      "pattern004.pfm" },
  };
  for (const Form& form : forms)
  {
    const std::string header = folder + "/" + form.Header;
    WriteBytes(header, form.Text);
    for (const std::string& file : form.Files)
    {
      WriteBytes(folder + "/" + file, Voxels().substr(0, 64 / form.Files.size()));
    }
    const std::string target = folder + "/" + form.Target;
    const std::vector<std::string> named = mcxio::DataFiles(header);
    ASSERT_EQ(form.Files.size(), named.size()) << form.Header;
    EXPECT_EQ(target, named.back()) << form.Header;
    unsigned long long claimed = 0;
    std::string error;
    EXPECT_TRUE(mcxio::CheckVolumeHeader(header, claimed, error)) << form.Header << ": " << error;
    const std::string before = Slurp(target);
    const Result r = RunCLI("render '" + header + "' --samples 1023 --output '" + target + "'");
    EXPECT_EQ(2, r.Status) << form.Header << "\n" << r.Errors;
    EXPECT_NE(std::string::npos, r.Errors.find("refusing to overwrite")) << r.Errors;
    EXPECT_EQ(r.Errors.size() - 1, r.Errors.find('\n')) << r.Errors;
    EXPECT_EQ(before, Slurp(target)) << form.Header << " let the output overwrite " << target;
  }
}

TEST(HostileTextFormats, AVTIsParsablePlacementPasses)
{
  const std::string folder = Folder();
  for (const std::string& placement : { std::string(),
         std::string("Origin=\"-1.5 2 1e-3\" Spacing=\"0.5 .5 2E0\" "
                     "Direction=\"6.123233995736766e-17 1 -0 -1 6.123233995736766e-17 0 0 "
                     "0 1E+00\"") })
  {
    const std::string path = folder + "/placed.vti";
    WriteBytes(path, Vti(placement));
    unsigned long long claimed = 0;
    std::string error;
    EXPECT_TRUE(mcxio::CheckVolumeHeader(path, claimed, error)) << placement << ": " << error;
  }
}

TEST(HostileTextFormats, ASparseFileOfOneEndlessTokenIsRefusedQuickly)
{
  // 2 GiB of holes (NUL bytes, no whitespace) after a legacy header: one
  // token that the check must not gather.
  const std::string folder = Folder();
  const std::string path = folder + "/sparse.vtk";
  WriteBytes(path,
    "# vtk DataFile Version 3.0\nsparse\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n"
    "POINT_DATA 8\nSCALARS s short\nLOOKUP_TABLE default\n");
  ASSERT_EQ(0, ::truncate(path.c_str(), 2LL << 30));
  const auto start = std::chrono::steady_clock::now();
  ExpectRefused(path, "a token longer than 255 characters");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
  vtksys::SystemTools::RemoveFile(path);
}

TEST(HostileTextFormats, ValidTextFormatsStillRead)
{
  // The checks' stricter parse accepts what the readers read well.
  const std::string folder = Folder();
  WriteBytes(folder + "/ok.raw", Voxels());
  const std::string z = Deflated(Voxels(), 15), gz = Deflated(Voxels(), 31);
  const std::vector<std::pair<std::string, std::string>> files = {
    { "ok.mhd", Mha + "ElementDataFile = ok.raw\n" },
    { "ok-indented.mha", Mha + "   ElementDataFile : LOCAL\n" + Voxels() },
    { "ok-z.mha",
      Mha + "CompressedData = True\nCompressedDataSize = " + std::to_string(z.size()) +
        "\nElementDataFile = LOCAL\n" + z },
    { "ok-gz.nrrd", Nrrd + "encoding: gzip\n\n" + gz },
    // Two gzip members, as zlib's gzread reads them on.
    { "ok-gz-members.nrrd",
      Nrrd + "encoding: gzip\n\n" + Deflated(Voxels().substr(0, 20), 31) +
        Deflated(Voxels().substr(20), 31) },
    { "ok-ascii.nhdr",
      "NRRD0004\ntype: short\ndimension: 3\nsizes: 10 1 1\nencoding: ascii\ndata file: ok.txt\n" },
    { "ok-ascii.mha",
      "NDims = 3\nDimSize = 10 1 1\nElementType = MET_SHORT\nBinaryData = False\n"
      "ElementDataFile = LOCAL\n1 2 3 4 5 6 7 8 9 10\n" },
  };
  WriteBytes(folder + "/ok.txt", "1 2 3 4 5\n6 7 8 9 10\n");
  std::string ten;
  for (std::int16_t v = 1; v <= 10; ++v)
  {
    ten.append(reinterpret_cast<const char*>(&v), 2);
  }
  for (const auto& file : files)
  {
    const std::string path = folder + "/" + file.first;
    WriteBytes(path, file.second);
    unsigned long long claimed = 0;
    std::string error;
    EXPECT_TRUE(mcxio::CheckVolumeHeader(path, claimed, error)) << file.first << ": " << error;
    const bool meta = file.first.find(".mh") != std::string::npos;
    const Said said =
      meta ? UpdateReader<vtkMCXMetaImageReader>(path) : UpdateReader<vtkMCXNrrdReader>(path);
    EXPECT_TRUE(said.Errors.empty()) << file.first << ": " << said.Errors.front();
    const bool text = file.first.find("ascii") != std::string::npos;
    EXPECT_EQ(text ? 10 : 64, said.Points) << file.first;
    EXPECT_EQ(text ? ten : Voxels(), said.Bytes) << file.first;
    EXPECT_EQ("", said.Cerr) << file.first;
  }
}

TEST(HostileTextFormats, RegressionFilesGiveOneLine)
{
  // Testing/Data/Hostile/README.md: issue 39's text-format files.
  const std::string folder = MCXRAY_TEST_DATA_DIR "/Hostile/";
  const std::pair<const char*, const char*> cases[] = {
    { "hidden-list.mhd", "'elementdatafile' is 'ElementDataFile' in another letter case" },
    { "compressed-random.mha", "do not inflate" },
    { "gzip-garbage.nrrd", "do not inflate" },
    { "color-scalars-first.vtk", "COLOR_SCALARS of 1000000000 x 4 values need 4000000000 bytes" },
  };
  for (const auto& c : cases)
  {
    const auto start = std::chrono::steady_clock::now();
    ExpectRefused(folder + c.first, c.second);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0)
      << c.first;
  }
}

TEST(HostileTextFormats, MetaIOsOwnMessagesBecomeTheReadersOneError)
{
  // With the check off, MetaIO itself meets the random bytes: its
  // "Uncompress failed" on std::cerr becomes the reader's one error.
  const std::string folder = Folder();
  const std::string path = folder + "/unchecked-random.mha";
  WriteBytes(path,
    Mha + "CompressedData = True\nCompressedDataSize = 200\nElementDataFile = LOCAL\n" +
      Random(200));
  vtkNew<vtkMCXMetaImageReader> reader;
  reader->SetFileName(path.c_str());
  reader->CheckHeaderOff();
  std::vector<std::string> errors;
  vtkNew<vtkCallbackCommand> observer;
  observer->SetClientData(&errors);
  observer->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      static_cast<std::vector<std::string>*>(clientData)
        ->push_back(callData ? static_cast<const char*>(callData) : "");
    });
  reader->AddObserver(vtkCommand::ErrorEvent, observer);
  std::stringstream cerr;
  std::streambuf* saved = std::cerr.rdbuf(cerr.rdbuf());
  reader->Update();
  std::cerr.rdbuf(saved);
  EXPECT_EQ("", cerr.str());
  ASSERT_EQ(1u, errors.size());
  EXPECT_NE(std::string::npos, errors[0].find("cannot read '" + path + "': ")) << errors[0];
  EXPECT_NE(std::string::npos, errors[0].find("MetaIO: Uncompress failed")) << errors[0];
  EXPECT_EQ(0, reader->GetOutput()->GetNumberOfPoints());
}

namespace
{
// vtkNrrdReader's data files, as it lists them after its header parse.
class NrrdProbe : public vtkNrrdReader
{
public:
  static NrrdProbe* New();
  vtkTypeMacro(NrrdProbe, vtkNrrdReader);
  std::vector<std::string> Files()
  {
    std::vector<std::string> files;
    for (vtkIdType i = 0; this->ReadHeader() && i < this->DataFiles->GetNumberOfValues(); ++i)
    {
      files.emplace_back(this->DataFiles->GetValue(i));
    }
    return files;
  }
};
vtkStandardNewMacro(NrrdProbe);
}

TEST(HostileTextFormats, TheChecksParseAsTheReadersDo)
{
  // Random headers of key spellings, separators, indentation, repeats and
  // noise: wherever a check passes, VTK's own parser (MetaIO, vtkNrrdReader)
  // reads the same volume from exactly the files DataFiles names.
  const std::string folder = Folder();
  for (const char* file : { "a.raw", "b.raw", "p1.raw", "p2.raw", "p3.raw", "p4.raw", "p%d.raw" })
  {
    WriteBytes(folder + "/" + file, std::string(64, 'x'));
  }
  std::mt19937 random(39);
  auto pick = [&random](const std::vector<std::string>& from)
  { return from[random() % from.size()]; };
  const std::vector<std::string> noise = { "", "", "Foo = bar\n", "garbage line\n", "\n",
    "Comment = x = y\n", ": odd\n", "ndims = 2\n", "elementdatafile = b.raw\n",
    "Offset = 0 0 0\n" };
  const bool warnings = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOff(); // vtkNrrdReader's "Unknown field" warnings
  int passed = 0;
  for (int t = 0; t < 1500; ++t)
  {
    const std::string path = folder + "/random.mha";
    WriteBytes(path,
      pick(noise) + pick({ "NDims = 3\n", "NDims: 3\n", "  NDims = 3\n", "NDims = 2\n" }) +
        pick(noise) + pick({ "DimSize = 4 4 4\n", "DimSize: 4 4 4\n", "DimSize = 4\n4 4\n" }) +
        pick(noise) +
        pick({ "ElementType = MET_UCHAR\n", "ElementType : MET_UCHAR\n",
          "ElementType = met_uchar\n" }) +
        pick(noise) +
        pick({ "ElementDataFile = a.raw\n", "ElementDataFile: b.raw\n",
          "  ElementDataFile = a.raw  \n", "ElementDataFile = p%d.raw\n",
          "ElementDataFile = p%d.raw 1\n", "ElementDataFile = LOCAL\n" }) +
        std::string(64, 'y'));
    unsigned long long claimed = 0;
    std::string error;
    if (!mcxio::CheckVolumeHeader(path, claimed, error))
    {
      continue;
    }
    ++passed;
    vtkmetaio::MetaImage meta;
    std::stringstream said;
    std::streambuf* saved = std::cerr.rdbuf(said.rdbuf());
    const bool read = meta.Read(path.c_str(), false);
    std::cerr.rdbuf(saved);
    ASSERT_TRUE(read) << Slurp(path);
    unsigned long long bytes = meta.ElementType() == vtkmetaio::MET_UCHAR ? 1 : 0;
    for (int a = 0; a < meta.NDims(); ++a)
    {
      bytes *= static_cast<unsigned long long>(meta.DimSize(a));
    }
    EXPECT_EQ(bytes, claimed) << Slurp(path);
    const std::string name = meta.ElementDataFileName();
    std::vector<std::string> expected;
    for (int i = 1; name.find('%') != std::string::npos && i <= meta.DimSize(meta.NDims() - 1); ++i)
    {
      expected.push_back(folder + "/p" + std::to_string(i) + ".raw");
    }
    if (expected.empty() && name != "LOCAL")
    {
      expected.push_back(folder + "/" + name);
    }
    EXPECT_EQ(expected, mcxio::DataFiles(path)) << Slurp(path);
  }
  EXPECT_GT(passed, 100) << "too few headers passed to compare";
  passed = 0;
  for (int t = 0; t < 1000; ++t)
  {
    const std::string path = folder + "/random.nhdr";
    WriteBytes(path,
      "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 16 1 4\nencoding: raw\n" +
        pick({ "", "content: x\n", "Type: short\n", "foo: bar\n", "# data file: b.raw\n" }) +
        pick(
          { "data file: a.raw\n", "datafile: b.raw\n", "Data File: a.raw\n", "data file: p%d.raw\n",
            "data file: p%d.raw 1 4 1\n", "data file: p%d.raw 1 4 1 3\n", "data file:a.raw\n",
            "data file:  a.raw  \n", "DATAFILE: b.raw\n", "data file := b.raw\n" }) +
        pick({ "", "datafile: a.raw\n", "space: left-posterior-superior\n" }));
    unsigned long long claimed = 0;
    std::string error;
    if (!mcxio::CheckVolumeHeader(path, claimed, error))
    {
      continue;
    }
    ++passed;
    vtkNew<NrrdProbe> probe;
    probe->SetFileName(path.c_str());
    EXPECT_EQ(probe->Files(), mcxio::DataFiles(path)) << Slurp(path);
  }
  EXPECT_GT(passed, 100) << "too few headers passed to compare";
  vtkObject::SetGlobalWarningDisplay(warnings);
}

TEST(HostileTextFormats, VTKsOwnLegacyFilesPassTheWholeFileWalk)
{
  // What vtkStructuredPointsWriter writes around the scalars (field data
  // first, component names as METADATA, vectors, cell data) passes, ASCII
  // and binary.
  const std::string folder = Folder();
  for (int type : { VTK_ASCII, VTK_BINARY })
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(3, 4, 5);
    vtkNew<vtkFloatArray> scalars;
    scalars->SetName("density");
    scalars->SetNumberOfTuples(60);
    scalars->SetComponentName(0, "HU");
    for (vtkIdType i = 0; i < 60; ++i)
    {
      scalars->SetValue(i, 0.5f * static_cast<float>(i));
    }
    image->GetPointData()->SetScalars(scalars);
    vtkNew<vtkFloatArray> vectors;
    vectors->SetName("flow");
    vectors->SetNumberOfComponents(3);
    vectors->SetNumberOfTuples(60);
    vectors->Fill(1.0);
    image->GetPointData()->SetVectors(vectors);
    vtkNew<vtkDoubleArray> cells, time;
    cells->SetName("cells");
    cells->SetNumberOfTuples(24);
    cells->Fill(2.0);
    image->GetCellData()->AddArray(cells);
    time->SetName("TimeValue");
    time->SetNumberOfTuples(1);
    time->SetValue(0, 3.0);
    image->GetFieldData()->AddArray(time);
    const std::string path = folder + "/written" + std::to_string(type) + ".vtk";
    vtkNew<vtkStructuredPointsWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(path.c_str());
    writer->SetFileType(type);
    ASSERT_EQ(1, writer->Write());
    unsigned long long claimed = 0;
    std::string error;
    EXPECT_TRUE(mcxio::CheckVolumeHeader(path, claimed, error)) << path << ": " << error;
    EXPECT_EQ(60u * 4u, claimed) << path;
    // Cut inside the vectors: the walk finds them short.
    const std::string whole = Slurp(path);
    WriteBytes(path, whole.substr(0, whole.find("VECTORS") + 40));
    EXPECT_FALSE(mcxio::CheckVolumeHeader(path, claimed, error)) << path;
    EXPECT_NE(std::string::npos, error.find("VECTORS")) << error;
  }
}

TEST(HostileTextFormats, WhereTheLegacyCheckPassesVTKsReaderReadsTheClaim)
{
  // Random legacy files (keyword case, FIELD first, EXTENT, CELL_DATA,
  // attributes in any order, arrays one value short): wherever the check
  // passes, vtkStructuredPointsReader reads without error the scalars'
  // bytes the check claims.
  const std::string path = Folder() + "/random.vtk";
  std::mt19937 random(39);
  auto pick = [&random](const std::vector<std::string>& from)
  { return from[random() % from.size()]; };
  int passed = 0;
  for (int t = 0; t < 1000; ++t)
  {
    const bool binary = random() % 2;
    std::string text = "# vtk DataFile Version 3.0\nt\n" +
      std::string(binary ? "BINARY" : "ASCII") + "\nDATASET STRUCTURED_POINTS\n" +
      pick({ "",
        "FIELD FieldData 1\nTimeValue 1 1 double\n" +
          std::string(binary ? std::string(8, '\0') : "3.0") + "\n" }) +
      pick({ "DIMENSIONS 2 2 2\n", "dimensions 2 2 2\n", "EXTENT 0 1 0 1 0 1\n" }) +
      pick({ "", "SPACING 1 1 1\n" }) +
      pick({ "POINT_DATA 8\n", "point_data 8\n", "CELL_DATA 1\n" });
    for (int part = 1 + random() % 3; part > 0; --part)
    {
      const std::string kind = pick({ "SCALARS s short\nLOOKUP_TABLE default\n",
        "SCALARS s float 1\nLOOKUP_TABLE default\n", "COLOR_SCALARS c 1\n", "VECTORS v float\n",
        "scalars s short\nlookup_table default\n", "LOOKUP_TABLE t 2\n", "POINT_DATA 8\n" });
      const bool tuples = kind.find("DATA") == std::string::npos;
      int values = kind[0] == 'V'                    ? 24
        : kind.find("_TABLE t") != std::string::npos ? 8
        : tuples                                     ? 8
                                                     : 0;
      values -= values > 0 && random() % 4 == 0 ? 1 : 0;
      const int size = kind.find("float") != std::string::npos ? 4
        : kind.find("short") != std::string::npos              ? 2
                                                               : 1;
      text += kind;
      for (int v = 0; v < values && !binary; ++v)
      {
        text += "1 ";
      }
      text += binary ? std::string(static_cast<std::size_t>(values * size), '\1') : "";
      text += values ? "\n" : "";
    }
    WriteBytes(path, text);
    unsigned long long claimed = 0;
    std::string error;
    if (!mcxio::CheckVolumeHeader(path, claimed, error))
    {
      continue;
    }
    ++passed;
    vtkNew<vtkStructuredPointsReader> reader;
    reader->SetFileName(path.c_str());
    int errors = 0;
    vtkNew<vtkCallbackCommand> counter;
    counter->SetClientData(&errors);
    counter->SetCallback(
      [](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
    reader->AddObserver(vtkCommand::ErrorEvent, counter);
    reader->Update();
    vtkDataArray* scalars = reader->GetOutput()->GetPointData()->GetScalars();
    EXPECT_EQ(0, errors) << text;
    ASSERT_NE(nullptr, scalars) << text;
    EXPECT_EQ(claimed,
      static_cast<unsigned long long>(scalars->GetNumberOfValues() * scalars->GetDataTypeSize()))
      << text;
  }
  EXPECT_GT(passed, 50) << "too few files passed to compare";
}
