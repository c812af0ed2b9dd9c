// The checked reader of every format (vtkMCXVolumeReader.h): settings, the
// pipeline requests and PrintSelf; the reading itself is mcxVolumeReader's
// and mcxContainedReader's.
#include "vtkMCXVolumeReader.h"

#include "mcxContainedReader.h"
#include "mcxVolumeReader.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMatrix3x3.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cctype>
#include <exception>
#include <string>

vtkStandardNewMacro(vtkMCXVolumeReader);

vtkMCXVolumeReader::vtkMCXVolumeReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkMCXVolumeReader::~vtkMCXVolumeReader()
{
  this->SetFileName(nullptr);
}

int vtkMCXVolumeReader::CanReadFile(const char* name)
{
  if (!name)
  {
    return 0;
  }
  if (vtksys::SystemTools::FileIsDirectory(name))
  {
    return 1;
  }
  std::string lower(name);
  std::transform(
    lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* extension :
    { ".vti", ".mha", ".mhd", ".nii", ".nii.gz", ".nrrd", ".nhdr", ".vtk", ".slc" })
  {
    const std::string suffix(extension);
    if (lower.size() >= suffix.size() &&
      lower.compare(lower.size() - suffix.size(), suffix.size(), suffix) == 0)
    {
      return 1;
    }
  }
  return 0;
}

std::string vtkMCXVolumeReader::Read()
{
  this->Volume = nullptr;
  if (!this->FileName || !*this->FileName)
  {
    return "no FileName is set";
  }
  mcxio::VolumeReadOptions options; // messages name this class's setters
  options.DicomSeries = this->DicomSeries;
  options.MemoryBudget = this->MemoryBudget;
  std::string error;
  try
  {
    // A DICOM folder always: vtk-dicom's parser reads past its buffer on
    // some damaged files (vtkMCXDICOMSeriesReader.h).
    if (this->ReadInChildProcess || vtksys::SystemTools::FileIsDirectory(this->FileName))
    {
      mcxio::ReadLimits limits;
      limits.Seconds = this->TimeLimit;
      limits.MemoryBytes = this->MemoryBudget;
      this->Volume = mcxio::ReadVolumeContained(this->FileName, options, limits, error);
    }
    else
    {
      this->Volume = mcxio::ReadVolume(this->FileName, options, error);
    }
  }
  catch (const std::exception&)
  {
    // bad_alloc or length_error past the readers' own catches (a copy of
    // the volume): one line here, never the end of Python or ParaView.
    this->Volume = nullptr;
    error = "cannot read '" + std::string(this->FileName) + "': out of memory";
  }
  return this->Volume
    ? std::string()
    : (error.empty() ? "cannot read '" + std::string(this->FileName) + "'" : error);
}

int vtkMCXVolumeReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (this->ReadTime < this->GetMTime())
  {
    this->Error = this->Read();
    this->ReadTime.Modified();
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!this->Volume)
  {
    // One line, said here; an empty extent, not a failed request (which the
    // executive would report again).
    // The code set without Modified(): a changed code would make the next
    // update read (and say) it all again.
    this->ErrorCode =
      this->FileName ? vtkErrorCode::FileFormatError : vtkErrorCode::NoFileNameError;
    vtkErrorMacro(<< this->Error);
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    return 1;
  }
  this->ErrorCode = vtkErrorCode::NoError;
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), this->Volume->GetExtent(), 6);
  outInfo->Set(vtkDataObject::SPACING(), this->Volume->GetSpacing(), 3);
  outInfo->Set(vtkDataObject::ORIGIN(), this->Volume->GetOrigin(), 3);
  double direction[9];
  std::copy(this->Volume->GetDirectionMatrix()->GetData(),
    this->Volume->GetDirectionMatrix()->GetData() + 9, direction);
  outInfo->Set(vtkDataObject::DIRECTION(), direction, 9);
  vtkDataArray* scalars = this->Volume->GetPointData()->GetScalars();
  vtkDataObject::SetPointDataActiveScalarInfo(
    outInfo, scalars->GetDataType(), scalars->GetNumberOfComponents());
  // Any piece (ParaView's processes each ask for theirs): cut from the volume.
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  return 1;
}

int vtkMCXVolumeReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  output->Initialize();
  if (this->Volume) // else said by RequestInformation
  {
    output->ShallowCopy(this->Volume);
    output->Crop(outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()));
  }
  return 1;
}

void vtkMCXVolumeReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "DicomSeries: " << this->DicomSeries << "\n";
  os << indent << "MemoryBudget: " << this->MemoryBudget << "\n";
  os << indent << "ReadInChildProcess: " << this->ReadInChildProcess << "\n";
  os << indent << "TimeLimit: " << this->TimeLimit << "\n";
  os << indent << "Volume: " << this->Volume.GetPointer() << "\n";
  os << indent << "Error: " << this->Error << "\n";
  os << indent << "ReadTime: " << this->ReadTime.GetMTime() << "\n";
}
