#include "vtkMCXNrrdReader.h"

#include "mcxHeaderCheck.h"

#include "vtkCharArray.h"
#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMCXPatientSpace.h"
#include "vtkMCXReaderErrorsPrivate.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cctype>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkMCXNrrdReader);

namespace
{
std::string Trim(const std::string& text)
{
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  const std::size_t last = text.find_last_not_of(" \t\r\n");
  return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
}

// The header's fields as vtkNrrdReader reads them: "field: description"
// lines after the magic, up to the first empty line, '#' comments skipped;
// a field given twice keeps its last value.
std::map<std::string, std::string> Fields(const std::string& header)
{
  std::map<std::string, std::string> fields;
  std::istringstream in(header);
  std::string line;
  std::getline(in, line); // the magic
  while (std::getline(in, line) && !line.empty())
  {
    const std::size_t separator = line.find(": ");
    if (line[0] != '#' && separator != std::string::npos)
    {
      fields[line.substr(0, separator)] = Trim(line.substr(separator + 2));
    }
  }
  return fields;
}

// A space name as teem compares it: any case, without spaces, hyphens or
// underscores ("right-anterior-superior", "Right Anterior Superior", "RAS").
std::string Normalized(const std::string& name)
{
  std::string out;
  for (unsigned char c : name)
  {
    if (c != ' ' && c != '-' && c != '_')
    {
      out += static_cast<char>(std::tolower(c));
    }
  }
  return out;
}

// The signs that take a named space to LPS; false for a space that has no
// LPS equivalent (or none this reader knows).
bool SpaceToLPS(const std::string& space, double sign[3])
{
  static const std::map<std::string, std::array<double, 3>> known = {
    { "rightanteriorsuperior", { -1, -1, 1 } }, { "ras", { -1, -1, 1 } },
    { "leftanteriorsuperior", { 1, -1, 1 } }, { "las", { 1, -1, 1 } },
    { "leftposteriorsuperior", { 1, 1, 1 } }, { "lps", { 1, 1, 1 } },
    { "scannerxyz", { 1, 1, 1 } }, { "3drighthanded", { 1, 1, 1 } }
  };
  const auto found = known.find(Normalized(space));
  if (found == known.end())
  {
    return false;
  }
  std::copy(found->second.begin(), found->second.end(), sign);
  return true;
}

// One vector "(a,b,c)" (spaces allowed) of exactly three numbers.
bool ParseVector(const std::string& text, double vector[3])
{
  if (text.size() < 2 || text.front() != '(' || text.back() != ')')
  {
    return false;
  }
  std::string inner = text.substr(1, text.size() - 2);
  std::istringstream in(inner);
  std::string part;
  int n = 0;
  while (std::getline(in, part, ','))
  {
    part = Trim(part);
    char* end = nullptr;
    const double value = std::strtod(part.c_str(), &end);
    if (part.empty() || n >= 3 || end != part.c_str() + part.size())
    {
      return false;
    }
    vector[n++] = value;
  }
  return n == 3;
}

// The entries of "space directions": "none" or a parenthesised vector.
bool ParseDirections(const std::string& text, std::vector<std::string>& entries)
{
  entries.clear();
  std::size_t at = 0;
  while ((at = text.find_first_not_of(" \t", at)) != std::string::npos)
  {
    std::size_t end;
    if (text[at] == '(')
    {
      end = text.find(')', at);
      if (end == std::string::npos)
      {
        return false;
      }
      ++end;
    }
    else
    {
      end = std::min(text.find_first_of(" \t", at), text.size());
    }
    entries.push_back(text.substr(at, end - at));
    at = end;
  }
  return true;
}

// The header's sizes, as integers.
std::vector<long long> Sizes(const std::string& text)
{
  std::istringstream in(text);
  std::vector<long long> sizes;
  long long size;
  while (in >> size)
  {
    sizes.push_back(size);
  }
  return sizes;
}

// Whether the first axis holds the voxels' components: a "none" space
// direction or a kind that is no domain says so; without either, VTK's
// guess (more than three axes, or at most 9 samples along the first).
bool LeadingComponentAxis(std::map<std::string, std::string>& f)
{
  std::vector<std::string> entries;
  if (f.count("space directions") && ParseDirections(f["space directions"], entries) &&
    !entries.empty())
  {
    return entries[0] == "none";
  }
  std::istringstream kinds(f["kinds"]);
  std::string first;
  if (kinds >> first)
  {
    return first != "domain" && first != "space";
  }
  const std::vector<long long> sizes = Sizes(f["sizes"]);
  return sizes.size() > 3 || (!sizes.empty() && sizes[0] <= 9);
}
}

vtkMCXNrrdReader::vtkMCXNrrdReader() = default;

std::string vtkMCXNrrdReader::PlaceHeader(const std::string& header, const int extent[6],
  const double vtkSpacing[3], double origin[3], double spacing[3], double direction[9])
{
  std::map<std::string, std::string> f = Fields(header);
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = 0.0;
    spacing[a] = vtkSpacing[a];
    for (int r = 0; r < 3; ++r)
    {
      direction[3 * r + a] = r == a ? 1.0 : 0.0;
    }
  }
  if (!f.count("space") && !f.count("space dimension") && !f.count("space directions") &&
    !f.count("space origin"))
  {
    return std::string(); // no world stated: VTK's grid, at the origin
  }
  double sign[3] = { 1, 1, 1 };
  if (f.count("space") && !SpaceToLPS(f["space"], sign))
  {
    return "the NRRD space '" + f["space"] +
      "' has no place in patient space (known: right-anterior-superior, left-anterior-superior, "
      "left-posterior-superior, scanner-xyz, 3D-right-handed)";
  }
  if (!f.count("space") && Trim(f["space dimension"]) != "3")
  {
    return "the NRRD header's space dimension is '" + f["space dimension"] + "', not 3";
  }
  std::vector<std::string> entries;
  if (!f.count("space directions") || !ParseDirections(f["space directions"], entries))
  {
    return "the NRRD header names a space but gives no readable space directions";
  }
  const std::vector<long long> sizes = Sizes(f["sizes"]);
  if (entries.size() != sizes.size() || sizes.empty())
  {
    return "the NRRD header's space directions do not give one entry per axis";
  }
  const std::size_t first = entries[0] == "none" ? 1 : 0;
  if (std::find(entries.begin() + first, entries.end(), "none") != entries.end())
  {
    return "the NRRD header has a non-spatial axis after its spatial ones (as diffusion "
           "gradients), which VTK's reader cannot read";
  }
  const std::size_t axes = entries.size() - first;
  if (axes < 2 || axes > 3)
  {
    return "the NRRD header gives " + std::to_string(axes) + " spatial axes, not 2 or 3";
  }
  double steps[9] = { 0, 0, 0, 0, 0, 0, 0, 0, 0 };
  for (std::size_t a = 0; a < axes; ++a)
  {
    double v[3];
    if (!ParseVector(entries[first + a], v))
    {
      return "the NRRD header's space direction '" + entries[first + a] +
        "' is not a vector of 3 numbers";
    }
    for (int r = 0; r < 3; ++r)
    {
      steps[3 * r + a] = sign[r] * v[r];
    }
  }
  if (axes == 2)
  {
    // One slice: a unit step along the normal of its plane.
    const double u[3] = { steps[0], steps[3], steps[6] }, w[3] = { steps[1], steps[4], steps[7] };
    double normal[3];
    vtkMath::Cross(u, w, normal);
    const double length = vtkMath::Norm(normal);
    for (int r = 0; r < 3; ++r)
    {
      steps[3 * r + 2] = length > 0 ? normal[r] / length : 0.0;
    }
  }
  if (f.count("space origin"))
  {
    double o[3];
    if (!ParseVector(f["space origin"], o))
    {
      return "the NRRD header's space origin '" + f["space origin"] +
        "' is not a vector of 3 numbers";
    }
    for (int r = 0; r < 3; ++r)
    {
      origin[r] = sign[r] * o[r];
    }
  }
  return vtkMCXPatientSpace::PlaceAxisSteps(steps, origin, extent, spacing, direction);
}

std::string vtkMCXNrrdReader::CheckLayout(const std::string& header)
{
  // vtkNrrdReader sizes its axes by the last "dimension", "space" or
  // "space dimension" line before "sizes" (and writes past a vector sized
  // 0 when none comes first): the header's own dimension and sizes decide
  // here, before it reads them.
  std::istringstream in(header);
  std::string line;
  std::getline(in, line); // the magic
  bool dimensionSeen = false;
  std::map<std::string, std::string> fields;
  while (std::getline(in, line) && !line.empty())
  {
    const std::size_t separator = line.find(": ");
    if (line[0] == '#' || separator == std::string::npos)
    {
      continue;
    }
    const std::string field = line.substr(0, separator);
    dimensionSeen = dimensionSeen || field == "dimension";
    if (field == "sizes" && !dimensionSeen)
    {
      return "the NRRD header gives its sizes before its dimension";
    }
    fields[field] = Trim(line.substr(separator + 2));
  }
  std::istringstream dimensionText(fields["dimension"]);
  long long dimension = 0;
  const std::vector<long long> sizes = Sizes(fields["sizes"]);
  if (!(dimensionText >> dimension) || dimension < 1 || dimension > 4 ||
    static_cast<long long>(sizes.size()) != dimension)
  {
    return "the NRRD header's sizes do not give its dimension's " + fields["dimension"] + " axes";
  }
  for (long long size : sizes)
  {
    if (size < 1 || size > VTK_INT_MAX)
    {
      return "the NRRD header's sizes '" + fields["sizes"] + "' are not all between 1 and 2^31 - 1";
    }
  }
  std::vector<std::string> entries;
  std::istringstream kinds(fields["kinds"]);
  std::string firstKind;
  if (ParseDirections(fields["space directions"], entries) && !entries.empty() &&
    (kinds >> firstKind) &&
    (entries[0] == "none") == (firstKind == "domain" || firstKind == "space"))
  {
    return "the NRRD header's kinds and space directions disagree about its first axis ('" +
      firstKind + "', '" + entries[0] + "')";
  }
  const long long spatial = dimension - (LeadingComponentAxis(fields) ? 1 : 0);
  if (spatial < 2 || spatial > 3)
  {
    return "the NRRD header has " + std::to_string(spatial) +
      " spatial axes (after a leading component axis, if any), not 2 or 3";
  }
  return std::string();
}

void vtkMCXNrrdReader::SetLayout(const std::string& header)
{
  std::map<std::string, std::string> fields = Fields(header);
  const std::vector<long long> sizes = Sizes(fields["sizes"]);
  const std::size_t first = LeadingComponentAxis(fields) ? 1 : 0;
  this->NumberOfScalarComponents = first ? static_cast<int>(sizes[0]) : 1;
  // Data in several files hold one slice each (vtkNrrdReader's rule).
  this->FileDimensionality = static_cast<int>(sizes.size() - first) -
    (this->DataFiles->GetNumberOfValues() > 1 ? 1 : 0);
  std::istringstream spacings(fields["spacings"]);
  std::string skipped;
  if (first)
  {
    spacings >> skipped;
  }
  double spacing[3] = { 1, 1, 1 };
  for (int a = 0; a < 3; ++a)
  {
    const std::size_t axis = first + a;
    this->DataExtent[2 * a] = 0;
    this->DataExtent[2 * a + 1] = axis < sizes.size() ? static_cast<int>(sizes[axis] - 1) : 0;
    if (axis < sizes.size() && (!(spacings >> spacing[a]) || !(spacing[a] > 0)))
    {
      spacing[a] = 1.0; // "nan" or none: VTK's unit spacing
    }
  }
  this->SetDataSpacing(spacing);
}

int vtkMCXNrrdReader::ReadHeader(vtkCharArray* headerBuffer)
{
  const std::string header(headerBuffer->GetPointer(0));
  this->PlacementProblem = CheckLayout(header);
  if (!this->PlacementProblem.empty() || !this->Superclass::ReadHeader(headerBuffer))
  {
    return 0;
  }
  // The same bytes the superclass parsed: the axes as the header gives them
  // (vtkNrrdReader guesses components and sizes them by the space), placed
  // in LPS; the voxels read in the file's order (it reverses LAS's rows).
  this->FileLowerLeft = 1;
  this->SetLayout(header);
  double origin[3], spacing[3], direction[9];
  this->PlacementProblem =
    PlaceHeader(header, this->DataExtent, this->DataSpacing, origin, spacing, direction);
  if (!this->PlacementProblem.empty())
  {
    return 0;
  }
  this->SetDataOrigin(origin);
  this->SetDataSpacing(spacing);
  this->SetDataDirection(direction);
  return 1;
}

std::vector<std::string> vtkMCXNrrdReader::DataFileNames() const
{
  std::vector<std::string> files;
  for (vtkIdType i = 0; i < this->DataFiles->GetNumberOfValues(); ++i)
  {
    files.push_back(this->DataFiles->GetValue(i));
  }
  if (files.empty() && this->FileName)
  {
    files.emplace_back(this->FileName); // the data follow the header
  }
  return files;
}

unsigned long long vtkMCXNrrdReader::DataBytes() const
{
  unsigned long long bytes = static_cast<unsigned long long>(this->NumberOfScalarComponents) *
    vtkDataArray::GetDataTypeSize(this->DataScalarType);
  for (int a = 0; a < 3; ++a)
  {
    bytes *= static_cast<unsigned long long>(this->DataExtent[2 * a + 1] - this->DataExtent[2 * a] + 1);
  }
  return bytes;
}

int vtkMCXNrrdReader::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->PlacementProblem.clear();
  std::string problem = this->CheckHeader
    ? mcxio::DescribeHeaderProblem(this->FileName, &mcxio::CheckNrrdHeader)
    : std::string();
  if (problem.empty())
  {
    problem = mcxio::RunReaderStage(
      this,
      [&] { return this->Superclass::RequestInformation(request, inputVector, outputVector); },
      [this] { return this->PlacementProblem; });
  }
  if (problem.empty() && this->Encoding == ENCODING_RAW)
  {
    problem = mcxio::DescribeShortRawData(this->DataFileNames(),
      this->DataFiles->GetNumberOfValues() > 0 ? 0 : this->GetHeaderSize(), this->DataBytes());
  }
  const mcxio::Placement placement{ this->DataOrigin, this->DataSpacing, this->DataDirection };
  this->Failed = !mcxio::FinishInformation(this, outputVector, this->FileName, problem, placement);
  if (this->Failed)
  {
    this->SetErrorCode(vtkErrorCode::FileFormatError);
  }
  return 1;
}

int vtkMCXNrrdReader::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const mcxio::Placement placement{ this->DataOrigin, this->DataSpacing, this->DataDirection };
  if (!mcxio::ReadPlaced(this, outputVector, this->FileName, this->Failed,
        [&] { return this->Superclass::RequestData(request, inputVector, outputVector); }, placement))
  {
    this->SetErrorCode(vtkErrorCode::FileFormatError);
  }
  return 1;
}

void vtkMCXNrrdReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CheckHeader: " << this->CheckHeader << "\n";
  os << indent << "Failed (last information request): " << this->Failed << "\n";
  os << indent << "PlacementProblem: " << this->PlacementProblem << "\n";
}
