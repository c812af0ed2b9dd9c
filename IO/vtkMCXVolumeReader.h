/**
 * @class   vtkMCXVolumeReader
 * @brief   Any volume the project reads, its header checked against the
 *          file first: what mcxray reads, for Python, C++ and ParaView.
 *
 * Reads FileName by its extension: .vti, .mha/.mhd (vtkMCXMetaImageReader),
 * .nii/.nii.gz (vtkMCXNIFTIReader), .nrrd/.nhdr (vtkMCXNrrdReader), .vtk
 * (structured points), .slc, or a folder holding a DICOM series
 * (vtkMCXDICOMSeriesReader, where IO is built with vtk-dicom), placed in
 * DICOM patient space (LPS). Before any VTK reader sees the file, its
 * header is checked against it (mcxHeaderCheck.h: dimensions, type, the
 * bytes the data hold), and the voxels the header claims against
 * MemoryBudget. A lying, truncated or unusable file is one vtkErrorMacro
 * line, "cannot read 'path': reason" (the text mcxray prints), an error
 * code (vtkErrorCode::FileFormatError) and an empty output.
 *
 * With ReadInChildProcess on (off by default; what mcxray does), the file
 * is read in a forked child process under an address-space limit of
 * MemoryBudget and stopped after TimeLimit seconds, the volume handed back
 * through shared memory: a reader that crashes or hangs on a file that
 * passed the checks is one line of error, not the end of this process. A
 * DICOM folder is read so whatever the setting (vtk-dicom's parser reads
 * past its buffer on some damaged files, vtkMCXDICOMSeriesReader.h).
 *
 * The volume is read whole when the pipeline first asks for information
 * (several formats place the volume only once read, and the child reads in
 * one go) and again after a setting changes; RequestData hands it over,
 * cut to the requested extent (a piece of ParaView's, say).
 */
#ifndef vtkMCXVolumeReader_h
#define vtkMCXVolumeReader_h

#include "MonteCarloXRayIOModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // for the volume read
#include "vtkTimeStamp.h"    // for when it was read

#include <string> // for the last error

class vtkImageData;

class MONTECARLOXRAYIO_EXPORT vtkMCXVolumeReader : public vtkImageAlgorithm
{
public:
  static vtkMCXVolumeReader* New();
  vtkTypeMacro(vtkMCXVolumeReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The volume file or DICOM folder (default: none). */
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /**
   * Which DICOM series of a folder to read, numbered from 1 as the error
   * that lists them numbers them; 0 (the default) when the folder must hold
   * exactly one.
   */
  vtkSetClampMacro(DicomSeries, int, 0, VTK_INT_MAX);
  vtkGetMacro(DicomSeries, int);
  ///@}

  ///@{
  /**
   * Bytes the voxels the header claims may take (in the child: its address
   * space for data); 0 (the default): any.
   */
  vtkSetMacro(MemoryBudget, unsigned long long);
  vtkGetMacro(MemoryBudget, unsigned long long);
  ///@}

  ///@{
  /** Whether to read in a child process within the limits (default: off). */
  vtkSetMacro(ReadInChildProcess, bool);
  vtkGetMacro(ReadInChildProcess, bool);
  vtkBooleanMacro(ReadInChildProcess, bool);
  ///@}

  ///@{
  /** Seconds the child may read before it is stopped (default: 300). */
  vtkSetClampMacro(TimeLimit, double, 0.001, VTK_DOUBLE_MAX);
  vtkGetMacro(TimeLimit, double);
  ///@}

  /** 1 if name has an extension this reader reads or is a folder, else 0. */
  int CanReadFile(const char* name);

protected:
  vtkMCXVolumeReader();
  ~vtkMCXVolumeReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;
  int DicomSeries = 0;
  unsigned long long MemoryBudget = 0;
  bool ReadInChildProcess = false;
  double TimeLimit = 300.0;

private:
  vtkMCXVolumeReader(const vtkMCXVolumeReader&) = delete;
  void operator=(const vtkMCXVolumeReader&) = delete;

  // Reads FileName as the settings say: "" or the one line of error.
  std::string Read();

  vtkSmartPointer<vtkImageData> Volume; // the last volume read (null after a failure)
  std::string Error;                    // the last read's error ("" after a success)
  vtkTimeStamp ReadTime;                // when Volume or Error was last set
};

#endif
