#include "vtkMCXMetaImageReader.h"

#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMCXPatientSpace.h"
#include "vtkMCXReaderErrorsPrivate.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkmetaio/metaImage.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkMCXMetaImageReader);

namespace
{
// The LPS direction an AnatomicalOrientation letter gives an axis (MetaIO:
// the letter says where the axis comes from); false for an unknown one.
bool OrientationDirection(vtkmetaio::MET_OrientationEnumType code, double direction[3])
{
  direction[0] = direction[1] = direction[2] = 0.0;
  switch (code)
  {
    case vtkmetaio::MET_ORIENTATION_RL:
      direction[0] = 1;
      return true;
    case vtkmetaio::MET_ORIENTATION_LR:
      direction[0] = -1;
      return true;
    case vtkmetaio::MET_ORIENTATION_AP:
      direction[1] = 1;
      return true;
    case vtkmetaio::MET_ORIENTATION_PA:
      direction[1] = -1;
      return true;
    case vtkmetaio::MET_ORIENTATION_IS:
      direction[2] = 1;
      return true;
    case vtkmetaio::MET_ORIENTATION_SI:
      direction[2] = -1;
      return true;
    default:
      return false;
  }
}

bool IsIdentity(const double* matrix, int n)
{
  for (int i = 0; i < n * n; ++i)
  {
    if (matrix[i] != ((i % (n + 1)) == 0 ? 1.0 : 0.0))
    {
      return false;
    }
  }
  return true;
}

// The unit directions of the first three axes (rows of TransformMatrix, or
// the AnatomicalOrientation's letters), axes[a][r].
void AxisDirections(const vtkmetaio::MetaImage& meta, double axes[3][3])
{
  const int n = meta.NDims();
  const int shown = std::min(n, 3);
  for (int a = 0; a < 3; ++a)
  {
    for (int r = 0; r < 3; ++r)
    {
      axes[a][r] = a == r ? 1.0 : 0.0;
    }
  }
  if (!IsIdentity(meta.TransformMatrix(), n))
  {
    for (int a = 0; a < shown; ++a)
    {
      for (int r = 0; r < shown; ++r)
      {
        axes[a][r] = meta.TransformMatrix()[a * n + r];
      }
    }
    return;
  }
  double fromOrientation[3][3];
  double present[3] = { 0, 0, 0 };
  for (int a = 0; a < shown; ++a)
  {
    if (!OrientationDirection(meta.AnatomicalOrientation(a), fromOrientation[a]))
    {
      return; // unknown or partial: the identity stands
    }
    for (int r = 0; r < 3; ++r)
    {
      present[r] += std::abs(fromOrientation[a][r]);
    }
  }
  for (int r = 0; r < shown; ++r)
  {
    if (present[r] != 1.0)
    {
      return; // an axis named twice
    }
  }
  std::copy(&fromOrientation[0][0], &fromOrientation[0][0] + 3 * shown, &axes[0][0]);
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
  std::string problem = vtkMCXPatientSpace::SplitAxisSteps(steps, spacing, direction);
  if (problem.empty())
  {
    problem =
      vtkMCXPatientSpace::DescribeUnusableExtent(origin, spacing, direction, this->DataExtent);
  }
  if (!problem.empty())
  {
    return "the header's placement cannot be used: " + problem;
  }
  this->SetDataOrigin(origin);
  this->SetDataSpacing(spacing);
  this->SetDataDirection(direction);
  return problem;
}

int vtkMCXMetaImageReader::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  std::string problem = mcxio::RunReaderStage(
    this, [&] { return this->Superclass::RequestInformation(request, inputVector, outputVector); },
    [] { return std::string(); });
  if (problem.empty())
  {
    problem = this->Place();
  }
  this->Failed = !problem.empty();
  if (this->Failed)
  {
    this->SetErrorCode(vtkErrorCode::FileFormatError);
    mcxio::ReportReaderFailure(this, outputVector, this->FileName, problem);
    return 1;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkDataObject::ORIGIN(), this->DataOrigin, 3);
  outInfo->Set(vtkDataObject::SPACING(), this->DataSpacing, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), this->DataDirection, 9);
  return 1;
}

int vtkMCXMetaImageReader::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (this->Failed)
  {
    output->Initialize();
    return 1; // reported by RequestInformation
  }
  const std::string problem = mcxio::RunReaderStage(
    this, [&] { return this->Superclass::RequestData(request, inputVector, outputVector); },
    [] { return std::string(); });
  if (!problem.empty())
  {
    output->Initialize();
    this->SetErrorCode(vtkErrorCode::FileFormatError);
    mcxio::ReportReaderFailure(this, nullptr, this->FileName, problem);
    return 1;
  }
  output->SetOrigin(this->DataOrigin);
  output->SetSpacing(this->DataSpacing);
  output->SetDirectionMatrix(this->DataDirection);
  return 1;
}

void vtkMCXMetaImageReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Failed (last information request): " << this->Failed << "\n";
}
