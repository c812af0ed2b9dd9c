// The format dispatch of the checked read (mcxVolumeReader.h): header check,
// memory budget, then the project's or VTK's reader by extension, its first
// error folded into one line.
#include "mcxVolumeReader.h"

#include "mcxByteSize.h"
#include "mcxDicomSeries.h"
#ifdef MCXRAY_IO_DICOM
#include "mcxDicomFiles.h"
#endif
#include "mcxHeaderCheck.h"
#include "mcxPrintableText.h"

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataCompressor.h"
#include "vtkImageData.h"
#include "vtkImageReader2.h"
#include "vtkMCXFirstErrorObserver.h"
#include "vtkMCXMetaImageReader.h"
#include "vtkMCXNIFTIReader.h"
#include "vtkMCXNrrdReader.h"
#include "vtkMCXPatientSpace.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSLCReader.h"
#include "vtkStructuredPointsReader.h"
#include "vtkXMLDataParser.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLReader.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <new>
#include <stdexcept>

#include <sys/stat.h>
#include <unistd.h>

namespace mcxio
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

// The reader path's extension names, set to read it; null for an unknown
// extension. The project's readers leave their header check to the caller
// (ReadVolume checked it already: a gzipped NIfTI is not decompressed twice).
vtkSmartPointer<vtkAlgorithm> ReaderFor(const std::string& path)
{
  if (EndsWith(path, ".vti"))
  {
    auto xml = vtkSmartPointer<vtkXMLImageDataReader>::New();
    xml->SetFileName(path.c_str());
    return xml;
  }
  if (EndsWith(path, ".mha") || EndsWith(path, ".mhd"))
  {
    auto meta = vtkSmartPointer<vtkMCXMetaImageReader>::New(); // oriented in LPS
    meta->SetFileName(path.c_str());
    meta->CheckHeaderOff();
    return meta;
  }
  if (EndsWith(path, ".nii") || EndsWith(path, ".nii.gz"))
  {
    auto nifti = vtkSmartPointer<vtkMCXNIFTIReader>::New(); // sform/qform in LPS, scaling applied
    nifti->SetFileName(path.c_str());
    nifti->CheckHeaderOff();
    return nifti;
  }
  if (EndsWith(path, ".nrrd") || EndsWith(path, ".nhdr"))
  {
    auto nrrd = vtkSmartPointer<vtkMCXNrrdReader>::New(); // its space, oriented in LPS
    nrrd->SetFileName(path.c_str());
    nrrd->CheckHeaderOff();
    return nrrd;
  }
  if (EndsWith(path, ".vtk"))
  {
    auto legacy = vtkSmartPointer<vtkStructuredPointsReader>::New();
    legacy->SetFileName(path.c_str());
    return legacy;
  }
  if (EndsWith(path, ".slc"))
  {
    auto slc = vtkSmartPointer<vtkSLCReader>::New();
    slc->SetFileName(path.c_str());
    return slc;
  }
  return nullptr;
}

// errno's words as a message continues them ("no such file or directory").
std::string SystemError(int number)
{
  std::string words = std::strerror(number);
  if (!words.empty())
  {
    words[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(words[0])));
  }
  return words;
}

// False with error set to one line naming why path cannot be read at all:
// empty, missing (errno's words: no such file, permission denied, a
// loop of links), or not readable by this user.
bool Accessible(const std::string& path, std::string& error)
{
  if (path.empty())
  {
    error = "cannot read '': the path is empty";
    return false;
  }
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
  {
    error = "cannot read '" + path + "': " + SystemError(errno);
    return false;
  }
  if (::access(path.c_str(), S_ISDIR(info.st_mode) ? (R_OK | X_OK) : R_OK) != 0)
  {
    error = "cannot read '" + path + "': " + SystemError(errno);
    return false;
  }
  return true;
}

// Runs reader (ReaderFor(path)): its volume, or null with error set to its
// first report, said once.
vtkSmartPointer<vtkImageData> ReadWith(
  vtkAlgorithm* reader, const std::string& path, std::string& error)
{
  vtkNew<vtkMCXFirstErrorObserver> capture; // the reader's report, said once below
  capture->ObserveAlgorithm(reader);
  // VTK's XML parser reports malformed XML itself, on an object of its own
  // (a second line in Python and ParaView): folded into the reader's.
  auto* xml = vtkXMLReader::SafeDownCast(reader);
  if (xml)
  {
    xml->SetParserErrorObserver(capture);
  }
  try
  {
    reader->UpdateInformation();
    // The data's decompressor, made from the header, reports on itself too.
    vtkXMLDataParser* parser = xml ? xml->GetXMLParser() : nullptr;
    if (parser && parser->GetCompressor())
    {
      parser->GetCompressor()->AddObserver(vtkCommand::ErrorEvent, capture);
    }
    reader->Update();
  }
  catch (const std::bad_alloc&)
  {
    // An allocation that grows with the input failed (an address-space
    // limit, a header that lies past the checks): one line, not the end.
    capture->StopObserving();
    xml ? xml->SetParserErrorObserver(nullptr) : void();
    error = "cannot read '" + path + "': out of memory (an allocation of the reader failed)";
    return nullptr;
  }
  catch (const std::length_error&)
  {
    capture->StopObserving();
    xml ? xml->SetParserErrorObserver(nullptr) : void();
    error = "cannot read '" + path + "': the reader asked for an impossible size";
    return nullptr;
  }
  capture->StopObserving();
  if (xml)
  {
    xml->SetParserErrorObserver(nullptr);
  }
  auto* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  const std::string& message = capture->GetErrorText();
  if (!message.empty() || !image || image->GetNumberOfPoints() == 0 ||
    !image->GetPointData()->GetScalars())
  {
    // The project's readers name the file themselves: said once.
    const std::string own = "cannot read '" + path + "': ";
    error = message.compare(0, own.size(), own) == 0
      ? message
      : own + (message.empty() ? std::string("no volume data") : message);
    return nullptr;
  }
  const std::string placement = vtkMCXPatientSpace::DescribeUnusablePlacement(image);
  if (!placement.empty())
  {
    error = "cannot read '" + path + "': the file's placement cannot be used: " + placement;
    return nullptr;
  }
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->ShallowCopy(image);
  return volume;
}
}

vtkSmartPointer<vtkImageData> ReadVolume(const std::string& path, std::string& error)
{
  return ReadVolume(path, VolumeReadOptions(), error);
}

// ReadVolume before its error is made printable.
static vtkSmartPointer<vtkImageData> ReadAnyVolume(
  const std::string& path, const VolumeReadOptions& options, std::string& error)
{
  const unsigned long long memoryBudget = options.MemoryBudget;
  if (!Accessible(path, error))
  {
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
      ", more than the memory budget of " + mcx::DescribeBytes(double(memoryBudget)) + " (" +
      options.MemoryBudgetName + ")";
    return nullptr;
  }
  if (vtksys::SystemTools::FileIsDirectory(path))
  {
    auto series = ReadDicomSeries(path, options, error);
    const std::string placement =
      series ? vtkMCXPatientSpace::DescribeUnusablePlacement(series) : std::string();
    if (!placement.empty())
    {
      error = "cannot read '" + path + "': the series' placement cannot be used: " + placement;
      return nullptr;
    }
    return series;
  }
  vtkSmartPointer<vtkAlgorithm> reader = ReaderFor(path);
  if (!reader)
  {
    error = "cannot read '" + path +
      "': unknown format (expected .vti, .mha, .mhd, .nii, .nii.gz, .nrrd, .nhdr, .vtk, .slc or a "
      "DICOM directory)";
    return nullptr;
  }
  return ReadWith(reader, path, error);
}

vtkSmartPointer<vtkImageData> ReadVolume(
  const std::string& path, const VolumeReadOptions& options, std::string& error)
{
  vtkSmartPointer<vtkImageData> volume = ReadAnyVolume(path, options, error);
  error = mcx::PrintableText(error); // a hostile header's bytes, quoted in it
  return volume;
}

std::vector<std::string> InputFiles(const std::string& path)
{
  std::vector<std::string> files = { path };
  if (!vtksys::SystemTools::FileIsDirectory(path))
  {
    const std::vector<std::string> data = DataFiles(path);
    files.insert(files.end(), data.begin(), data.end());
    return files;
  }
  files.push_back(path + "/DICOMDIR");
#ifdef MCXRAY_IO_DICOM
  std::vector<std::string> found;
  std::string error; // past the limit: the files found so far; the read refuses it
  DicomFolderFiles(path, DicomScanDepth, DicomFileLimit, found, error);
  files.insert(files.end(), found.begin(), found.end());
#endif
  return files;
}

} // namespace mcxio
