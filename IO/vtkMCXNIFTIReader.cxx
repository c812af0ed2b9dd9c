#include "vtkMCXNIFTIReader.h"

#include "mcxPrintableText.h"

#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMCXFirstErrorObserver.h"
#include "vtkMCXPatientSpace.h"
#include "vtkMCXReaderErrorsPrivate.h"
#include "vtkMatrix4x4.h"
#include "vtkNIFTIImageReader.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <new>
#include <string>

vtkStandardNewMacro(vtkMCXNIFTIReader);

namespace
{
bool EndsWith(std::string text, const std::string& suffix) // of a lower-case suffix, any case
{
  std::transform(
    text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text.size() >= suffix.size() &&
    text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Runs a stage of the wrapped reader; its first error (its executive's
// included, none of them printed), or "" on success.
template <typename Stage>
std::string Run(vtkNIFTIImageReader* reader, Stage stage)
{
  vtkNew<vtkMCXFirstErrorObserver> error;
  error->ObserveAlgorithm(reader);
  try
  {
    stage();
  }
  catch (const std::bad_alloc&)
  {
    error->StopObserving();
    return "out of memory";
  }
  error->StopObserving();
  return error->GetErrorText();
}
}

namespace
{
// "" when the voxels of the extent the wrapped reader's information gives
// (and their float64 copy when rescaled) can be allocated now, else why.
std::string ProbeMemory(vtkInformation* info, bool rescale)
{
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  vtkInformation* scalars = vtkDataObject::GetActiveFieldInformation(
    info, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
  const int components = scalars && scalars->Has(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS())
    ? scalars->Get(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS())
    : 1;
  double values = components;
  for (int a = 0; a < 3; ++a)
  {
    values *= std::max(0, extent[2 * a + 1] - extent[2 * a] + 1);
  }
  const int type = scalars && scalars->Has(vtkDataObject::FIELD_ARRAY_TYPE())
    ? scalars->Get(vtkDataObject::FIELD_ARRAY_TYPE())
    : VTK_DOUBLE;
  const double bytes = values * (vtkDataArray::GetDataTypeSize(type) + (rescale ? 8.0 : 0.0));
  void* room = bytes < 9e18 ? std::malloc(static_cast<std::size_t>(bytes) + 1) : nullptr;
  std::free(room);
  return room
    ? std::string()
    : "out of memory: the voxels need " + std::to_string(static_cast<long long>(bytes)) + " bytes";
}
}

vtkMCXNIFTIReader::vtkMCXNIFTIReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkMCXNIFTIReader::~vtkMCXNIFTIReader()
{
  this->SetFileName(nullptr);
}

int vtkMCXNIFTIReader::CanReadFile(const char* name)
{
  const std::string path = name ? name : "";
  return EndsWith(path, ".nii") || EndsWith(path, ".nii.gz") ? 1 : 0;
}

bool vtkMCXNIFTIReader::Rescale() const
{
  // NIfTI-1: scl_slope 0 means no scaling at all (scl_inter ignored).
  const double slope = this->Reader->GetRescaleSlope();
  const double intercept = this->Reader->GetRescaleIntercept();
  return slope != 0.0 && (slope != 1.0 || intercept != 0.0);
}

std::string vtkMCXNIFTIReader::Place(vtkInformation* readerInfo)
{
  // The form maps (spacing x index) to RAS: its columns times the spacing
  // are the axes' steps, in LPS once their x and y are negated (the
  // identity, the NIfTI standard's "method 1", when there is no form).
  vtkMatrix4x4* form = this->Reader->GetSFormMatrix() ? this->Reader->GetSFormMatrix()
                                                      : this->Reader->GetQFormMatrix();
  double stored[3] = { 1, 1, 1 };
  readerInfo->Get(vtkDataObject::SPACING(), stored);
  double steps[9];
  const double toLPS[3] = { -1.0, -1.0, 1.0 };
  for (int r = 0; r < 3; ++r)
  {
    this->Origin[r] = form ? toLPS[r] * form->GetElement(r, 3) : 0.0;
    for (int c = 0; c < 3; ++c)
    {
      steps[3 * r + c] =
        toLPS[r] * (form ? form->GetElement(r, c) : (r == c ? 1.0 : 0.0)) * stored[c];
    }
  }
  int extent[6];
  readerInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  return vtkMCXPatientSpace::PlaceAxisSteps(steps, this->Origin, extent, this->Spacing, this->Direction);
}

int vtkMCXNIFTIReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData::GetData(outInfo)->Initialize(); // no stale volume after a failure
  const std::string path = this->FileName ? this->FileName : "";
  std::string problem = path.empty() ? "no FileName is set" : std::string();
  // Whatever CheckHeader says: a FIFO or a device would block the wrapped
  // reader or feed it without end.
  if (problem.empty() && !mcxio::check::RegularFile(path, std::string(), problem))
  {
    problem = problem.substr(problem.compare(0, 3, "it ") == 0 ? 3 : 0);
    problem = problem.compare(0, 3, "is ") == 0 ? "it " + problem : problem;
  }
  if (problem.empty() && this->CheckHeader)
  {
    problem = mcxio::DescribeHeaderProblem(this->FileName, &mcxio::CheckNiftiHeader);
  }
  if (problem.empty())
  {
    this->Reader->SetFileName(path.c_str());
    problem = Run(this->Reader, [this] { this->Reader->UpdateInformation(); });
  }
  vtkInformation* readerInfo = this->Reader->GetOutputInformation(0);
  if (problem.empty())
  {
    problem = this->Place(readerInfo);
  }
  this->Failed = !problem.empty();
  if (this->Failed)
  {
    // One line: reported here, then an empty extent (not a failed request,
    // which the executive would report again).
    this->SetErrorCode(path.empty() ? vtkErrorCode::NoFileNameError : vtkErrorCode::FileFormatError);
    vtkErrorMacro(<< mcx::PrintableText(
                    path.empty() ? problem : "cannot read '" + path + "': " + problem));
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    return 1;
  }
  outInfo->CopyEntry(readerInfo, vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  outInfo->Set(vtkDataObject::SPACING(), this->Spacing, 3);
  outInfo->CopyEntry(readerInfo, vtkDataObject::POINT_DATA_VECTOR(), 1);
  if (this->Rescale())
  {
    vtkInformation* scalars = vtkDataObject::GetActiveFieldInformation(
      readerInfo, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
    const int components = scalars && scalars->Has(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS())
      ? scalars->Get(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS())
      : 1;
    vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_DOUBLE, components);
  }
  outInfo->Set(vtkDataObject::ORIGIN(), this->Origin, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), this->Direction, 9);
  this->SetErrorCode(vtkErrorCode::NoError);
  return 1;
}

int vtkMCXNIFTIReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  if (this->Failed)
  {
    return 1; // reported by RequestInformation
  }
  const std::string path = this->FileName ? this->FileName : "";
  // VTK's data arrays fail an allocation without an exception and its
  // reader then writes through a null pointer: the voxels' room is tried
  // first (the rescaled float64 copy's too), so that a limited address
  // space is one error.
  std::string problem = ProbeMemory(this->Reader->GetOutputInformation(0), this->Rescale());
  if (problem.empty())
  {
    problem = Run(this->Reader, [this] { this->Reader->UpdateWholeExtent(); });
  }
  vtkImageData* image = this->Reader->GetOutput();
  if (problem.empty() && (image->GetNumberOfPoints() == 0 || !image->GetPointData()->GetScalars()))
  {
    problem = "no volume data";
  }
  if (!problem.empty())
  {
    // A partial read must not pass as current at the next update.
    this->Reader->GetOutput()->ReleaseData();
    this->Reader->Modified();
    this->SetErrorCode(vtkErrorCode::FileFormatError);
    vtkErrorMacro(<< mcx::PrintableText("cannot read '" + path + "': " + problem));
    return 1;
  }
  output->ShallowCopy(image);
  output->SetOrigin(this->Origin);
  output->SetSpacing(this->Spacing);
  output->SetDirectionMatrix(this->Direction);
  if (this->Rescale())
  {
    const double slope = this->Reader->GetRescaleSlope();
    const double intercept = this->Reader->GetRescaleIntercept();
    vtkDataArray* stored = output->GetPointData()->GetScalars();
    const int components = stored->GetNumberOfComponents();
    const vtkIdType values = stored->GetNumberOfTuples() * components;
    // Allocated here, so that a failure is seen (and said once).
    auto* room = static_cast<double*>(std::malloc(sizeof(double) * std::max<vtkIdType>(values, 1)));
    if (!room)
    {
      output->Initialize();
      this->Reader->GetOutput()->ReleaseData();
      this->Reader->Modified();
      this->SetErrorCode(vtkErrorCode::OutOfDiskSpaceError);
      vtkErrorMacro(<< "cannot read '" << path << "': out of memory for the rescaled values ("
                    << values << " float64 values)");
      return 1;
    }
    vtkNew<vtkDoubleArray> rescaled;
    rescaled->SetName(stored->GetName());
    rescaled->SetNumberOfComponents(components); // vector intents too
    rescaled->SetArray(room, values, 0, vtkDoubleArray::VTK_DATA_ARRAY_FREE);
    for (vtkIdType t = 0; t < stored->GetNumberOfTuples(); ++t)
    {
      for (int c = 0; c < components; ++c)
      {
        rescaled->SetComponent(t, c, stored->GetComponent(t, c) * slope + intercept);
      }
    }
    output->GetPointData()->SetScalars(rescaled);
  }
  this->Reader->GetOutput()->ReleaseData(); // the output holds the voxels now
  return 1;
}

void vtkMCXNIFTIReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Reader: " << this->Reader.GetPointer() << "\n";
  os << indent << "CheckHeader: " << this->CheckHeader << "\n";
  os << indent << "Failed (last information request): " << this->Failed << "\n";
  os << indent << "Origin (LPS): " << this->Origin[0] << " " << this->Origin[1] << " "
     << this->Origin[2] << "\n";
  os << indent << "Spacing: " << this->Spacing[0] << " " << this->Spacing[1] << " "
     << this->Spacing[2] << "\n";
  os << indent << "Direction (LPS):";
  for (double d : this->Direction)
  {
    os << " " << d;
  }
  os << "\n";
}
