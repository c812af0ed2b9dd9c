// The DICOM series of the checked read (mcxDicomSeries.h).
#include "mcxDicomSeries.h"

#include "vtkImageData.h"
#ifdef MCXRAY_IO_DICOM
#include "vtkMCXDICOMSeriesReader.h"
#endif
#include "vtkMCXFirstErrorObserver.h"
#include "vtkNew.h"

namespace mcxio
{

#ifndef MCXRAY_IO_DICOM
vtkSmartPointer<vtkImageData> ReadDicomSeries(
  const std::string& folder, const VolumeReadOptions&, std::string& error)
{
  error = "cannot read '" + folder + "': this build reads no DICOM series (it has no vtk-dicom)";
  return nullptr;
}
#else
vtkSmartPointer<vtkImageData> ReadDicomSeries(
  const std::string& folder, const VolumeReadOptions& options, std::string& error)
{
  const int series = options.DicomSeries;
  vtkNew<vtkMCXDICOMSeriesReader> reader;
  reader->SetDirectoryName(folder.c_str());
  reader->SetMemoryBudget(options.MemoryBudget);
  reader->SetSeriesIndex(series - 1); // counted from 1; 0 (none) is -1
  reader->SetReadInChildProcess(!options.DicomInThisProcess);
  vtkNew<vtkMCXFirstErrorObserver> read; // the reader's report, said once below
  read->ObserveAlgorithm(reader);
  reader->Update();
  read->StopObserving();
  if (reader->GetErrorCode() == vtkMCXDICOMSeriesReader::SeriesChoiceError)
  {
    // The reader's list counts from 0 and names its setter; ours counts from 1.
    const int count = reader->GetNumberOfSeries();
    std::string list;
    for (int s = 0; s < count; ++s)
    {
      list += (s ? "; " : "") + std::to_string(s + 1) + ": " + reader->GetSeriesDescription(s);
    }
    error = "'" + folder + "' holds " + std::to_string(count) + " DICOM series" +
      (series > count ? "; there is no series " + std::to_string(series) : std::string()) +
      "; choose one with " + options.DicomSeriesName + ": " + list;
    return nullptr;
  }
  if (!read->GetErrorText().empty())
  {
    // The budget as the caller's user sets it.
    error = read->GetErrorText() +
      (read->GetErrorText().find("memory budget") != std::string::npos
          ? " (" + options.MemoryBudgetName + ")"
          : std::string());
    return nullptr;
  }
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->ShallowCopy(reader->GetOutput());
  return volume;
}
#endif

} // namespace mcxio
