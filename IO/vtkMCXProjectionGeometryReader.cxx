#include "vtkMCXProjectionGeometryReader.h"

#include "mcxGeometryFilePoses.h"

#include "vtkObjectFactory.h"

#include <algorithm>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMCXProjectionGeometryReader);

struct vtkMCXProjectionGeometryReader::PoseList
{
  std::vector<mcxio::GeometryFilePose> List;
};

vtkMCXProjectionGeometryReader::vtkMCXProjectionGeometryReader()
  : Poses(new PoseList)
{
}

vtkMCXProjectionGeometryReader::~vtkMCXProjectionGeometryReader()
{
  this->SetFileName(nullptr);
  this->SetBeam(nullptr);
}

namespace
{
const char* KindName(int kind)
{
  switch (kind)
  {
    case vtkMCXProjectionGeometryReader::RTKGeometryFile:
      return "RTK geometry";
    case vtkMCXProjectionGeometryReader::RTPlanFile:
      return "RT plan";
    case vtkMCXProjectionGeometryReader::ProjectionMatricesFile:
      return "projection matrices";
    default:
      return "none";
  }
}

int ReaderKind(mcxio::GeometryFileKind kind)
{
  switch (kind)
  {
    case mcxio::GeometryFileKind::RTPlan:
      return vtkMCXProjectionGeometryReader::RTPlanFile;
    case mcxio::GeometryFileKind::RTKGeometry:
      return vtkMCXProjectionGeometryReader::RTKGeometryFile;
    default:
      return vtkMCXProjectionGeometryReader::ProjectionMatricesFile;
  }
}
}

bool vtkMCXProjectionGeometryReader::Update()
{
  this->Poses->List.clear();
  this->FileKind = NoFile;
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "no geometry file: set FileName");
    return false;
  }
  const std::string path = this->FileName;
  mcxio::GeometryFileKind kind;
  std::string problem = mcxio::GeometryFileKindOf(path, kind);
  if (problem.empty() && this->ExpectedFileKind != NoFile &&
    ReaderKind(kind) != this->ExpectedFileKind)
  {
    const char* given[] = { "an XML file", "a DICOM file",
      "a file of projection matrices (JSON or text)" };
    const char* asked[] = { "", "RTK geometry XML", "DICOM RT plan",
      "file of projection matrices" };
    problem = std::string("geometry file '") + path + "': " + given[static_cast<int>(kind)] +
      ", not the " + asked[this->ExpectedFileKind] + " asked for";
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return false;
  }
  mcxio::GeometryFileDetector detector;
  std::copy(this->DetectorPixels, this->DetectorPixels + 2, detector.Pixels);
  std::copy(this->PixelPitch, this->PixelPitch + 2, detector.Pitch);
  detector.HasOrigin = this->UseDetectorOrigin;
  std::copy(this->DetectorOrigin, this->DetectorOrigin + 2, detector.Origin);
  detector.SourceToImage = this->SourceToImageDistance;
  detector.SourceToAxis = this->SourceToAxisDistance;
  detector.SourceToAxisOption =
    this->UseSourceToAxisDistance ? "the source-to-axis distance given" : "";
  std::vector<mcxio::GeometryFilePose> poses(1);
  switch (kind)
  {
    case mcxio::GeometryFileKind::RTPlan:
      problem = mcxio::RTPlanPose(path, this->Beam ? this->Beam : "", detector, poses[0]);
      this->FileKind = RTPlanFile;
      break;
    case mcxio::GeometryFileKind::RTKGeometry:
      problem = mcxio::RTKGeometryPoses(path, mcxio::MaximumGeometryFilePoses, detector, poses);
      this->FileKind = RTKGeometryFile;
      break;
    case mcxio::GeometryFileKind::ProjectionMatrices:
      problem = mcxio::MatrixFilePoses(path, mcxio::MaximumGeometryFilePoses, detector, poses);
      this->FileKind = ProjectionMatricesFile;
      break;
  }
  if (!problem.empty())
  {
    this->FileKind = NoFile;
    vtkErrorMacro(<< problem);
    return false;
  }
  this->Poses->List = std::move(poses);
  return true;
}

const char* vtkMCXProjectionGeometryReader::GetFileKindAsString()
{
  return KindName(this->FileKind);
}

int vtkMCXProjectionGeometryReader::GetNumberOfPoses()
{
  return static_cast<int>(this->Poses->List.size());
}

bool vtkMCXProjectionGeometryReader::GetProjectionMatrix(int k, double P[12])
{
  if (k < 0 || k >= this->GetNumberOfPoses())
  {
    return false;
  }
  std::copy(this->Poses->List[k].Matrix, this->Poses->List[k].Matrix + 12, P);
  return true;
}

bool vtkMCXProjectionGeometryReader::GetImageSize(int k, int size[2])
{
  if (k < 0 || k >= this->GetNumberOfPoses())
  {
    return false;
  }
  std::copy(this->Poses->List[k].Size, this->Poses->List[k].Size + 2, size);
  return true;
}

double vtkMCXProjectionGeometryReader::GetFocalPlaneDistance(int k)
{
  return k < 0 || k >= this->GetNumberOfPoses() ? 0.0 : this->Poses->List[k].FocalDistance;
}

void vtkMCXProjectionGeometryReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Beam: " << (this->Beam ? this->Beam : "(none)") << "\n";
  os << indent << "DetectorPixels: " << this->DetectorPixels[0] << " x " << this->DetectorPixels[1]
     << "\n";
  os << indent << "PixelPitch: " << this->PixelPitch[0] << ", " << this->PixelPitch[1] << "\n";
  os << indent << "SourceToImageDistance: " << this->SourceToImageDistance << "\n";
  os << indent << "SourceToAxisDistance: " << this->SourceToAxisDistance << "\n";
  os << indent << "UseSourceToAxisDistance: " << this->UseSourceToAxisDistance << "\n";
  os << indent << "DetectorOrigin: " << this->DetectorOrigin[0] << ", " << this->DetectorOrigin[1]
     << "\n";
  os << indent << "UseDetectorOrigin: " << this->UseDetectorOrigin << "\n";
  os << indent << "FileKind: " << this->GetFileKindAsString() << "\n";
  os << indent << "ExpectedFileKind: " << KindName(this->ExpectedFileKind) << "\n";
  os << indent << "NumberOfPoses: " << this->GetNumberOfPoses() << "\n";
}
