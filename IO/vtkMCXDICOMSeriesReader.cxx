#include "vtkMCXDICOMSeriesReader.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDICOMDictHash.h"
#include "vtkDICOMDirectory.h"
#include "vtkDICOMItem.h"
#include "vtkDICOMMetaData.h"
#include "vtkDICOMReader.h"
#include "vtkDICOMValue.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMCXFirstErrorObserver.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtksys/SystemTools.hxx"

#include "mcxByteSize.h"
#include "mcxDicomFiles.h"
#include "mcxHeaderCheckPrivate.h"
#include "mcxPrintableText.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <new>
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

// Positions along the slice normal, in the reader's slice order.
std::vector<double> SlicePositions(vtkDICOMReader* reader, const double normal[3])
{
  vtkIntArray* files = reader->GetFileIndexArray();
  vtkIntArray* frames = reader->GetFrameIndexArray(); // enhanced multi-frame files
  vtkDICOMMetaData* meta = reader->GetMetaData();
  std::vector<double> along(static_cast<std::size_t>(files->GetNumberOfTuples()));
  for (vtkIdType k = 0; k < files->GetNumberOfTuples(); ++k)
  {
    double p[3] = { 0, 0, 0 };
    const int file = static_cast<int>(files->GetComponent(k, 0));
    const int frame = frames ? static_cast<int>(frames->GetComponent(k, 0)) : 0;
    const vtkDICOMValue& position = meta->Get(file, frame, DC::ImagePositionPatient);
    if (position.GetNumberOfValues() == 3)
    {
      position.GetValues(p, 3);
    }
    along[static_cast<std::size_t>(k)] = p[0] * normal[0] + p[1] * normal[1] + p[2] * normal[2];
  }
  return along;
}

// Values of one decimal-string attribute of image (file, frame), parsed
// from its text (vtk-dicom reads "nan" as a number); false unless there
// are `count` of them, each finite.
bool FiniteValues(
  vtkDICOMMetaData* meta, int file, int frame, vtkDICOMTag tag, std::size_t count, double* values)
{
  std::string text = meta->Get(file, frame, tag).AsString();
  std::replace(text.begin(), text.end(), '\\', ' ');
  std::vector<double> parsed;
  if (!mcxio::check::ParseFiniteNumbers(text, parsed) || parsed.size() != count)
  {
    return false;
  }
  std::copy(parsed.begin(), parsed.end(), values);
  return true;
}

// Whether the images stack into one volume as vtk-dicom reads it: each
// with a position, the first image's orientation and pixel spacing (> 0),
// and a finite rescale; and every image of the series in the volume (its
// slice sorter leaves out what does not stack, a tilted slice). Empty
// when they do, else which image does not and why.
std::string CheckSlicesStack(vtkDICOMReader* reader)
{
  const vtkIdType filesInSeries = reader->GetFileNames()->GetNumberOfValues();
  vtkIntArray* files = reader->GetFileIndexArray();
  vtkIntArray* frames = reader->GetFrameIndexArray();
  vtkDICOMMetaData* meta = reader->GetMetaData();
  double first[8] = { 0, 0, 0, 0, 0, 0, 0, 0 }; // orientation, then pixel spacing
  std::vector<bool> used(static_cast<std::size_t>(std::max<vtkIdType>(filesInSeries, 0)));
  for (vtkIdType k = 0; k < files->GetNumberOfTuples(); ++k)
  {
    const int file = static_cast<int>(files->GetComponent(k, 0));
    const int frame = frames ? static_cast<int>(frames->GetComponent(k, 0)) : 0;
    if (file < 0 || file >= static_cast<int>(used.size()) || file >= meta->GetNumberOfInstances() ||
      frame < 0)
    {
      return "slice " + std::to_string(k + 1) + " is no image of the series";
    }
    for (int c = 0; c < files->GetNumberOfComponents(); ++c) // images sharing the slice
    {
      const int shared = static_cast<int>(files->GetComponent(k, c));
      if (shared >= 0 && shared < static_cast<int>(used.size()))
      {
        used[static_cast<std::size_t>(shared)] = true;
      }
    }
    const std::string slice = "slice " + std::to_string(k + 1) + " ('" +
      vtksys::SystemTools::GetFilenameName(reader->GetFileNames()->GetValue(file)) + "')";
    double v[8], rescale[2];
    if (!FiniteValues(meta, file, frame, DC::ImagePositionPatient, 3, v))
    {
      return slice + " has no ImagePositionPatient of 3 finite numbers";
    }
    if (!FiniteValues(meta, file, frame, DC::ImageOrientationPatient, 6, v) ||
      !FiniteValues(meta, file, frame, DC::PixelSpacing, 2, v + 6) || !(v[6] > 0 && v[7] > 0))
    {
      return slice +
        " has no ImageOrientationPatient of 6 finite numbers and PixelSpacing of 2 "
        "positive ones";
    }
    const bool same = k == 0 ||
      std::equal(v, v + 8, first,
        [](double a, double b) { return std::fabs(a - b) <= 1e-4 * std::max(1.0, std::fabs(b)); });
    if (!same)
    {
      return slice +
        " has another ImageOrientationPatient or PixelSpacing than slice 1 (a tilted "
        "or resized slice?)";
    }
    if (k == 0)
    {
      std::copy(v, v + 8, first);
    }
    const bool rescaled = meta->Get(file, frame, DC::RescaleSlope).IsValid() ||
      meta->Get(file, frame, DC::RescaleIntercept).IsValid();
    if (rescaled &&
      (!FiniteValues(meta, file, frame, DC::RescaleSlope, 1, rescale) ||
        !FiniteValues(meta, file, frame, DC::RescaleIntercept, 1, rescale + 1)))
    {
      return slice + " has no RescaleSlope and RescaleIntercept of one finite number each";
    }
  }
  const auto missing = std::find(used.begin(), used.end(), false);
  if (missing != used.end())
  {
    return "the image '" +
      vtksys::SystemTools::GetFilenameName(
        reader->GetFileNames()->GetValue(static_cast<vtkIdType>(missing - used.begin()))) +
      "' does not stack with the others (vtk-dicom left it out: another orientation or position; "
      "a localizer? remove it from the folder)";
  }
  return std::string();
}

// Repeated positions, gaps of more than 1.5 times the median spacing
// (missing slices) and slices off the even spacing the volume gives them;
// empty when the slices are evenly spaced.
std::string CheckSliceSpacing(vtkDICOMReader* reader, const double normal[3])
{
  if (reader->GetFileIndexArray()->GetNumberOfComponents() > 1)
  {
    return "several images share slice positions (duplicated slices, or a time series: "
           "keep one image per position)";
  }
  const std::vector<double> along = SlicePositions(reader, normal);
  if (along.size() < 3)
  {
    return std::string();
  }
  std::vector<double> steps;
  for (std::size_t k = 1; k < along.size(); ++k)
  {
    steps.push_back(std::fabs(along[k] - along[k - 1]));
  }
  std::vector<double> sorted = steps;
  // The lower median: with 2 steps, the smaller (a gap is the larger one).
  const std::size_t middle = (sorted.size() - 1) / 2;
  std::nth_element(sorted.begin(), sorted.begin() + middle, sorted.end());
  const double median = sorted[middle];
  for (std::size_t k = 0; k < steps.size(); ++k)
  {
    std::ostringstream where;
    where << " between slices " << k + 1 << " and " << k + 2 << " (" << along[k] << " and "
          << along[k + 1] << " mm along the normal)";
    if (!(steps[k] > 1e-3 * median))
    {
      return "two slices lie at the same position" + where.str() + " (a duplicated slice?)";
    }
    if (steps[k] > 1.5 * median)
    {
      std::ostringstream gap;
      gap << "a gap of " << steps[k] << " mm where the slices are " << median << " mm apart"
          << where.str() << " (missing slices?)";
      return gap.str();
    }
  }
  // The volume places slice k at along[0] + k x the mean step: refuse a
  // slice a tenth of a step or more off that, and more than the 0.05 mm of
  // positions written to 0.1 mm (0.25 mm slices among them).
  const double mean = (along.back() - along.front()) / static_cast<double>(along.size() - 1);
  std::size_t worst = 0;
  double worstOff = 0.0;
  for (std::size_t k = 1; k + 1 < along.size(); ++k)
  {
    const double off = std::fabs(along[k] - (along.front() + static_cast<double>(k) * mean));
    worst = off > worstOff ? k : worst;
    worstOff = std::max(off, worstOff);
  }
  if (worstOff >= std::max(0.1 * std::fabs(mean), 0.051))
  {
    std::ostringstream uneven;
    uneven << "slice " << worst + 1 << " lies " << worstOff << " mm off the even spacing of "
           << std::fabs(mean) << " mm (at " << along[worst]
           << " mm along the normal; resample the series to even spacing)";
    return uneven.str();
  }
  return std::string();
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
    const std::string stack = CheckSlicesStack(this->Reader);
    const std::string spacing = stack.empty() ? CheckSliceSpacing(this->Reader, normal) : stack;
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
  return this->Internal->Directory->GetNumberOfSeries();
}

std::string vtkMCXDICOMSeriesReader::GetSeriesDescription(int index)
{
  if (index < 0 || index >= this->GetNumberOfSeries())
  {
    return std::string();
  }
  return Describe(this->Internal->Directory, index);
}

int vtkMCXDICOMSeriesReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // A failure below leaves no stale volume of an earlier series.
  vtkImageData::GetData(outInfo)->Initialize();
  const char* folder = this->DirectoryName ? this->DirectoryName : "";
  unsigned long code = vtkErrorCode::NoError;
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
  this->SetErrorCode(code);
  if (!problem.empty())
  {
    // One line: reported here, then an empty extent (not a failed request,
    // which the executive would report again).
    vtkErrorMacro(<< mcx::PrintableText(problem));
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    this->Internal->Failed = true;
    return 1;
  }
  this->Internal->Failed = false;
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
  os << indent << "NumberOfSeries (last scan): " << this->GetNumberOfSeries() << "\n";
}
