// The checked readers (mcxio::ReadVolume, IO/) against the files
// themselves, read a second way: NIfTI headers written here with known
// sform, qform and scl_slope/scl_inter, the shared NIfTI files parsed by hand
// (zlib), and the shared DICOM series parsed by hand. Each stored voxel must
// appear in our volume, with its rescaled value, at the world point its
// header gives it.
#include "mcxSharedData.h"
#include "mcxVolumeReader.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtksys/Directory.hxx"
#include "vtksys/SystemTools.hxx"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using World = std::array<double, 3>;

// The grid index of world point `x` in `volume`: each coordinate must be a
// whole number within the extent (to 1e-6 of a voxel), else false.
bool IndexOf(vtkImageData* volume, const World& x, int index[3])
{
  double continuous[3];
  volume->TransformPhysicalPointToContinuousIndex(x.data(), continuous);
  const int* extent = volume->GetExtent();
  for (int a = 0; a < 3; ++a)
  {
    index[a] = static_cast<int>(std::lround(continuous[a]));
    if (std::abs(continuous[a] - index[a]) > 1e-6 || index[a] < extent[2 * a] ||
      index[a] > extent[2 * a + 1])
    {
      return false;
    }
  }
  return true;
}

double ValueAt(vtkImageData* volume, const int index[3])
{
  return volume->GetPointData()->GetScalars()->GetTuple1(
    volume->ComputePointId(const_cast<int*>(index)));
}

// Every stored voxel v of `count` (its world point, its expected value)
// is where and what our volume says; stops at the first few mismatches.
void ExpectVoxels(vtkImageData* volume, std::size_t count,
  const std::function<void(std::size_t, World&, double&)>& voxel, double tolerance = 0.0)
{
  ASSERT_EQ(static_cast<vtkIdType>(count), volume->GetNumberOfPoints());
  int failures = 0;
  for (std::size_t v = 0; v < count && failures < 5; ++v)
  {
    World x;
    double expected;
    voxel(v, x, expected);
    int index[3];
    if (!IndexOf(volume, x, index))
    {
      ADD_FAILURE() << "stored voxel " << v << " at world (" << x[0] << ", " << x[1] << ", " << x[2]
                    << ") is not a grid point of the volume";
      ++failures;
      continue;
    }
    const double value = ValueAt(volume, index);
    if (std::abs(value - expected) > tolerance * std::max(1.0, std::abs(expected)))
    {
      ADD_FAILURE() << "stored voxel " << v << " at index (" << index[0] << ", " << index[1] << ", "
                    << index[2] << "): " << value << ", expected " << expected;
      ++failures;
    }
  }
}

// ---- NIfTI-1 ----------------------------------------------------------------

// The fields of a NIfTI-1 header this test writes or reads (the standard's
// byte offsets, little endian).
struct Nifti
{
  int Dims[3] = { 1, 1, 1 };
  short Datatype = 4;               // int16
  float Pixdim[4] = { 1, 1, 1, 1 }; // [0] is qfac
  float Slope = 0, Intercept = 0;
  short QFormCode = 0, SFormCode = 0;
  float Quatern[3] = { 0, 0, 0 }, QOffset[3] = { 0, 0, 0 };
  float SRow[3][4] = { { 0 } };
  float VoxOffset = 352;

  // World point of stored voxel (i, j, k) in patient space (LPS): the
  // standard's RAS point (RASOf) with x and y negated.
  World WorldOf(int i, int j, int k) const
  {
    const World ras = this->RASOf(i, j, k);
    return { -ras[0], -ras[1], ras[2] };
  }

  // RAS point of stored voxel (i, j, k) by the standard: sform when its
  // code is set, else the qform, else pixdim alone.
  World RASOf(int i, int j, int k) const
  {
    const double ijk[3] = { double(i), double(j), double(k) };
    World x{ 0, 0, 0 };
    if (this->SFormCode > 0)
    {
      for (int r = 0; r < 3; ++r)
      {
        x[r] = this->SRow[r][0] * ijk[0] + this->SRow[r][1] * ijk[1] + this->SRow[r][2] * ijk[2] +
          this->SRow[r][3];
      }
      return x;
    }
    if (this->QFormCode > 0)
    {
      const double b = this->Quatern[0], c = this->Quatern[1], d = this->Quatern[2];
      const double a = std::sqrt(std::max(0.0, 1.0 - (b * b + c * c + d * d)));
      const double rotation[3][3] = {
        { a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c) },
        { 2 * (b * c + a * d), a * a + c * c - b * b - d * d, 2 * (c * d - a * b) },
        { 2 * (b * d - a * c), 2 * (c * d + a * b), a * a + d * d - c * c - b * b },
      };
      const double qfac = this->Pixdim[0] < 0 ? -1.0 : 1.0;
      const double scaled[3] = { this->Pixdim[1] * ijk[0], this->Pixdim[2] * ijk[1],
        qfac * this->Pixdim[3] * ijk[2] };
      for (int r = 0; r < 3; ++r)
      {
        x[r] = rotation[r][0] * scaled[0] + rotation[r][1] * scaled[1] +
          rotation[r][2] * scaled[2] + this->QOffset[r];
      }
      return x;
    }
    return { this->Pixdim[1] * ijk[0], this->Pixdim[2] * ijk[1], this->Pixdim[3] * ijk[2] };
  }

  // The value a reader must give stored value `stored`: slope 0 means none.
  double Rescaled(double stored) const
  {
    return this->Slope == 0 ? stored : stored * this->Slope + this->Intercept;
  }
};

template <typename T>
void Put(std::string& bytes, std::size_t offset, T value)
{
  std::memcpy(&bytes[offset], &value, sizeof(T));
}

template <typename T>
T Get(const std::string& bytes, std::size_t offset)
{
  T value;
  std::memcpy(&value, &bytes[offset], sizeof(T));
  return value;
}

// A single-file .nii of int16 values.
void WriteNifti(const std::string& path, const Nifti& h, const std::vector<std::int16_t>& values)
{
  std::string bytes(352, '\0');
  Put<int>(bytes, 0, 348);
  const short dim[8] = { 3, short(h.Dims[0]), short(h.Dims[1]), short(h.Dims[2]), 1, 1, 1, 1 };
  std::memcpy(&bytes[40], dim, sizeof(dim));
  Put<short>(bytes, 70, h.Datatype);
  Put<short>(bytes, 72, 16);
  const float pixdim[8] = { h.Pixdim[0], h.Pixdim[1], h.Pixdim[2], h.Pixdim[3], 1, 1, 1, 1 };
  std::memcpy(&bytes[76], pixdim, sizeof(pixdim));
  Put<float>(bytes, 108, h.VoxOffset);
  Put<float>(bytes, 112, h.Slope);
  Put<float>(bytes, 116, h.Intercept);
  Put<char>(bytes, 123, 2); // mm
  Put<short>(bytes, 252, h.QFormCode);
  Put<short>(bytes, 254, h.SFormCode);
  std::memcpy(&bytes[256], h.Quatern, sizeof(h.Quatern));
  std::memcpy(&bytes[268], h.QOffset, sizeof(h.QOffset));
  std::memcpy(&bytes[280], h.SRow, sizeof(h.SRow));
  std::memcpy(&bytes[344], "n+1\0", 4);
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.write(reinterpret_cast<const char*>(values.data()),
    static_cast<std::streamsize>(values.size() * sizeof(std::int16_t)));
}

// The whole (gunzipped) file.
std::string ReadGzip(const std::string& path)
{
  std::string bytes;
  gzFile in = gzopen(path.c_str(), "rb");
  if (!in)
  {
    return bytes;
  }
  char buffer[1 << 16];
  int n;
  while ((n = gzread(in, buffer, sizeof(buffer))) > 0)
  {
    bytes.append(buffer, static_cast<std::size_t>(n));
  }
  gzclose(in);
  return bytes;
}

Nifti ParseNifti(const std::string& bytes)
{
  Nifti h;
  for (int a = 0; a < 3; ++a)
  {
    h.Dims[a] = Get<short>(bytes, 42 + 2 * a);
    h.Pixdim[a + 1] = Get<float>(bytes, 80 + 4 * a);
    h.Quatern[a] = Get<float>(bytes, 256 + 4 * a);
    h.QOffset[a] = Get<float>(bytes, 268 + 4 * a);
    for (int c = 0; c < 4; ++c)
    {
      h.SRow[a][c] = Get<float>(bytes, 280 + 16 * a + 4 * c);
    }
  }
  h.Pixdim[0] = Get<float>(bytes, 76);
  h.Datatype = Get<short>(bytes, 70);
  h.VoxOffset = Get<float>(bytes, 108);
  h.Slope = Get<float>(bytes, 112);
  h.Intercept = Get<float>(bytes, 116);
  h.QFormCode = Get<short>(bytes, 252);
  h.SFormCode = Get<short>(bytes, 254);
  return h;
}

double StoredValue(const std::string& bytes, const Nifti& h, std::size_t v)
{
  const std::size_t data = static_cast<std::size_t>(h.VoxOffset);
  switch (h.Datatype)
  {
    case 2:
      return static_cast<unsigned char>(bytes[data + v]);
    case 4:
      return Get<std::int16_t>(bytes, data + 2 * v);
    case 8:
      return Get<std::int32_t>(bytes, data + 4 * v);
    case 16:
      return Get<float>(bytes, data + 4 * v);
    default:
      return std::nan("");
  }
}

// Stored voxel v of a NIfTI file, in the file's order (i fastest).
void NiftiVoxel(const Nifti& h, std::size_t v, int& i, int& j, int& k)
{
  i = static_cast<int>(v % h.Dims[0]);
  j = static_cast<int>(v / h.Dims[0] % h.Dims[1]);
  k = static_cast<int>(v / (static_cast<std::size_t>(h.Dims[0]) * h.Dims[1]));
}

vtkSmartPointer<vtkImageData> ReadOurs(const std::string& path)
{
  std::string error;
  auto volume = mcxio::ReadVolume(path, error);
  EXPECT_TRUE(volume) << error;
  return volume;
}

// Writes h with distinct values 1 + v and checks our reading of it.
void CheckSyntheticNifti(const std::string& name, const Nifti& h)
{
  std::vector<std::int16_t> stored(static_cast<std::size_t>(h.Dims[0]) * h.Dims[1] * h.Dims[2]);
  for (std::size_t v = 0; v < stored.size(); ++v)
  {
    stored[v] = static_cast<std::int16_t>(1 + v);
  }
  const std::string path = vtksys::SystemTools::GetCurrentWorkingDirectory() + "/" + name;
  WriteNifti(path, h, stored);
  auto volume = ReadOurs(path);
  ASSERT_TRUE(volume);
  ExpectVoxels(
    volume, stored.size(),
    [&](std::size_t v, World& x, double& expected)
    {
      int i, j, k;
      NiftiVoxel(h, v, i, j, k);
      x = h.WorldOf(i, j, k);
      expected = h.Rescaled(stored[v]);
    },
    1e-6);
}

// ---- DICOM ------------------------------------------------------------------

// One file of an uncompressed explicit-VR little-endian series: the
// attributes of the image plane and the pixels, parsed by hand.
struct DicomSlice
{
  World Position{ 0, 0, 0 };                    // (0020,0032)
  double Orientation[6] = { 1, 0, 0, 0, 1, 0 }; // (0020,0037)
  double PixelSpacing[2] = { 1, 1 };            // (0028,0030): row spacing, column spacing
  int Rows = 0, Columns = 0;
  double Slope = 1, Intercept = 0;
  std::vector<std::int16_t> Pixels; // row by row from the top left
};

std::vector<double> Numbers(const std::string& text)
{
  std::vector<double> numbers;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, '\\'))
  {
    numbers.push_back(std::atof(item.c_str()));
  }
  return numbers;
}

// Walks the elements from `at` to `end` (or to the delimiter that closes an
// undefined-length item or sequence); records the top level's values.
std::size_t Walk(const std::string& b, std::size_t at, std::size_t end, DicomSlice* slice)
{
  while (at + 8 <= end)
  {
    const auto group = Get<std::uint16_t>(b, at), element = Get<std::uint16_t>(b, at + 2);
    if (group == 0xFFFE) // item, item delimiter, sequence delimiter: no VR
    {
      const auto length = Get<std::uint32_t>(b, at + 4);
      if (element == 0xE00D || element == 0xE0DD)
      {
        return at + 8;
      }
      at = length == 0xFFFFFFFFu ? Walk(b, at + 8, end, nullptr) : at + 8 + length;
      continue;
    }
    const std::string vr = b.substr(at + 4, 2);
    const bool longForm =
      vr == "OB" || vr == "OW" || vr == "OF" || vr == "SQ" || vr == "UT" || vr == "UN";
    const std::uint32_t length =
      longForm ? Get<std::uint32_t>(b, at + 8) : Get<std::uint16_t>(b, at + 6);
    const std::size_t value = at + (longForm ? 12 : 8);
    if (length == 0xFFFFFFFFu) // a sequence of undefined length
    {
      at = Walk(b, value, end, nullptr);
      continue;
    }
    if (slice)
    {
      const std::string text = b.substr(value, std::min<std::size_t>(length, 256));
      const std::uint32_t tag = (std::uint32_t(group) << 16) | element;
      if (tag == 0x00200032)
      {
        const auto p = Numbers(text);
        slice->Position = { p.at(0), p.at(1), p.at(2) };
      }
      else if (tag == 0x00200037)
      {
        const auto o = Numbers(text);
        std::copy(o.begin(), o.begin() + 6, slice->Orientation);
      }
      else if (tag == 0x00280030)
      {
        const auto s = Numbers(text);
        slice->PixelSpacing[0] = s.at(0);
        slice->PixelSpacing[1] = s.at(1);
      }
      else if (tag == 0x00280010)
      {
        slice->Rows = Get<std::uint16_t>(b, value);
      }
      else if (tag == 0x00280011)
      {
        slice->Columns = Get<std::uint16_t>(b, value);
      }
      else if (tag == 0x00281053)
      {
        slice->Slope = std::atof(text.c_str());
      }
      else if (tag == 0x00281052)
      {
        slice->Intercept = std::atof(text.c_str());
      }
      else if (tag == 0x7FE00010)
      {
        slice->Pixels.resize(length / 2);
        std::memcpy(slice->Pixels.data(), &b[value], slice->Pixels.size() * 2);
      }
    }
    at = value + length;
  }
  return at;
}

bool ParseDicom(const std::string& path, DicomSlice& slice)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  const std::string b = bytes.str();
  if (b.size() < 132 || b.compare(128, 4, "DICM") != 0)
  {
    return false;
  }
  Walk(b, 132, b.size(), &slice);
  return slice.Rows > 0 && slice.Pixels.size() == std::size_t(slice.Rows) * slice.Columns;
}

World Cross(const double a[3], const double b[3])
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
}

TEST(Readers, NiftiSformWinsOverQformAndSlopeAndInterceptApply)
{
  // sform: 90 degrees about z, spacing (2, 3, 4), offset (10, -20, 30); a
  // different qform (identity, offset 0) that must not be used.
  Nifti h;
  h.Dims[0] = 4;
  h.Dims[1] = 3;
  h.Dims[2] = 2;
  h.Pixdim[1] = 2;
  h.Pixdim[2] = 3;
  h.Pixdim[3] = 4;
  h.Slope = 2.5f;
  h.Intercept = -7;
  h.SFormCode = 2;
  h.QFormCode = 1;
  const float srow[3][4] = { { 0, -3, 0, 10 }, { 2, 0, 0, -20 }, { 0, 0, 4, 30 } };
  std::memcpy(h.SRow, srow, sizeof(srow));
  CheckSyntheticNifti("reader_sform.nii", h);
}

TEST(Readers, NiftiQformWithNegativeQfac)
{
  // qform only: quaternion of 120 degrees about (1, 1, 1) (x -> y -> z),
  // qfac -1 (the third axis reversed), offset (5, 6, 7); scl_slope 0: no scaling.
  Nifti h;
  h.Dims[0] = 3;
  h.Dims[1] = 4;
  h.Dims[2] = 5;
  h.Pixdim[0] = -1;
  h.Pixdim[1] = 1.5f;
  h.Pixdim[2] = 2;
  h.Pixdim[3] = 2.5f;
  h.Slope = 0;
  h.Intercept = 100; // ignored with slope 0
  h.QFormCode = 1;
  h.Quatern[0] = h.Quatern[1] = h.Quatern[2] = 0.5f;
  h.QOffset[0] = 5;
  h.QOffset[1] = 6;
  h.QOffset[2] = 7;
  CheckSyntheticNifti("reader_qform.nii", h);
}

TEST(Readers, NiftiWithoutFormsIsPixdimAlone)
{
  Nifti h;
  h.Dims[0] = 2;
  h.Dims[1] = 3;
  h.Dims[2] = 4;
  h.Pixdim[1] = 0.5f;
  h.Pixdim[2] = 0.75f;
  h.Pixdim[3] = 1.25f;
  h.Slope = 1;
  h.Intercept = -1024;
  CheckSyntheticNifti("reader_noform.nii", h);
}

TEST(Readers, SharedNiftiFilesMatchTheirHeaders)
{
  // cta_head_avm: uint8 with scl_slope 2.2086, sform and qform; the chest CT:
  // int16 HU with a sform that reverses x and y; the body CT: int32.
  for (const char* name :
    { "cta_head_avm.nii.gz", "ct_chest_cta_totalseg.nii.gz", "ct_body_totalseg.nii.gz" })
  {
    const std::string path = mcxtest::SharedDataPath(name);
    MCXTEST_NEED_FILE(path);
    const std::string bytes = ReadGzip(path);
    ASSERT_GT(bytes.size(), 352u) << path;
    const Nifti h = ParseNifti(bytes);
    ASSERT_GT(h.SFormCode, 0) << name;
    auto volume = ReadOurs(path);
    ASSERT_TRUE(volume) << name;
    const std::size_t count = static_cast<std::size_t>(h.Dims[0]) * h.Dims[1] * h.Dims[2];
    ASSERT_GE(bytes.size(), static_cast<std::size_t>(h.VoxOffset) + count) << name;
    SCOPED_TRACE(name);
    // Rescaled in double from the float header values.
    ExpectVoxels(
      volume, count,
      [&](std::size_t v, World& x, double& expected)
      {
        int i, j, k;
        NiftiVoxel(h, v, i, j, k);
        x = h.WorldOf(i, j, k);
        expected = h.Rescaled(StoredValue(bytes, h, v));
      },
      1e-6);
  }
}

TEST(Readers, DicomSeriesIsStackedAlongTheSliceNormal)
{
  // headsq as 93 DICOM files: slice k of our volume must be the file at the
  // k-th ImagePositionPatient along the normal (row x column direction), its
  // rows in the file's order along the column direction, and the volume's
  // origin, spacing and direction those of the series.
  const std::string directory = mcxtest::SharedDataPath("ct_head_headsq_dicom");
  MCXTEST_NEED(vtksys::SystemTools::FileIsDirectory(directory), directory);
  vtksys::Directory listing;
  ASSERT_TRUE(listing.Load(directory));
  std::vector<DicomSlice> slices;
  for (unsigned long f = 0; f < listing.GetNumberOfFiles(); ++f)
  {
    const std::string file = listing.GetFile(f);
    DicomSlice slice;
    if (file != "." && file != ".." && ParseDicom(directory + "/" + file, slice))
    {
      slices.push_back(slice);
    }
  }
  ASSERT_EQ(93u, slices.size());
  const double* u = slices[0].Orientation;
  const double* v = slices[0].Orientation + 3;
  const World n = Cross(u, v);
  auto along = [&](const DicomSlice& s)
  { return s.Position[0] * n[0] + s.Position[1] * n[1] + s.Position[2] * n[2]; };
  std::sort(slices.begin(), slices.end(),
    [&](const DicomSlice& a, const DicomSlice& b) { return along(a) < along(b); });
  const double dz = (along(slices.back()) - along(slices.front())) / (slices.size() - 1);
  ASSERT_GT(dz, 0.0);

  auto volume = ReadOurs(directory);
  ASSERT_TRUE(volume);
  int dims[3];
  volume->GetDimensions(dims);
  ASSERT_EQ(slices[0].Columns, dims[0]);
  ASSERT_EQ(slices[0].Rows, dims[1]);
  ASSERT_EQ(93, dims[2]);
  // Geometry: origin at the first position, spacing (column, row, slice
  // distance), direction (row direction, column direction, normal).
  const double* origin = volume->GetOrigin();
  const double* spacing = volume->GetSpacing();
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(slices[0].Position[a], origin[a], 1e-4) << a;
    EXPECT_NEAR(u[a], volume->GetDirectionMatrix()->GetElement(a, 0), 1e-6) << a;
    EXPECT_NEAR(v[a], volume->GetDirectionMatrix()->GetElement(a, 1), 1e-6) << a;
    EXPECT_NEAR(n[a], volume->GetDirectionMatrix()->GetElement(a, 2), 1e-6) << a;
  }
  EXPECT_NEAR(slices[0].PixelSpacing[1], spacing[0], 1e-6);
  EXPECT_NEAR(slices[0].PixelSpacing[0], spacing[1], 1e-6);
  EXPECT_NEAR(dz, spacing[2], 1e-6);
  // Slice k, row r, column c: value and world point.
  vtkDataArray* scalars = volume->GetPointData()->GetScalars();
  int failures = 0;
  for (int k = 0; k < 93 && failures < 5; ++k)
  {
    const DicomSlice& s = slices[static_cast<std::size_t>(k)];
    for (int r = 0; r < s.Rows && failures < 5; ++r)
    {
      for (int c = 0; c < s.Columns && failures < 5; ++c)
      {
        const double expected = s.Pixels[std::size_t(r) * s.Columns + c] * s.Slope + s.Intercept;
        const double value = scalars->GetTuple1((std::size_t(k) * dims[1] + r) * dims[0] + c);
        World x;
        for (int a = 0; a < 3; ++a)
        {
          x[a] = s.Position[a] + c * s.PixelSpacing[1] * u[a] + r * s.PixelSpacing[0] * v[a];
        }
        int index[3];
        const bool placed = IndexOf(volume, x, index);
        if (value != expected || !placed || index[0] != c || index[1] != r || index[2] != k)
        {
          ADD_FAILURE() << "file at position " << k << " along the normal, row " << r << ", column "
                        << c << ": our voxel (" << c << ", " << r << ", " << k << ") holds "
                        << value << ", the file " << expected
                        << (placed ? "" : "; its world point is not a grid point");
          ++failures;
        }
      }
    }
  }
}

namespace
{
// A copy of the headsq series with one DS element of every file (2 bytes,
// as the files store "0 " and "1 ") replaced: tag bytes, then the value.
void CopySeriesWithElement(
  const std::string& from, const std::string& to, const std::string& tag, const std::string& value)
{
  vtksys::SystemTools::RemoveADirectory(to);
  vtksys::SystemTools::MakeDirectory(to);
  vtksys::Directory listing;
  listing.Load(from);
  for (unsigned long f = 0; f < listing.GetNumberOfFiles(); ++f)
  {
    const std::string file = listing.GetFile(f);
    if (file == "." || file == "..")
    {
      continue;
    }
    std::ifstream in(from + "/" + file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t at = bytes.find(tag + "DS\x02\x00", 0);
    ASSERT_NE(std::string::npos, at) << file;
    bytes.replace(at + tag.size() + 4, 2, value);
    std::ofstream out(to + "/" + file, std::ios::binary);
    out << bytes;
  }
}
}

TEST(Readers, DicomRescaleSlopeAndInterceptGiveHounsfieldUnits)
{
  // RescaleSlope 2 and RescaleIntercept -9 in every file of the series: each
  // voxel is 2 x stored - 9 (the stored values: the series as exported).
  const std::string directory = mcxtest::SharedDataPath("ct_head_headsq_dicom");
  MCXTEST_NEED(vtksys::SystemTools::FileIsDirectory(directory), directory);
  const std::string work = vtksys::SystemTools::GetCurrentWorkingDirectory();
  CopySeriesWithElement(directory, work + "/rescale-slope", std::string("\x28\x00\x53\x10", 4), "2 ");
  CopySeriesWithElement(
    work + "/rescale-slope", work + "/rescale-both", std::string("\x28\x00\x52\x10", 4), "-9");
  auto stored = ReadOurs(directory);
  auto rescaled = ReadOurs(work + "/rescale-both");
  ASSERT_TRUE(stored && rescaled);
  vtkDataArray* a = stored->GetPointData()->GetScalars();
  vtkDataArray* b = rescaled->GetPointData()->GetScalars();
  ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples());
  vtkIdType wrong = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    wrong += b->GetTuple1(i) == 2 * a->GetTuple1(i) - 9 ? 0 : 1;
  }
  EXPECT_EQ(0, wrong);
  EXPECT_EQ(-9.0, b->GetRange()[0]);
}

TEST(Readers, DicomCompressedTransferSyntaxesGiveTheSameVolume)
{
  // The series converted by GDCM's gdcmconv to lossless JPEG, JPEG 2000,
  // JPEG-LS and RLE: vtk-dicom (with GDCM) must give the same voxels as the
  // uncompressed files, value for value.
  const std::string directory = mcxtest::SharedDataPath("ct_head_headsq_dicom");
  MCXTEST_NEED(vtksys::SystemTools::FileIsDirectory(directory), directory);
  const bool haveConverter = std::system("gdcmconv --version > /dev/null 2>&1") == 0;
  MCXTEST_NEED(haveConverter, std::string("gdcmconv (Debian's libgdcm-tools)"));
  auto plain = ReadOurs(directory);
  ASSERT_TRUE(plain);
  vtksys::Directory listing;
  ASSERT_TRUE(listing.Load(directory));
  const std::string work = vtksys::SystemTools::GetCurrentWorkingDirectory();
  for (const char* syntax : { "jpeg", "j2k", "jpegls", "rle" })
  {
    const std::string converted = work + "/series-" + syntax;
    vtksys::SystemTools::RemoveADirectory(converted);
    vtksys::SystemTools::MakeDirectory(converted);
    for (unsigned long f = 0; f < listing.GetNumberOfFiles(); ++f)
    {
      const std::string file = listing.GetFile(f);
      if (file == "." || file == "..")
      {
        continue;
      }
      const std::string command = std::string("gdcmconv --") + syntax + " '" + directory + "/" +
        file + "' '" + converted + "/" + file + "'";
      ASSERT_EQ(0, std::system(command.c_str())) << command;
    }
    auto volume = ReadOurs(converted);
    ASSERT_TRUE(volume) << syntax;
    vtkDataArray* a = plain->GetPointData()->GetScalars();
    vtkDataArray* b = volume->GetPointData()->GetScalars();
    ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples()) << syntax;
    vtkIdType differing = 0;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      differing += a->GetTuple1(i) == b->GetTuple1(i) ? 0 : 1;
    }
    EXPECT_EQ(0, differing) << syntax;
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(plain->GetOrigin()[k], volume->GetOrigin()[k]) << syntax;
      EXPECT_EQ(plain->GetSpacing()[k], volume->GetSpacing()[k]) << syntax;
    }
  }
}

TEST(Readers, DicomDecoderFailuresAreErrorsNotZeros)
{
  // Five slices converted to lossless JPEG and JPEG-LS, the middle one's
  // second half overwritten with random bytes after its valid markers:
  // GDCM fails to decode it, which vtk-dicom ignores (a slice of zeros);
  // the check decodes each such file itself and says which one. (JPEG 2000
  // is not tried: openjpeg decodes such a stream into wrong values without
  // a report, which no check can tell from an image.)
  const std::string directory = mcxtest::SharedDataPath("ct_head_headsq_dicom");
  MCXTEST_NEED(vtksys::SystemTools::FileExists(directory + "/CTHead5.dcm"), directory);
  const bool haveConverter = std::system("gdcmconv --version > /dev/null 2>&1") == 0;
  MCXTEST_NEED(haveConverter, std::string("gdcmconv (Debian's libgdcm-tools)"));
  const std::string work = vtksys::SystemTools::GetCurrentWorkingDirectory();
  for (const char* syntax : { "jpeg", "jpegls" })
  {
    const std::string converted = work + "/series-garbage-" + syntax;
    vtksys::SystemTools::RemoveADirectory(converted);
    vtksys::SystemTools::MakeDirectory(converted);
    for (int z = 1; z <= 5; ++z)
    {
      const std::string file = "/CTHead" + std::to_string(z) + ".dcm";
      const std::string command = std::string("gdcmconv --") + syntax + " '" + directory + file +
        "' '" + converted + file + "'";
      ASSERT_EQ(0, std::system(command.c_str())) << command;
    }
    std::string error;
    ASSERT_TRUE(mcxio::ReadVolume(converted, error)) << syntax << ": " << error;
    const std::string broken = converted + "/CTHead3.dcm";
    std::string bytes;
    {
      std::ifstream in(broken, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    std::uint32_t state = 12345;
    for (std::size_t i = bytes.size() / 2; i + 20 < bytes.size(); ++i)
    {
      state = state * 1664525u + 1013904223u;
      bytes[i] = static_cast<char>(state >> 24);
    }
    std::ofstream(broken, std::ios::binary).write(bytes.data(), bytes.size());
    EXPECT_FALSE(mcxio::ReadVolume(converted, error)) << syntax;
    EXPECT_NE(std::string::npos, error.find("CTHead3.dcm': its compressed pixel data")) << error;
    EXPECT_NE(std::string::npos, error.find(") do not decode")) << error;
  }
}
