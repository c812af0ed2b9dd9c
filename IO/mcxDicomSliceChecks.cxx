// The checks that a series' images make one volume (mcxDicomSliceChecks.h).
#include "mcxDicomSliceChecks.h"

#include "mcxHeaderCheckPrivate.h"

#include "vtkDICOMDictHash.h"
#include "vtkDICOMMetaData.h"
#include "vtkDICOMReader.h"
#include "vtkDICOMValue.h"
#include "vtkIntArray.h"
#include "vtkStringArray.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace mcxio
{

namespace
{
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

}

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

} // namespace mcxio
