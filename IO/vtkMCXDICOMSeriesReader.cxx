#include "vtkMCXDICOMSeriesReader.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDICOMDictHash.h"
#include "vtkDICOMDirectory.h"
#include "vtkDICOMItem.h"
#include "vtkDICOMReader.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMCXFirstErrorObserver.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtksys/SystemTools.hxx"

#include "mcxByteSize.h"
#include "mcxContainedReader.h"
#include "mcxDicomFiles.h"
#include "mcxDicomSliceChecks.h"
#include "mcxPrintableText.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <functional>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkMCXDICOMSeriesReader);

namespace
{
// The first error an algorithm of vtk-dicom (or its executive) reports,
// while in scope: kept for one line of ours, not printed.
class FirstError
{
public:
  explicit FirstError(vtkAlgorithm* algorithm) { this->Observer->ObserveAlgorithm(algorithm); }
  ~FirstError() { this->Observer->StopObserving(); }
  FirstError(const FirstError&) = delete;
  FirstError& operator=(const FirstError&) = delete;

  const std::string& Message() const { return this->Observer->GetErrorText(); }

private:
  vtkNew<vtkMCXFirstErrorObserver> Observer;
};

std::string Describe(vtkDICOMDirectory* directory, int s)
{
  const vtkDICOMItem& record = directory->GetSeriesRecord(s);
  std::ostringstream text;
  text << record.Get(DC::Modality).AsString() << " '"
       << record.Get(DC::SeriesDescription).AsString() << "' ("
       << directory->GetFileNamesForSeries(s)->GetNumberOfValues() << " images)";
  return text.str();
}

// vtk-dicom splits a series whose images repeat (the same image in two
// files) or disagree into several; one SeriesInstanceUID must be one series.
std::string SplitSeries(vtkDICOMDirectory* directory)
{
  std::vector<std::string> uids;
  for (int s = 0; s < directory->GetNumberOfSeries(); ++s)
  {
    uids.push_back(directory->GetSeriesRecord(s).Get(DC::SeriesInstanceUID).AsString());
  }
  for (std::size_t a = 0; a < uids.size(); ++a)
  {
    for (std::size_t b = a + 1; b < uids.size(); ++b)
    {
      if (!uids[a].empty() && uids[a] == uids[b])
      {
        return "the images of series " + uids[a] + " fall into parts (" +
          Describe(directory, static_cast<int>(a)) + "; " +
          Describe(directory, static_cast<int>(b)) +
          "): duplicated images, or images that disagree on size or orientation";
      }
    }
  }
  return std::string();
}

// What a read in the child hands back besides the volume: its error code and
// the folder's series in words, each text as its length, ':' and its bytes.
std::string SeriesNote(unsigned long code, const std::vector<std::string>& series)
{
  std::string note = std::to_string(code) + ":";
  for (const std::string& text : series)
  {
    note += std::to_string(text.size()) + ":" + text;
  }
  return note;
}

// The decimal number of note[from, to); false where it is none.
bool ReadCount(const std::string& note, std::size_t from, std::size_t to, unsigned long long& value)
{
  if (to == std::string::npos || to == from || to - from > 19 ||
    note.find_first_not_of("0123456789", from) < to)
  {
    return false;
  }
  value = std::stoull(note.substr(from, to - from));
  return true;
}

// The code and series of a note; false for a note that is none (a child that
// crashed leaves none).
bool ReadSeriesNote(const std::string& note, unsigned long& code, std::vector<std::string>& series)
{
  series.clear();
  unsigned long long value = 0;
  std::size_t at = note.find(':');
  if (!ReadCount(note, 0, at, value))
  {
    return false;
  }
  code = static_cast<unsigned long>(value);
  for (++at; at < note.size();)
  {
    const std::size_t colon = note.find(':', at);
    if (!ReadCount(note, at, colon, value) || value > note.size() - colon - 1)
    {
      return false;
    }
    series.push_back(note.substr(colon + 1, static_cast<std::size_t>(value)));
    at = colon + 1 + static_cast<std::size_t>(value);
  }
  return true;
}
}

struct vtkMCXDICOMSeriesReader::Internals
{
  vtkNew<vtkDICOMDirectory> Directory;
  vtkNew<vtkDICOMReader> Reader;
  vtkNew<vtkCallbackCommand> Progress;
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  double Origin[3] = { 0, 0, 0 };
  bool Failed = false; // the last RequestInformation reported an error
  std::vector<std::string> Series;      // the last scan's series, in words
  vtkSmartPointer<vtkImageData> Volume; // read in the child (ReadInChildProcess)

  // The last scan's series in words, from the directory.
  void ListSeries()
  {
    this->Series.clear();
    for (int s = 0; s < this->Directory->GetNumberOfSeries(); ++s)
    {
      this->Series.push_back(Describe(this->Directory, s));
    }
  }

  // Drops what the wrapped reader read, so that the next update reads again.
  void Forget()
  {
    this->Reader->GetOutput()->ReleaseData();
    this->Reader->Modified();
  }

  // Scans the folder (again only when the name changed) and chooses the
  // series; empty on success, else what is wrong.
  std::string ChooseSeries(const char* folder, int index, unsigned long& code)
  {
    code = vtkErrorCode::CannotOpenFileError;
    if (!folder || !*folder)
    {
      return "no DirectoryName is set";
    }
    // Series in subfolders too, as exports nest them; each folder and file
    // once, by inode (links to '..' or to a folder itself made vtk-dicom see
    // every image twice). A DICOMDIR lists the files itself.
    std::vector<std::string> found;
    std::string walk;
    if (vtksys::SystemTools::FileExists(std::string(folder) + "/DICOMDIR", true))
    {
      this->Directory->SetInputFileNames(nullptr);
      this->Directory->SetDirectoryName(folder);
      this->Directory->SetScanDepth(mcxio::DicomScanDepth);
    }
    else if (mcxio::DicomFolderFiles(
               folder, mcxio::DicomScanDepth, mcxio::DicomFileLimit, found, walk))
    {
      vtkNew<vtkStringArray> names;
      for (const std::string& name : found)
      {
        names->InsertNextValue(name);
      }
      this->Directory->SetDirectoryName(nullptr);
      this->Directory->SetInputFileNames(names);
    }
    else
    {
      return std::string("cannot read the DICOM folder '") + folder + "': " + walk;
    }
    this->Directory->Modified(); // rescanned each time: files may have come or gone
    // Every file vtk-dicom will parse, parsed first in a child (the scan
    // below, then each file's pixel data): a file that crashes its parser
    // must not end this process (Python, ParaView).
    std::vector<std::string> probed = found;
    if (probed.empty())
    {
      mcxio::DicomFolderFiles(folder, mcxio::DicomScanDepth, mcxio::DicomFileLimit, probed, walk);
      probed.push_back(std::string(folder) + "/DICOMDIR");
    }
    std::string probe;
    vtkDICOMDirectory* directory = this->Directory;
    if (!mcxio::ProbeDicomFiles(
          probed, [directory]() { directory->Update(); }, probe))
    {
      return std::string("cannot read the DICOM series in '") + folder + "': " + probe;
    }
    FirstError scan(this->Directory);
    this->Directory->Update();
    this->ListSeries();
    const int count = this->Directory->GetNumberOfSeries();
    if (count == 0)
    {
      return std::string("no DICOM series in '") + folder + "'" +
        (scan.Message().empty() ? std::string() : ": " + scan.Message());
    }
    code = vtkErrorCode::FileFormatError;
    const std::string split = SplitSeries(this->Directory);
    if (!split.empty())
    {
      return std::string("the DICOM files in '") + folder + "' do not make consistent series: " +
        split;
    }
    if (index >= count || (index < 0 && count > 1))
    {
      code = SeriesChoiceError;
      std::string list;
      for (int s = 0; s < count; ++s)
      {
        list += (s ? "; " : "") + std::to_string(s) + ": " + Describe(this->Directory, s);
      }
      return std::string("'") + folder + "' holds " + std::to_string(count) + " DICOM series" +
        (index >= count ? "; there is no series index " + std::to_string(index) : std::string()) +
        "; choose one with SetSeriesIndex: " + list;
    }
    vtkStringArray* names = this->Directory->GetFileNamesForSeries(std::max(index, 0));
    // Each file's pixel data against its header before vtk-dicom allocates
    // what the header claims (NumberOfFrames 2^31 - 1) or decodes garbage.
    std::vector<std::string> files;
    for (vtkIdType f = 0; f < names->GetNumberOfValues(); ++f)
    {
      files.push_back(names->GetValue(f));
    }
    unsigned long long claimed = 0;
    std::string problem;
    if (!mcxio::CheckDicomPixelData(files, claimed, problem))
    {
      return std::string("cannot read the DICOM series in '") + folder + "': " + problem;
    }
    this->Reader->SetFileNames(names);
    code = vtkErrorCode::NoError;
    return std::string();
  }

  // "" when the voxels the reader's information claims fit the budget (0:
  // any) and can be allocated now, else why: vtk-dicom's arrays fail an
  // allocation without an exception, and it then writes through null.
  std::string CheckRoom(const char* folder, unsigned long long budget)
  {
    vtkInformation* info = this->Reader->GetOutputInformation(0);
    int extent[6] = { 0, -1, 0, -1, 0, -1 };
    info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
    vtkInformation* scalars = vtkDataObject::GetActiveFieldInformation(
      info, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
    double bytes = scalars && scalars->Has(vtkDataObject::FIELD_ARRAY_TYPE())
      ? vtkDataArray::GetDataTypeSize(scalars->Get(vtkDataObject::FIELD_ARRAY_TYPE()))
      : 8.0;
    bytes *= scalars && scalars->Has(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS())
      ? scalars->Get(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS())
      : 1;
    for (int a = 0; a < 3; ++a)
    {
      bytes *= std::max(0, extent[2 * a + 1] - extent[2 * a] + 1);
    }
    const std::string where = std::string("cannot read the DICOM series in '") + folder + "': ";
    if (budget > 0 && bytes > static_cast<double>(budget))
    {
      return where + "its voxels need " + mcx::DescribeBytes(bytes) +
        ", more than the memory budget of " + mcx::DescribeBytes(double(budget));
    }
    void* room = bytes < 9e18 ? std::malloc(static_cast<std::size_t>(bytes) + 1) : nullptr;
    std::free(room);
    return room ? std::string()
                : where + "out of memory: its voxels need " + mcx::DescribeBytes(bytes);
  }

  // The chosen series' geometry in patient space; empty on success.
  std::string ReadInformation(const char* folder, unsigned long& code)
  {
    code = vtkErrorCode::FileFormatError;
    this->Reader->SetMemoryRowOrderToFileNative();
    this->Reader->AutoRescaleOn(); // CT values in HU
    FirstError read(this->Reader);
    this->Reader->UpdateInformation();
    if (!read.Message().empty())
    {
      return std::string("cannot read the DICOM series in '") + folder + "': " + read.Message();
    }
    // Patient space: world = M (spacing x index), M the patient matrix.
    vtkMatrix4x4* m = this->Reader->GetPatientMatrix();
    const double normal[3] = { m->GetElement(0, 2), m->GetElement(1, 2), m->GetElement(2, 2) };
    const std::string stack = mcxio::CheckSlicesStack(this->Reader);
    const std::string spacing =
      stack.empty() ? mcxio::CheckSliceSpacing(this->Reader, normal) : stack;
    if (!spacing.empty())
    {
      return std::string("the DICOM series in '") + folder + "' is not a volume: " + spacing;
    }
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        this->Direction[3 * r + c] = m->GetElement(r, c);
      }
    }
    double o[3] = { 0, 0, 0 };
    this->Reader->GetOutputInformation(0)->Get(vtkDataObject::ORIGIN(), o);
    for (int r = 0; r < 3; ++r)
    {
      this->Origin[r] = m->GetElement(r, 3) + this->Direction[3 * r] * o[0] +
        this->Direction[3 * r + 1] * o[1] + this->Direction[3 * r + 2] * o[2];
    }
    code = vtkErrorCode::NoError;
    return std::string();
  }
};

vtkMCXDICOMSeriesReader::vtkMCXDICOMSeriesReader()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(0);
  // The reader's progress is this reader's; an abort here stops it.
  this->Internal->Progress->SetClientData(this);
  this->Internal->Progress->SetCallback(
    [](vtkObject* caller, unsigned long, void* self, void*)
    {
      auto* reader = static_cast<vtkDICOMReader*>(caller);
      auto* outer = static_cast<vtkMCXDICOMSeriesReader*>(self);
      outer->UpdateProgress(reader->GetProgress());
      if (outer->GetAbortExecute())
      {
        reader->AbortExecuteOn();
      }
    });
  this->Internal->Reader->AddObserver(vtkCommand::ProgressEvent, this->Internal->Progress);
}

vtkMCXDICOMSeriesReader::~vtkMCXDICOMSeriesReader()
{
  this->SetDirectoryName(nullptr);
}

int vtkMCXDICOMSeriesReader::GetNumberOfSeries()
{
  return static_cast<int>(this->Internal->Series.size());
}

std::string vtkMCXDICOMSeriesReader::GetSeriesDescription(int index)
{
  if (index < 0 || index >= this->GetNumberOfSeries())
  {
    return std::string();
  }
  return this->Internal->Series[static_cast<std::size_t>(index)];
}

std::string vtkMCXDICOMSeriesReader::ReadInChild(unsigned long& code)
{
  const std::string folder = this->DirectoryName ? this->DirectoryName : "";
  mcxio::ReadLimits limits;
  limits.Seconds = this->TimeLimit;
  limits.MemoryBytes = this->MemoryBudget;
  limits.ReadHereWhenNotHandedOver = false; // never parsed here
  // The child's progress is this reader's; an abort stops the child (the
  // executive clears AbortExecute before RequestData, not before this).
  this->AbortExecuteOff();
  limits.Progress = [this](double fraction)
  {
    this->UpdateProgress(fraction);
    return !this->GetAbortExecute();
  };
  const int index = this->SeriesIndex;
  const unsigned long long budget = this->MemoryBudget;
  auto read = [&folder, index, budget](
                std::string& error, std::string& note, const std::function<void(double)>& progress)
  {
    vtkNew<vtkMCXDICOMSeriesReader> reader;
    reader->SetDirectoryName(folder.c_str());
    reader->SetSeriesIndex(index);
    reader->SetMemoryBudget(budget);
    reader->ReadInChildProcessOff(); // this is the child
    vtkNew<vtkCallbackCommand> report;
    report->SetClientData(const_cast<std::function<void(double)>*>(&progress));
    report->SetCallback(
      [](vtkObject* caller, unsigned long, void* to, void*)
      {
        (*static_cast<std::function<void(double)>*>(to))(
          static_cast<vtkAlgorithm*>(caller)->GetProgress());
      });
    reader->AddObserver(vtkCommand::ProgressEvent, report);
    vtkNew<vtkMCXFirstErrorObserver> errors;
    errors->ObserveAlgorithm(reader);
    reader->Update();
    errors->StopObserving();
    note = SeriesNote(reader->GetErrorCode(), reader->Internal->Series);
    error = errors->GetErrorText();
    auto volume = vtkSmartPointer<vtkImageData>::New();
    volume->ShallowCopy(reader->GetOutput());
    return error.empty() ? volume : nullptr;
  };
  this->UpdateProgress(0.0);
  std::string error;
  std::string note;
  this->Internal->Volume = mcxio::RunContained(folder, read, limits, error, note);
  if (!ReadSeriesNote(note, code, this->Internal->Series))
  {
    code = vtkErrorCode::FileFormatError; // the child said nothing: it crashed or hung
  }
  if (this->Internal->Volume || !error.empty() || this->GetAbortExecute())
  {
    return error; // "" and no volume: stopped by the user
  }
  return "cannot read the DICOM series in '" + folder + "'";
}

std::string vtkMCXDICOMSeriesReader::ReadInformationHere(unsigned long& code)
{
  const char* folder = this->DirectoryName ? this->DirectoryName : "";
  std::string problem = this->Internal->ChooseSeries(this->DirectoryName, this->SeriesIndex, code);
  if (problem.empty())
  {
    problem = this->Internal->ReadInformation(folder, code);
  }
  if (problem.empty())
  {
    problem = this->Internal->CheckRoom(folder, this->MemoryBudget);
    code = problem.empty() ? code : vtkErrorCode::OutOfDiskSpaceError;
  }
  return problem;
}

int vtkMCXDICOMSeriesReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // A failure below leaves no stale volume of an earlier series.
  vtkImageData::GetData(outInfo)->Initialize();
  this->Internal->Volume = nullptr;
  this->Internal->Series.clear();
  unsigned long code = vtkErrorCode::NoError;
  const std::string problem =
    this->ReadInChildProcess ? this->ReadInChild(code) : this->ReadInformationHere(code);
  if (!problem.empty() && code == vtkErrorCode::NoError)
  {
    code = vtkErrorCode::FileFormatError; // the child read it, this process could not take it
  }
  this->SetErrorCode(code);
  if (!problem.empty())
  {
    vtkErrorMacro(<< mcx::PrintableText(problem));
  }
  // A child read stopped by the user leaves no volume and no error
  // (Modified() reads again).
  this->Internal->Failed =
    !problem.empty() || (this->ReadInChildProcess && !this->Internal->Volume);
  if (this->Internal->Failed)
  {
    // One line, said above, then an empty extent (not a failed request,
    // which the executive would report again).
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    return 1;
  }
  if (vtkImageData* volume = this->Internal->Volume)
  {
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), volume->GetExtent(), 6);
    outInfo->Set(vtkDataObject::SPACING(), volume->GetSpacing(), 3);
    outInfo->Set(vtkDataObject::ORIGIN(), volume->GetOrigin(), 3);
    outInfo->Set(vtkDataObject::DIRECTION(), volume->GetDirectionMatrix()->GetData(), 9);
    vtkDataArray* scalars = volume->GetPointData()->GetScalars();
    vtkDataObject::SetPointDataActiveScalarInfo(
      outInfo, scalars->GetDataType(), scalars->GetNumberOfComponents());
    return 1;
  }
  vtkInformation* readerInfo = this->Internal->Reader->GetOutputInformation(0);
  outInfo->CopyEntry(readerInfo, vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT());
  outInfo->CopyEntry(readerInfo, vtkDataObject::SPACING());
  outInfo->CopyEntry(readerInfo, vtkDataObject::POINT_DATA_VECTOR(), 1);
  outInfo->Set(vtkDataObject::ORIGIN(), this->Internal->Origin, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), this->Internal->Direction, 9);
  return 1;
}

int vtkMCXDICOMSeriesReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  if (this->Internal->Failed)
  {
    return 1; // reported by RequestInformation
  }
  if (this->Internal->Volume)
  {
    output->ShallowCopy(this->Internal->Volume); // read whole in the child
    return 1;
  }
  const std::string folder = this->DirectoryName ? this->DirectoryName : "";
  vtkDICOMReader* reader = this->Internal->Reader;
  FirstError read(reader);
  try
  {
    reader->AbortExecuteOff();
    reader->UpdateWholeExtent();
  }
  catch (const std::exception&) // bad_alloc, length_error: never the end of the process
  {
    this->SetErrorCode(vtkErrorCode::UnknownError);
    this->Internal->Forget();
    vtkErrorMacro(<< "out of memory reading the DICOM series in '" << folder << "'");
    return 1;
  }
  if (this->GetAbortExecute())
  {
    this->Internal->Forget();
    return 1; // stopped by the user: an empty output, no error
  }
  vtkImageData* image = reader->GetOutput();
  if (!read.Message().empty() || reader->GetErrorCode() != vtkErrorCode::NoError || !image ||
    image->GetNumberOfPoints() == 0 || !image->GetPointData()->GetScalars())
  {
    this->SetErrorCode(reader->GetErrorCode() ? reader->GetErrorCode() : vtkErrorCode::FileFormatError);
    this->Internal->Forget(); // a partial read must not pass as current next time
    vtkErrorMacro(<< mcx::PrintableText("cannot read the DICOM series in '" + folder + "'" +
                    (read.Message().empty() ? std::string(": no image data")
                                            : ": " + read.Message())));
    return 1;
  }
  output->ShallowCopy(image);
  output->SetOrigin(this->Internal->Origin);
  output->SetDirectionMatrix(this->Internal->Direction);
  reader->GetOutput()->ReleaseData(); // the output holds the voxels now
  this->SetErrorCode(vtkErrorCode::NoError);
  return 1;
}

void vtkMCXDICOMSeriesReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DirectoryName: " << (this->DirectoryName ? this->DirectoryName : "(none)")
     << "\n";
  os << indent << "SeriesIndex: " << this->SeriesIndex << "\n";
  os << indent << "MemoryBudget: " << this->MemoryBudget << "\n";
  os << indent << "ReadInChildProcess: " << this->ReadInChildProcess << "\n";
  os << indent << "TimeLimit: " << this->TimeLimit << "\n";
  os << indent << "NumberOfSeries (last scan): " << this->GetNumberOfSeries() << "\n";
}
