#include "vtkMCXMetaImageReader.h"

#include "mcxHeaderCheck.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMCXPatientSpace.h"
#include "vtkMCXReaderErrorsPrivate.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkmetaio/metaImage.h"
#include "vtkmetaio/metaUtils.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

vtkStandardNewMacro(vtkMCXMetaImageReader);

namespace
{
// The unit directions of the first three axes, axes[a][r]: the rows of
// TransformMatrix (ITK's reading), the identity beyond them.
void AxisDirections(const vtkmetaio::MetaImage& meta, double axes[3][3])
{
  const int n = meta.NDims();
  for (int a = 0; a < 3; ++a)
  {
    for (int r = 0; r < 3; ++r)
    {
      axes[a][r] = a < n && r < n ? meta.TransformMatrix()[a * n + r] : (a == r ? 1.0 : 0.0);
    }
  }
}
}

namespace
{
// MetaIO writes its warnings and errors to std::cerr itself ("Uncompress
// failed", "data not read completely"): kept while a stage runs, so that a
// failure is said once, in one line, by the reader.
class MetaIOMessages
{
public:
  explicit MetaIOMessages(std::string& first)
    : First(first)
    , Saved(std::cerr.rdbuf(this->Text.rdbuf()))
  {
  }
  ~MetaIOMessages() { std::cerr.rdbuf(this->Saved); }
  MetaIOMessages(const MetaIOMessages&) = delete;
  MetaIOMessages& operator=(const MetaIOMessages&) = delete;

  // The first line MetaIO wrote, if any (then kept in First).
  bool Said()
  {
    std::string line;
    while (this->First.empty() && std::getline(this->Text, line))
    {
      const std::size_t start = line.find_first_not_of(" \t\r");
      this->First = start == std::string::npos ? std::string() : line.substr(start);
    }
    return !this->First.empty();
  }

private:
  std::string& First;
  std::stringstream Text;
  std::streambuf* Saved;
};

// Where the voxels of a header with ElementDataFile = LOCAL begin: after
// the line of that field (MetaIO ends the header there).
unsigned long long LocalDataOffset(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  unsigned long long offset = 0;
  while (offset < (1ULL << 20) && std::getline(in, line))
  {
    offset += line.size() + 1;
    const std::size_t key = line.find_first_not_of(" \t\r\v\f"); // MetaIO skips them
    if (key != std::string::npos && line.compare(key, 15, "ElementDataFile") == 0)
    {
      return offset;
    }
  }
  return offset;
}

// "" when uncompressed binary data hold the voxels the header claims (data
// after the header, or in one file beside it); VTK's reader only warns of a
// short read and leaves zeros. Compressed data, file lists and patterns are
// left to the read.
std::string DescribeShortData(const vtkmetaio::MetaImage& meta, const char* header)
{
  const std::string data = meta.ElementDataFileName();
  int elementBytes = 0;
  if (meta.CompressedData() || !meta.BinaryData() || data.empty() || data == "LIST" ||
    data.find('%') != std::string::npos || data.find(' ') != std::string::npos ||
    !vtkmetaio::MET_SizeOfType(meta.ElementType(), &elementBytes))
  {
    return std::string();
  }
  unsigned long long total = static_cast<unsigned long long>(elementBytes) *
    static_cast<unsigned long long>(std::max(1, meta.ElementNumberOfChannels()));
  for (int a = 0; a < meta.NDims(); ++a)
  {
    total *= static_cast<unsigned long long>(std::max(0, meta.DimSize(a)));
  }
  if (data == "LOCAL")
  {
    return mcxio::DescribeShortRawData({ header }, LocalDataOffset(header), total);
  }
  const std::string file = vtksys::SystemTools::CollapseFullPath(
    data, vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::CollapseFullPath(header)));
  return meta.HeaderSize() >= 0
    ? mcxio::DescribeShortRawData({ file }, static_cast<unsigned long long>(meta.HeaderSize()), total)
    : std::string(); // -1: the data end the file
}
}

std::string vtkMCXMetaImageReader::Place()
{
  vtkmetaio::MetaImage meta;
  if (!this->FileName || !meta.Read(this->FileName, false))
  {
    return "the MetaImage header cannot be read";
  }
  const int n = meta.NDims();
  if (n < 2)
  {
    return "the MetaImage header has " + std::to_string(n) + " dimensions, not 2 or more";
  }
  double axes[3][3];
  AxisDirections(meta, axes);
  if (n == 2)
  {
    vtkMath::Cross(axes[0], axes[1], axes[2]); // one slice: its plane's normal
  }
  double steps[9], origin[3];
  for (int a = 0; a < 3; ++a)
  {
    const double spacing = a < n ? meta.ElementSpacing(a) : 1.0;
    origin[a] = a < n ? meta.Offset(a) : 0.0;
    for (int r = 0; r < 3; ++r)
    {
      steps[3 * r + a] = spacing * axes[a][r];
    }
  }
  double spacing[3], direction[9];
  const std::string problem =
    vtkMCXPatientSpace::PlaceAxisSteps(steps, origin, this->DataExtent, spacing, direction);
  if (!problem.empty())
  {
    return problem;
  }
  this->SetDataOrigin(origin);
  this->SetDataSpacing(spacing);
  this->SetDataDirection(direction);
  return DescribeShortData(meta, this->FileName);
}

int vtkMCXMetaImageReader::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  std::string problem = this->CheckHeader
    ? mcxio::DescribeHeaderProblem(this->FileName, &mcxio::CheckMetaImageHeader)
    : std::string();
  if (problem.empty())
  {
    problem = mcxio::RunReaderStage(
      this,
      [&]
      {
        std::string said;
        MetaIOMessages metaio(said);
        const int result = this->Superclass::RequestInformation(request, inputVector, outputVector);
        if (metaio.Said())
        {
          throw std::runtime_error("MetaIO: " + said); // said once, by RunReaderStage
        }
        return result;
      },
      [] { return std::string(); });
  }
  if (problem.empty())
  {
    std::string said;
    MetaIOMessages metaio(said);
    problem = this->Place();
    if (metaio.Said() && problem.empty())
    {
      problem = "MetaIO: " + said;
    }
  }
  const mcxio::Placement placement{ this->DataOrigin, this->DataSpacing, this->DataDirection };
  this->Failed = !mcxio::FinishInformation(this, outputVector, this->FileName, problem, placement);
  if (this->Failed)
  {
    this->SetErrorCode(vtkErrorCode::FileFormatError);
  }
  return 1;
}

int vtkMCXMetaImageReader::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const mcxio::Placement placement{ this->DataOrigin, this->DataSpacing, this->DataDirection };
  if (!mcxio::ReadPlaced(
        this, outputVector, this->FileName, this->Failed,
        [&]
        {
          std::string said;
          MetaIOMessages metaio(said);
          const int result = this->Superclass::RequestData(request, inputVector, outputVector);
          if (metaio.Said())
          {
            throw std::runtime_error("MetaIO: " + said); // said once, by RunReaderStage
          }
          return result;
        },
        placement))
  {
    this->SetErrorCode(vtkErrorCode::FileFormatError);
  }
  return 1;
}

void vtkMCXMetaImageReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CheckHeader: " << this->CheckHeader << "\n";
  os << indent << "Failed (last information request): " << this->Failed << "\n";
}
