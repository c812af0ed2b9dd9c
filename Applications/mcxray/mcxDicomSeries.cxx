#include "mcxDicomSeries.h"

#include "mcxReaderError.h"

#include "vtkDICOMDictHash.h"
#include "vtkDICOMDirectory.h"
#include "vtkDICOMItem.h"
#include "vtkDICOMMetaData.h"
#include "vtkDICOMReader.h"
#include "vtkDICOMValue.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace mcxapp
{

namespace
{
// "1: CT 'HEAD' (93 images)", one entry of the folder's list.
std::string DescribeSeries(vtkDICOMDirectory* directory, int s)
{
  const vtkDICOMItem& record = directory->GetSeriesRecord(s);
  std::ostringstream text;
  text << s + 1 << ": " << record.Get(DC::Modality).AsString() << " '"
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
          DescribeSeries(directory, static_cast<int>(a)) + "; " +
          DescribeSeries(directory, static_cast<int>(b)) +
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

// Repeated positions and gaps of more than 1.5 times the median spacing
// (missing slices); empty when the slices are evenly spaced.
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
  return std::string();
}
}

vtkSmartPointer<vtkImageData> ReadDicomSeries(
  const std::string& folder, int series, std::string& error)
{
  vtkNew<vtkDICOMDirectory> directory;
  directory->SetDirectoryName(folder.c_str());
  directory->SetScanDepth(4); // series in subfolders too, as exports nest them
  ReaderError scan(directory);
  directory->Update();
  const int count = directory->GetNumberOfSeries();
  if (count == 0)
  {
    error = "no DICOM series in '" + folder + "'" +
      (scan.Message.empty() ? std::string() : ": " + scan.Message);
    return nullptr;
  }
  const std::string split = SplitSeries(directory);
  if (!split.empty())
  {
    error = "the DICOM files in '" + folder + "' do not make consistent series: " + split;
    return nullptr;
  }
  if (series < 0 || series > count || (series == 0 && count > 1))
  {
    std::string list;
    for (int s = 0; s < count; ++s)
    {
      list += (s ? "; " : "") + DescribeSeries(directory, s);
    }
    error = "'" + folder + "' holds " + std::to_string(count) + " DICOM series" +
      (series > count ? "; there is no series " + std::to_string(series) : std::string()) +
      "; choose one with --series N: " + list;
    return nullptr;
  }
  vtkNew<vtkDICOMReader> reader;
  reader->SetFileNames(directory->GetFileNamesForSeries(std::max(series, 1) - 1));
  reader->SetMemoryRowOrderToFileNative();
  reader->AutoRescaleOn(); // CT values in HU
  ReaderError read(reader);
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (!read.Message.empty() || !image || image->GetNumberOfPoints() == 0 ||
    !image->GetPointData()->GetScalars())
  {
    error = "cannot read the DICOM series in '" + folder + "'" +
      (read.Message.empty() ? std::string(": no image data") : ": " + read.Message);
    return nullptr;
  }
  // Patient space: world = M (spacing x index), M the patient matrix.
  vtkMatrix4x4* m = reader->GetPatientMatrix();
  const double normal[3] = { m->GetElement(0, 2), m->GetElement(1, 2), m->GetElement(2, 2) };
  const std::string spacing = CheckSliceSpacing(reader, normal);
  if (!spacing.empty())
  {
    error = "the DICOM series in '" + folder + "' is not a volume: " + spacing;
    return nullptr;
  }
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->ShallowCopy(image);
  double direction[9];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      direction[3 * r + c] = m->GetElement(r, c);
    }
  }
  volume->SetDirectionMatrix(direction);
  const double* o = image->GetOrigin();
  double origin[3];
  for (int r = 0; r < 3; ++r)
  {
    origin[r] = m->GetElement(r, 3) + direction[3 * r] * o[0] + direction[3 * r + 1] * o[1] +
      direction[3 * r + 2] * o[2];
  }
  volume->SetOrigin(origin);
  return volume;
}

} // namespace mcxapp
