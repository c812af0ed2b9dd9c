// The binary formats against hostile input (issue 39): VTK XML images whose
// data lie where the first check did not look (base64 appended data, inline
// binary data, a second piece or array, cell and field data, past a long
// comment), one-file DICOM claiming 2^31 - 1 frames, garbage compressed
// DICOM pixel data, links that lead back into a DICOM folder, and NIfTI
// given as a FIFO or rescaled under an address-space limit. mcxray refuses
// each with exit status 2 and one line naming the reason, writing nothing;
// the reader classes give one error, an empty output and no crash.
#include "mcxCommandLineRunner.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMCXNIFTIReader.h"
#include "vtkMCXVolumeReader.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtksys/SystemTools.hxx"
#ifdef MCXRAY_TEST_DICOM
#include "vtkMCXDICOMSeriesReader.h"
#endif

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

using mcxtest::Result;
using mcxtest::RunCLI;
using mcxtest::Temporary;

namespace
{
void WriteBytes(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string Base64(const std::string& bytes)
{
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  for (std::size_t i = 0; i < bytes.size(); i += 3)
  {
    unsigned int bits = static_cast<unsigned char>(bytes[i]) << 16;
    bits |= i + 1 < bytes.size() ? static_cast<unsigned char>(bytes[i + 1]) << 8 : 0;
    bits |= i + 2 < bytes.size() ? static_cast<unsigned char>(bytes[i + 2]) : 0;
    text += alphabet[(bits >> 18) & 63];
    text += alphabet[(bits >> 12) & 63];
    text += i + 1 < bytes.size() ? alphabet[(bits >> 6) & 63] : '=';
    text += i + 2 < bytes.size() ? alphabet[bits & 63] : '=';
  }
  return text;
}

// Little-endian UInt32 words (a VTK XML size word or block table).
std::string Words(const std::vector<std::uint32_t>& words)
{
  std::string bytes;
  for (std::uint32_t w : words)
  {
    for (int b = 0; b < 4; ++b)
    {
      bytes += static_cast<char>((w >> (8 * b)) & 0xff);
    }
  }
  return bytes;
}

// One zlib block of n zero bytes with its one-block table.
std::string CompressedZeros(std::size_t n)
{
  std::vector<unsigned char> packed(compressBound(n));
  uLongf size = static_cast<uLongf>(packed.size());
  const std::string zeros(n, '\0');
  compress2(packed.data(), &size, reinterpret_cast<const Bytef*>(zeros.data()), n, 6);
  return Words({ 1, static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(n),
           static_cast<std::uint32_t>(size) }) +
    std::string(reinterpret_cast<const char*>(packed.data()), size);
}

// A block table of 2^31 - 1 blocks and nothing after it: VTK's reader
// allocates 16 GiB for the table, then loops over the blocks.
const std::string LyingTable = Words({ 0x7fffffffu, 32768, 4096 });

std::string Head(bool compressed, const std::string& extent = "0 15 0 15 0 15")
{
  return std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" "
                     "byte_order=\"LittleEndian\" header_type=\"UInt32\"") +
    (compressed ? " compressor=\"vtkZLibDataCompressor\"" : "") + ">\n<ImageData WholeExtent=\"" +
    extent + "\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n";
}

std::string Array(const std::string& format, const std::string& extra, const std::string& inner)
{
  return "<DataArray type=\"UInt8\" Name=\"v\" format=\"" + format + "\" " + extra + ">" + inner +
    "</DataArray>\n";
}

std::string Appended(const std::string& encoding, const std::string& data)
{
  return "</ImageData>\n<AppendedData encoding=\"" + encoding + "\">\n_" + data +
    "\n</AppendedData>\n</VTKFile>\n";
}

const std::string Piece = "<Piece Extent=\"0 15 0 15 0 15\">\n<PointData Scalars=\"v\">\n";
const std::string PieceEnd = "</PointData>\n</Piece>\n";

// Exit status 2, one line naming needle, nothing written; the checked
// reader class gives one error and an empty output.
void ExpectRefused(const std::string& input, const std::string& needle)
{
  const std::string output = Temporary("binary_never.pfm");
  const auto start = std::chrono::steady_clock::now();
  Result r = RunCLI("render " + input + " --samples 1023 --read-timeout 60 --output " + output);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0)
    << input;
  EXPECT_EQ(2, r.Status) << input << "\n" << r.Errors;
  EXPECT_EQ(0u, r.Errors.find("mcxray: error: ")) << input << "\n" << r.Errors;
  EXPECT_EQ(r.Errors.size() - 1, r.Errors.find('\n')) << input << "\n" << r.Errors;
  EXPECT_NE(std::string::npos, r.Errors.find(needle)) << input << "\n" << r.Errors;
  EXPECT_FALSE(vtksys::SystemTools::FileExists(output)) << input;
}

// The errors an algorithm reports while observed: their count and the first.
struct Errors
{
  int Count = 0;
  std::string First;
  vtkNew<vtkCallbackCommand> Callback;
  explicit Errors(vtkAlgorithm* algorithm)
  {
    this->Callback->SetClientData(this);
    this->Callback->SetCallback(
      [](vtkObject*, unsigned long, void* self, void* text)
      {
        auto* errors = static_cast<Errors*>(self);
        errors->First = errors->Count++ ? errors->First : static_cast<const char*>(text);
      });
    algorithm->AddObserver(vtkCommand::ErrorEvent, this->Callback);
  }
};

void ExpectOneReaderError(vtkAlgorithm* reader, const std::string& needle)
{
  Errors errors(reader);
  reader->Update();
  auto* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  EXPECT_EQ(1, errors.Count) << errors.First;
  EXPECT_NE(std::string::npos, errors.First.find(needle)) << errors.First;
  EXPECT_TRUE(!image || image->GetNumberOfPoints() == 0);
}

// Runs body in a child process (a hang or crash there cannot take the test
// with it): its exit status, or -signal, or -1000 past seconds.
int InChild(double seconds, const std::function<int()>& body)
{
  const pid_t child = ::fork();
  if (child == 0)
  {
    ::_exit(body());
  }
  const auto start = std::chrono::steady_clock::now();
  int status = 0;
  while (::waitpid(child, &status, WNOHANG) == 0)
  {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds)
    {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      return -1000;
    }
    ::usleep(20000);
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

// This process's address space now (/proc/self/statm).
unsigned long long MappedBytes()
{
  unsigned long long pages = 0;
  if (FILE* statm = std::fopen("/proc/self/statm", "r"))
  {
    if (std::fscanf(statm, "%llu", &pages) != 1)
    {
      pages = 0;
    }
    std::fclose(statm);
  }
  return pages * static_cast<unsigned long long>(::sysconf(_SC_PAGESIZE));
}
}

TEST(HostileBinaryFormats, VTIDataAreCheckedWhereverTheyLie)
{
  const std::string folder = Temporary("binary_vti");
  vtksys::SystemTools::RemoveADirectory(folder);
  vtksys::SystemTools::MakeDirectory(folder);
  const std::string valid = CompressedZeros(4096);
  const std::string twoPieces = "<Piece Extent=\"0 15 0 15 0 7\">\n<PointData Scalars=\"v\">\n" +
    Array("appended", "offset=\"0\"", "") + PieceEnd +
    "<Piece Extent=\"0 15 0 15 8 15\">\n<PointData Scalars=\"v\">\n" +
    Array("appended", "offset=\"" + std::to_string(CompressedZeros(2048).size()) + "\"", "") +
    PieceEnd;
  struct Case
  {
    std::string Name, Bytes, Needle;
  };
  const std::vector<Case> cases = {
    { "base64-appended.vti",
      Head(true) + Piece + Array("appended", "offset=\"0\"", "") + PieceEnd +
        Appended("base64", Base64(LyingTable)),
      "block table" },
    { "inline-compressed.vti",
      Head(true) + Piece + Array("binary", "", Base64(LyingTable)) + PieceEnd +
        "</ImageData>\n</VTKFile>\n",
      "block table" },
    { "inline-raw.vti",
      Head(false) + Piece + Array("binary", "", Base64(Words({ 0x7fffffffu }) + "abc")) + PieceEnd +
        "</ImageData>\n</VTKFile>\n",
      "where its extent needs 4 KiB" },
    { "second-piece.vti",
      Head(true) + twoPieces + Appended("raw", CompressedZeros(2048) + LyingTable), "block table" },
    { "second-array.vti",
      Head(true) + Piece + Array("appended", "offset=\"0\"", "") +
        "<DataArray type=\"Float64\" Name=\"w\" format=\"appended\" offset=\"" +
        std::to_string(valid.size()) + "\"/>\n" + PieceEnd + Appended("raw", valid + LyingTable),
      "'w' end inside their block table" },
    { "cell-data.vti",
      Head(true) + Piece + Array("appended", "offset=\"0\"", "") +
        "</PointData>\n<CellData>\n<DataArray type=\"Int32\" Name=\"c\" format=\"appended\" "
        "offset=\"" +
        std::to_string(valid.size()) + "\"/>\n</CellData>\n</Piece>\n" +
        Appended("raw", valid + LyingTable),
      "'c' end inside their block table" },
    { "field-data.vti",
      Head(false) +
        "<FieldData>\n<DataArray type=\"Float64\" Name=\"f\" NumberOfTuples=\"1000000\" "
        "format=\"ascii\">1 2 3</DataArray>\n</FieldData>\n" +
        Piece + Array("ascii", "", std::string(8191, ' ')) + PieceEnd +
        "</ImageData>\n</VTKFile>\n",
      "ascii array 'f' needs 1000000 values" },
    { "field-data-huge.vti",
      Head(false) +
        "<FieldData>\n<DataArray type=\"Float64\" Name=\"f\" NumberOfTuples=\"2147483647\" "
        "format=\"ascii\">1 2 3</DataArray>\n</FieldData>\n" +
        Piece + Array("ascii", "", std::string(8191, ' ')) + PieceEnd +
        "</ImageData>\n</VTKFile>\n",
      "(16 GiB) from 8.46 KiB of compressed data, more than deflate can hold" },
    { "components.vti",
      Head(false) + Piece + Array("appended", "NumberOfComponents=\"1000000\" offset=\"0\"", "") +
        PieceEnd + Appended("raw", Words({ 4096 }) + std::string(4096, '\0')),
      "NumberOfComponents" },
    { "long-comment.vti",
      Head(true) + "<!-- " + std::string(100000, 'x') + " -->\n" + Piece +
        Array("appended", "offset=\"0\"", "") + PieceEnd + Appended("raw", LyingTable),
      "block table" },
    { "long-attribute.vti",
      Head(true) + Piece +
        Array("appended", "offset=\"0\" Note=\"" + std::string(100000, 'y') + "\"", "") + PieceEnd +
        Appended("raw", LyingTable),
      "block table" },
    { "huge-header.vti",
      Head(false) + "<!-- " + std::string(17 << 20, 'x') + " -->\n" + Piece +
        Array("appended", "offset=\"0\"", "") + PieceEnd +
        Appended("raw", Words({ 4096 }) + std::string(4096, '\0')),
      "longer than 16 MiB" },
  };
  for (const Case& c : cases)
  {
    const std::string path = folder + "/" + c.Name;
    WriteBytes(path, c.Bytes);
    SCOPED_TRACE(c.Name);
    ExpectRefused(path, c.Needle);
    vtkNew<vtkMCXVolumeReader> reader;
    reader->SetFileName(path.c_str());
    ExpectOneReaderError(reader, c.Needle);
  }
  // The same shapes told the truth read (the check is no stricter than VTK).
  const std::string good = folder + "/two-pieces.vti";
  WriteBytes(
    good, Head(true) + twoPieces + Appended("raw", CompressedZeros(2048) + CompressedZeros(2048)));
  vtkNew<vtkMCXVolumeReader> reader;
  reader->SetFileName(good.c_str());
  reader->Update();
  ASSERT_EQ(4096, reader->GetOutput()->GetNumberOfPoints());
  // The claim of every array and of field data meets the memory budget.
  const std::string budget = folder + "/budget.vti";
  WriteBytes(budget,
    Head(false, "0 15 0 15 0 15") +
      "<FieldData>\n<DataArray type=\"Float64\" Name=\"f\" "
      "NumberOfTuples=\"1000000\" format=\"appended\" offset=\"0\"/>\n</FieldData>\n" +
      Piece + Array("appended", "offset=\"8000004\"", "") + PieceEnd +
      Appended("raw",
        Words({ 8000000 }) + std::string(8000000, '\0') + Words({ 4096 }) +
          std::string(4096, '\0')));
  reader->SetFileName(budget.c_str());
  reader->SetMemoryBudget(4 << 20);
  ExpectOneReaderError(reader, "more than the memory budget of 4 MiB");
  reader->SetMemoryBudget(0);
  reader->Update();
  EXPECT_EQ(4096, reader->GetOutput()->GetNumberOfPoints());
}

TEST(HostileBinaryFormats, RegressionFilesGiveOneLine)
{
  // Testing/Data/Hostile/README.md: each once made VTK's reader allocate
  // 16 GiB for a block table (an uncaught bad_alloc under a limit).
  for (const char* name : { "base64-block-table.vti", "inline-block-table.vti" })
  {
    const std::string path = std::string(MCXRAY_TEST_DATA_DIR "/Hostile/") + name;
    SCOPED_TRACE(name);
    ExpectRefused(
      path, "the compressed data of the image's array 'v' end inside their block table");
    vtkNew<vtkMCXVolumeReader> reader;
    reader->SetFileName(path.c_str());
    ExpectOneReaderError(reader, "block table");
  }
}

TEST(HostileBinaryFormats, NiftiReaderRefusesAFifoAndBudgetsItsRescaledCopy)
{
  const std::string fifo = Temporary("binary_fifo.nii");
  ASSERT_EQ(0, ::mkfifo(fifo.c_str(), 0600));
  // CheckHeader off (what vtkMCXVolumeReader sets): the class itself refuses.
  const int status = InChild(20,
    [&]
    {
      vtkNew<vtkMCXNIFTIReader> reader;
      reader->SetFileName(fifo.c_str());
      reader->CheckHeaderOff();
      Errors errors(reader);
      reader->Update();
      return errors.Count == 1 && errors.First.find("not a regular file") != std::string::npos ? 0
                                                                                               : 1;
    });
  EXPECT_EQ(0, status) << "-1000: the reader blocked on the FIFO";
  vtksys::SystemTools::RemoveFile(fifo);

  // uint8 voxels with scl_slope: the float64 copy is 8 times the file; under
  // an address-space limit it is one error, not a crash.
  const std::string path = Temporary("binary_slope.nii");
  std::string header(352, '\0');
  auto put = [&](std::size_t offset, const void* value, std::size_t size)
  { std::memcpy(&header[offset], value, size); };
  const std::int32_t size = 348;
  const std::int16_t dims[4] = { 3, 256, 256, 256 }, datatype = 2, bitpix = 8;
  const float pixdim[4] = { 1, 1, 1, 1 }, offset = 352, slope = 2.0f, inter = 1.0f;
  put(0, &size, 4);
  put(40, dims, 8);
  put(70, &datatype, 2);
  put(72, &bitpix, 2);
  put(76, pixdim, 16);
  put(108, &offset, 4);
  put(112, &slope, 4);
  put(116, &inter, 4);
  put(344, "n+1", 4);
  WriteBytes(path, header + std::string(1 << 24, '\1'));
  if (MCXRAY_TEST_SANITIZED)
  {
    vtksys::SystemTools::RemoveFile(path);
    GTEST_SKIP() << "an address-space limit AddressSanitizer cannot live under (the unsanitized "
                    "build runs it)";
  }
  const int limited = InChild(120,
    [&]
    {
      // Room for the stored voxels, not for their float64 copy (128 MiB).
      const rlim_t room = static_cast<rlim_t>(MappedBytes() + (96ULL << 20));
      struct rlimit limit = { room, room };
      ::setrlimit(RLIMIT_AS, &limit);
      vtkNew<vtkMCXNIFTIReader> reader;
      reader->SetFileName(path.c_str());
      Errors errors(reader);
      reader->Update();
      return errors.Count == 1 && errors.First.find("out of memory") != std::string::npos &&
          reader->GetOutput()->GetNumberOfPoints() == 0
        ? 0
        : 1;
    });
  EXPECT_EQ(0, limited) << "a negative status: the reader died of its signal";
  // Without a limit the same file reads, scaled.
  vtkNew<vtkMCXNIFTIReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  ASSERT_EQ(1 << 24, reader->GetOutput()->GetNumberOfPoints());
  EXPECT_EQ(3.0, reader->GetOutput()->GetPointData()->GetScalars()->GetComponent(12345, 0));
  vtksys::SystemTools::RemoveFile(path);
}

TEST(HostileBinaryFormats, SLCOfOneLongTokenIsRefusedQuickly)
{
  // 64 MiB of digits: the check reads 4 KiB of them, not a number's text;
  // so too for a slice's compressed size after a valid header.
  const std::string path = Temporary("binary_digits.slc");
  WriteBytes(path, std::string(64 << 20, '1'));
  ExpectRefused(path, "token longer than 64 characters");
  WriteBytes(path, "11111 2 2 1 8 1 1 1 0 0 0 1\n1 1 X\n\x01\x02\x03" + std::string(64 << 20, '7'));
  ExpectRefused(path, "slice 0 of 1 has no positive compressed size");
}

#ifdef MCXRAY_TEST_DICOM
namespace
{
// One DICOM element in explicit VR little endian, its value padded to even.
std::string Element(std::uint16_t group, std::uint16_t element, const char* vr, std::string value)
{
  if (value.size() % 2)
  {
    value += std::string(vr) == "UI" ? '\0' : ' ';
  }
  std::string bytes;
  auto u16 = [&](std::uint16_t v)
  { bytes += static_cast<char>(v & 0xff), bytes += static_cast<char>(v >> 8); };
  auto u32 = [&](std::uint32_t v)
  { u16(static_cast<std::uint16_t>(v & 0xffff)), u16(static_cast<std::uint16_t>(v >> 16)); };
  u16(group);
  u16(element);
  bytes += vr;
  const std::string longForm = "OB OW SQ UN UT";
  if (longForm.find(vr) != std::string::npos)
  {
    u16(0);
    u32(static_cast<std::uint32_t>(value.size()));
  }
  else
  {
    u16(static_cast<std::uint16_t>(value.size()));
  }
  return bytes + value;
}

std::string US(std::uint16_t v)
{
  return std::string{ static_cast<char>(v & 0xff), static_cast<char>(v >> 8) };
}

// A CT image of rows x columns int16 at z, frames claimed (0: no
// NumberOfFrames), pixel data as given: native bytes, or (fragments not
// empty) encapsulated fragments of the transfer syntax.
std::string Dicom(const std::string& syntax, int z, long long frames, const std::string& pixels,
  const std::vector<std::string>& fragments = {})
{
  const std::string meta = Element(0x0002, 0x0001, "OB", std::string("\0\1", 2)) +
    Element(0x0002, 0x0002, "UI", "1.2.840.10008.5.1.4.1.1.2") +
    Element(0x0002, 0x0003, "UI", "1.2.3.4.5." + std::to_string(z + 1)) +
    Element(0x0002, 0x0010, "UI", syntax);
  std::string length;
  for (int b = 0; b < 4; ++b)
  {
    length += static_cast<char>((meta.size() >> (8 * b)) & 0xff);
  }
  std::string data = std::string(128, '\0') + "DICM" + Element(0x0002, 0x0000, "UL", length) +
    meta + Element(0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2") +
    Element(0x0008, 0x0018, "UI", "1.2.3.4.5." + std::to_string(z + 1)) +
    Element(0x0008, 0x0060, "CS", "CT") + Element(0x0010, 0x0020, "LO", "HOSTILE") +
    Element(0x0020, 0x000D, "UI", "1.2.3.4.1") + Element(0x0020, 0x000E, "UI", "1.2.3.4.2") +
    Element(0x0020, 0x0013, "IS", std::to_string(z + 1)) +
    Element(0x0020, 0x0032, "DS", "0\\0\\" + std::to_string(z)) +
    Element(0x0020, 0x0037, "DS", "1\\0\\0\\0\\1\\0") + Element(0x0028, 0x0002, "US", US(1)) +
    Element(0x0028, 0x0004, "CS", "MONOCHROME2") +
    (frames ? Element(0x0028, 0x0008, "IS", std::to_string(frames)) : std::string()) +
    Element(0x0028, 0x0010, "US", US(16)) + Element(0x0028, 0x0011, "US", US(16)) +
    Element(0x0028, 0x0030, "DS", "1\\1") + Element(0x0028, 0x0100, "US", US(16)) +
    Element(0x0028, 0x0101, "US", US(16)) + Element(0x0028, 0x0102, "US", US(15)) +
    Element(0x0028, 0x0103, "US", US(1));
  if (fragments.empty())
  {
    return data + Element(0x7FE0, 0x0010, "OW", pixels);
  }
  data += std::string("\xe0\x7f\x10\x00OB\0\0\xff\xff\xff\xff", 12);
  const std::string item("\xfe\xff\x00\xe0", 4);
  data += item + std::string(4, '\0'); // an empty offset table
  for (std::string fragment : fragments)
  {
    fragment += fragment.size() % 2 ? std::string(1, '\0') : std::string();
    data += item + Words({ static_cast<std::uint32_t>(fragment.size()) }).substr(0, 4) + fragment;
  }
  return data + std::string("\xfe\xff\xdd\xe0\0\0\0\0", 8);
}

std::string Garbage(std::size_t n, unsigned seed)
{
  std::mt19937 random(seed);
  std::string bytes(n, '\0');
  for (char& c : bytes)
  {
    c = static_cast<char>(random() & 0x7f); // never 0xff: no marker
  }
  return bytes;
}

// A folder holding one file.
std::string OneFileFolder(const std::string& name, const std::string& bytes)
{
  const std::string folder = Temporary(name);
  vtksys::SystemTools::RemoveADirectory(folder);
  vtksys::SystemTools::MakeDirectory(folder);
  WriteBytes(folder + "/image.dcm", bytes);
  return folder;
}
}

TEST(HostileBinaryFormats, DicomPixelDataAreCheckedBeforeVtkDicomTrustsThem)
{
  const std::string native = "1.2.840.10008.1.2.1";
  struct Case
  {
    std::string Name, Bytes, Needle;
  };
  const std::vector<Case> cases = {
    { "frames", Dicom(native, 0, 2147483647LL, std::string(512, '\0')),
      "claims 2147483647 frames of 16x16" },
    { "short", Dicom(native, 0, 0, std::string(100, '\0')), "truncated" },
    { "jpeg-ls", Dicom("1.2.840.10008.1.2.4.80", 0, 0, "", { Garbage(300, 1) }),
      "no start marker" },
    { "jpeg2000", Dicom("1.2.840.10008.1.2.4.90", 0, 0, "", { Garbage(300, 2) }),
      "no start marker" },
    { "jpeg-lossless", Dicom("1.2.840.10008.1.2.4.70", 0, 0, "", { Garbage(300, 3) }),
      "no start marker" },
    { "rle", Dicom("1.2.840.10008.1.2.5", 0, 0, "", { Garbage(300, 4) }), "not RLE data" },
    { "rle-short",
      Dicom("1.2.840.10008.1.2.5", 0, 0, "",
        { Words({ 2, 64, 66 }) + std::string(52, '\0') + std::string("\x01\x00\x01\x00", 4) }),
      "does not decode to a whole frame" },
    { "jpeg-frames", Dicom("1.2.840.10008.1.2.4.80", 0, 3, "", { "\xff\xd8" + Garbage(300, 5) }),
      "hold 1 of its 3 frames" },
    { "mpeg2", Dicom("1.2.840.10008.1.2.4.100", 0, 0, "", { Garbage(300, 6) }),
      "not one this reader decodes" },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE(c.Name);
    const std::string folder = OneFileFolder("binary_dicom_" + c.Name, c.Bytes);
    ExpectRefused(folder, c.Needle);
    const int status = InChild(60,
      [&]
      {
        vtkNew<vtkMCXDICOMSeriesReader> reader;
        reader->SetDirectoryName(folder.c_str());
        Errors errors(reader);
        reader->Update();
        return errors.Count == 1 && errors.First.find(c.Needle) != std::string::npos &&
            reader->GetOutput()->GetNumberOfPoints() == 0
          ? 0
          : 1;
      });
    EXPECT_EQ(0, status) << "not one error naming the reason (negative: a crash)";
  }
}

TEST(HostileBinaryFormats, TheOutputGuardKnowsEveryFileTheSeriesReaderReads)
{
  // Slices without the 128-byte preamble and "DICM", named as images the
  // command writes: vtk-dicom still reads them, so they are the input. The
  // guard walks the folder as the reader does, each folder once (100 links
  // to itself and one to '..' notwithstanding), quickly.
  const std::string folder = Temporary("binary_dicom_no_preamble");
  vtksys::SystemTools::RemoveADirectory(folder);
  vtksys::SystemTools::MakeDirectory(folder);
  const std::vector<std::string> names = { "IM0.png", "IM1.pfm", "IM2.vti" };
  for (int z = 0; z < 3; ++z)
  {
    const std::string pixels(512, static_cast<char>(z + 1));
    WriteBytes(folder + "/" + names[z], Dicom("1.2.840.10008.1.2.1", z, 0, pixels).substr(128 + 4));
  }
  ASSERT_EQ(0, ::symlink("..", (folder + "/up").c_str()));
  for (int l = 0; l < 100; ++l)
  {
    ASSERT_EQ(0, ::symlink(".", (folder + "/self" + std::to_string(l)).c_str()));
  }
  vtkNew<vtkMCXDICOMSeriesReader> reader;
  reader->SetDirectoryName(folder.c_str());
  reader->Update();
  ASSERT_EQ(16 * 16 * 3, reader->GetOutput()->GetNumberOfPoints()) << "vtk-dicom reads them";
  for (const std::string& output : { folder + "/IM0.png", folder + "/self7/IM1.pfm",
         folder + "/up/binary_dicom_no_preamble/IM2.vti" })
  {
    const std::string before = mcxtest::Slurp(output);
    const auto start = std::chrono::steady_clock::now();
    Result r = RunCLI("render " + folder + " --samples 1023 --size 16x16 --output " + output);
    EXPECT_EQ(2, r.Status) << r.Errors;
    EXPECT_EQ(
      0u, r.Errors.find("mcxray: error: the output '" + output + "' is the input volume's file '"))
      << r.Errors;
    EXPECT_NE(
      std::string::npos, r.Errors.find("'; refusing to overwrite it (choose another --output)\n"))
      << r.Errors;
    EXPECT_EQ(before, mcxtest::Slurp(output));
    EXPECT_LT(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 60.0);
  }
}

TEST(HostileBinaryFormats, LinksInADicomFolderAddNothing)
{
  // A valid series of 3 slices, a link to '..' beside them, links to the
  // slices and 100 links to the folder itself: one series, each image once,
  // read quickly.
  const std::string top = Temporary("binary_dicom_links");
  vtksys::SystemTools::RemoveADirectory(top);
  const std::string folder = top + "/series";
  vtksys::SystemTools::MakeDirectory(folder);
  for (int z = 0; z < 3; ++z)
  {
    std::string pixels;
    for (int v = 0; v < 256; ++v)
    {
      pixels += US(static_cast<std::uint16_t>(100 * z + v % 16));
    }
    WriteBytes(
      folder + "/slice" + std::to_string(z) + ".dcm", Dicom("1.2.840.10008.1.2.1", z, 0, pixels));
  }
  ASSERT_EQ(0, ::symlink("..", (folder + "/up").c_str()));
  // A folder of links to the slices (as viewers' exports make them): the
  // same files, each read once (vtk-dicom saw duplicated images).
  vtksys::SystemTools::MakeDirectory(folder + "/linked");
  for (int z = 0; z < 3; ++z)
  {
    const std::string name = "slice" + std::to_string(z) + ".dcm";
    ASSERT_EQ(0, ::symlink(("../" + name).c_str(), (folder + "/linked/" + name).c_str()));
  }
  for (int l = 0; l < 100; ++l)
  {
    ASSERT_EQ(0, ::symlink(".", (folder + "/self" + std::to_string(l)).c_str()));
  }
  const std::string output = Temporary("binary_links.pfm");
  const auto start = std::chrono::steady_clock::now();
  Result r = RunCLI("render " + folder + " --samples 1023 --size 16x16 --quiet --output " + output);
  EXPECT_EQ(0, r.Status) << r.Errors;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 60.0);
  vtkNew<vtkMCXDICOMSeriesReader> reader;
  reader->SetDirectoryName(folder.c_str());
  reader->Update();
  EXPECT_EQ(1, reader->GetNumberOfSeries());
  ASSERT_EQ(16 * 16 * 3, reader->GetOutput()->GetNumberOfPoints());
  EXPECT_EQ(203.0, reader->GetOutput()->GetPointData()->GetScalars()->GetComponent(2 * 256 + 3, 0));
  // Its 1.5 KiB of voxels against a budget, before vtk-dicom allocates.
  reader->SetMemoryBudget(1000);
  reader->Modified();
  ExpectOneReaderError(
    reader, "its voxels need 1.5 KiB, more than the memory budget of 1000 bytes");
}
#endif
