#include "mcxVolumeReader.h"

#include "mcxByteSize.h"
#include "mcxHeaderCheck.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDICOMImageReader.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkMetaImageReader.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkNrrdReader.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSLCReader.h"
#include "vtkStructuredPointsReader.h"
#include "vtkXMLImageDataReader.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <vector>

namespace mcxapp
{

namespace
{
bool EndsWith(std::string text, const std::string& suffix)
{
  std::transform(
    text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text.size() >= suffix.size() &&
    text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Captures a reader's error messages instead of letting VTK print them.
struct ErrorCapture
{
  std::string Message;
  vtkNew<vtkCallbackCommand> Command;

  explicit ErrorCapture(vtkAlgorithm* algorithm)
  {
    this->Command->SetClientData(&this->Message);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long, void* data, void* text)
      {
        auto* message = static_cast<std::string*>(data);
        if (message->empty() && text)
        {
          *message = static_cast<const char*>(text);
        }
      });
    algorithm->AddObserver(vtkCommand::ErrorEvent, this->Command);
  }
};

std::string FirstLine(const std::string& text)
{
  std::string line = text.substr(0, text.find('\n'));
  // VTK prefixes "ERROR: In file, line N\nclass (address): " -- keep the message.
  const std::size_t colon = text.find("): ");
  if (colon != std::string::npos)
  {
    line = text.substr(colon + 3);
    line = line.substr(0, line.find('\n'));
  }
  return line;
}

// NIfTI: world = (s|q)form * (spacing * index); apply it as origin and
// direction, and the scl_slope/scl_inter rescaling, so values and geometry are physical.
void ApplyNiftiHeader(vtkNIFTIImageReader* reader, vtkImageData* image)
{
  vtkMatrix4x4* form =
    reader->GetSFormMatrix() ? reader->GetSFormMatrix() : reader->GetQFormMatrix();
  if (form)
  {
    double direction[9];
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        direction[3 * r + c] = form->GetElement(r, c);
      }
    }
    const double origin[3] = { form->GetElement(0, 3), form->GetElement(1, 3),
      form->GetElement(2, 3) };
    image->SetDirectionMatrix(direction);
    image->SetOrigin(origin);
  }
  // NIfTI-1: scl_slope 0 means no scaling at all (scl_inter ignored).
  const double slope = reader->GetRescaleSlope();
  const double intercept = reader->GetRescaleIntercept();
  if (slope != 0.0 && (slope != 1.0 || intercept != 0.0))
  {
    vtkDataArray* scalars = image->GetPointData()->GetScalars();
    vtkSmartPointer<vtkDataArray> rescaled =
      vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_DOUBLE));
    rescaled->SetName(scalars->GetName());
    rescaled->SetNumberOfTuples(scalars->GetNumberOfTuples());
    for (vtkIdType i = 0; i < scalars->GetNumberOfTuples(); ++i)
    {
      rescaled->SetTuple1(i, scalars->GetTuple1(i) * slope + intercept);
    }
    image->GetPointData()->SetScalars(rescaled);
  }
}

// vtkDICOMImageReader with the order of its files in view (protected in VTK 9.1).
class DicomSeriesReader : public vtkDICOMImageReader
{
public:
  static DicomSeriesReader* New();
  vtkTypeMacro(DicomSeriesReader, vtkDICOMImageReader);
  using vtkDICOMImageReader::GetDICOMFileName;
  using vtkDICOMImageReader::GetNumberOfDICOMFileNames;
};
vtkStandardNewMacro(DicomSeriesReader);

// vtkDICOMImageReader stacks a series' files in descending order along the
// slice normal and turns each slice's rows bottom-up, but leaves origin 0 and
// the identity direction: the volume stood reversed in patient space. Put
// slice k at the k-th ImagePositionPatient along the normal (row x column
// direction), rows in the files' order, and the series' origin, slice
// distance and direction (row direction, column direction, normal) on it.
void ApplyDicomGeometry(DicomSeriesReader* reader, vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  const int files = reader->GetNumberOfDICOMFileNames();
  if (files < 1 || files != dims[2])
  {
    return;
  }
  std::vector<std::array<double, 3>> positions(static_cast<std::size_t>(files));
  double u[3] = { 1, 0, 0 }, v[3] = { 0, 1, 0 };
  for (int f = 0; f < files; ++f)
  {
    vtkNew<vtkDICOMImageReader> header;
    header->SetFileName(reader->GetDICOMFileName(f));
    header->UpdateInformation();
    const float* p = header->GetImagePositionPatient();
    positions[static_cast<std::size_t>(f)] = { p[0], p[1], p[2] };
    const float* o = header->GetImageOrientationPatient();
    if (f == 0 && vtkMath::Norm(o) > 0 && vtkMath::Norm(o + 3) > 0)
    {
      std::copy(o, o + 3, u);
      std::copy(o + 3, o + 6, v);
      vtkMath::Normalize(u);
      vtkMath::Normalize(v);
    }
  }
  double n[3];
  vtkMath::Cross(u, v, n);
  std::vector<double> along(positions.size());
  std::vector<int> order(positions.size());
  for (std::size_t f = 0; f < positions.size(); ++f)
  {
    along[f] = vtkMath::Dot(positions[f].data(), n);
    order[f] = static_cast<int>(f);
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return along[a] < along[b]; });

  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  vtkSmartPointer<vtkDataArray> sorted =
    vtkSmartPointer<vtkDataArray>::Take(scalars->NewInstance());
  sorted->SetName(scalars->GetName());
  sorted->SetNumberOfComponents(scalars->GetNumberOfComponents());
  sorted->SetNumberOfTuples(scalars->GetNumberOfTuples());
  const std::size_t row = static_cast<std::size_t>(dims[0]) * scalars->GetNumberOfComponents() *
    scalars->GetDataTypeSize();
  const auto* from = static_cast<const unsigned char*>(scalars->GetVoidPointer(0));
  auto* to = static_cast<unsigned char*>(sorted->GetVoidPointer(0));
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      const std::size_t source =
        static_cast<std::size_t>(order[static_cast<std::size_t>(k)]) * dims[1] + (dims[1] - 1 - j);
      std::memcpy(to + (static_cast<std::size_t>(k) * dims[1] + j) * row, from + source * row, row);
    }
  }
  image->GetPointData()->SetScalars(sorted);

  const std::array<double, 3>& first = positions[static_cast<std::size_t>(order.front())];
  image->SetOrigin(first.data());
  if (files > 1 && along[order.back()] > along[order.front()])
  {
    const double* spacing = image->GetSpacing();
    image->SetSpacing(
      spacing[0], spacing[1], (along[order.back()] - along[order.front()]) / (files - 1));
  }
  const double direction[9] = { u[0], v[0], n[0], u[1], v[1], n[1], u[2], v[2], n[2] };
  image->SetDirectionMatrix(direction);
}
}

std::string BundledVolumePath()
{
  const std::string installed = vtksys::SystemTools::CollapseFullPath(
    std::string(MCXRAY_INSTALLED_DATA_DIR) + "/ct_head_headsq.vti");
  if (vtksys::SystemTools::FileExists(installed, true))
  {
    return installed;
  }
  return std::string(MCXRAY_SOURCE_DATA_DIR) + "/ct_head_headsq.vti";
}

vtkSmartPointer<vtkImageData> ReadVolume(
  const std::string& path, std::string& error, unsigned long long memoryBudget)
{
  if (!vtksys::SystemTools::FileExists(path))
  {
    error = "cannot read '" + path + "': no such file or directory";
    return nullptr;
  }
  unsigned long long claimed = 0;
  std::string problem;
  if (!CheckVolumeHeader(path, claimed, problem))
  {
    error = "cannot read '" + path + "': " + problem;
    return nullptr;
  }
  if (memoryBudget > 0 && claimed > memoryBudget)
  {
    error = "cannot read '" + path + "': its voxels need " + mcx::DescribeBytes(double(claimed)) +
      ", more than the memory budget of " + mcx::DescribeBytes(double(memoryBudget)) +
      " (--memory-limit)";
    return nullptr;
  }
  vtkSmartPointer<vtkAlgorithm> reader;
  vtkNIFTIImageReader* nifti = nullptr;
  DicomSeriesReader* series = nullptr;
  if (vtksys::SystemTools::FileIsDirectory(path))
  {
    auto dicom = vtkSmartPointer<DicomSeriesReader>::New();
    dicom->SetDirectoryName(path.c_str());
    series = dicom;
    reader = dicom;
  }
  else if (EndsWith(path, ".vti"))
  {
    auto xml = vtkSmartPointer<vtkXMLImageDataReader>::New();
    xml->SetFileName(path.c_str());
    reader = xml;
  }
  else if (EndsWith(path, ".mha") || EndsWith(path, ".mhd"))
  {
    auto meta = vtkSmartPointer<vtkMetaImageReader>::New();
    meta->SetFileName(path.c_str());
    reader = meta;
  }
  else if (EndsWith(path, ".nii") || EndsWith(path, ".nii.gz"))
  {
    auto n = vtkSmartPointer<vtkNIFTIImageReader>::New();
    n->SetFileName(path.c_str());
    nifti = n;
    reader = n;
  }
  else if (EndsWith(path, ".nrrd") || EndsWith(path, ".nhdr"))
  {
    auto nrrd = vtkSmartPointer<vtkNrrdReader>::New();
    nrrd->SetFileName(path.c_str());
    reader = nrrd;
  }
  else if (EndsWith(path, ".vtk"))
  {
    auto legacy = vtkSmartPointer<vtkStructuredPointsReader>::New();
    legacy->SetFileName(path.c_str());
    reader = legacy;
  }
  else if (EndsWith(path, ".slc"))
  {
    auto slc = vtkSmartPointer<vtkSLCReader>::New();
    slc->SetFileName(path.c_str());
    reader = slc;
  }
  else
  {
    error = "cannot read '" + path +
      "': unknown format (expected .vti, .mha, .mhd, .nii, .nii.gz, .nrrd, .nhdr, .vtk, .slc or a "
      "DICOM directory)";
    return nullptr;
  }
  ErrorCapture capture(reader);
  reader->Update();
  auto* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!capture.Message.empty() || !image || image->GetNumberOfPoints() == 0 ||
    !image->GetPointData()->GetScalars())
  {
    error = "cannot read '" + path + "'" +
      (capture.Message.empty() ? std::string(": no volume data")
                               : ": " + FirstLine(capture.Message));
    return nullptr;
  }
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->ShallowCopy(image);
  if (nifti)
  {
    ApplyNiftiHeader(nifti, volume);
  }
  if (series)
  {
    ApplyDicomGeometry(series, volume);
  }
  return volume;
}

} // namespace mcxapp
