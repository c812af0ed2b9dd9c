/**
 * @class   vtkMCXDICOMSeriesReader
 * @brief   A DICOM series as hospitals export it, read with vtk-dicom.
 *
 * Scans DirectoryName (and its subfolders, four levels deep, as exports nest
 * them) for DICOM series, reads the chosen one with vtk-dicom's
 * vtkDICOMReader and checks it is a volume:
 * - slices sorted by position along the slice normal;
 * - rescale slope and intercept applied (CT values in Hounsfield units);
 * - the output placed in patient space: origin and direction matrix from the
 *   patient matrix (world = direction x (spacing x index) + origin);
 * - repeated slice positions (duplicated slices, time series), gaps of more
 *   than 1.5 times the median spacing (missing slices), a series whose images
 *   fall into parts, and short pixel data are errors that say where;
 * - each file's pixel data checked against its header before vtk-dicom
 *   allocates (frames x rows x columns x samples x bits within the file, or
 *   encapsulated in fragments of its transfer syntax, RLE decoded whole), an
 *   unsupported transfer syntax and a decoder's failure are errors, and the
 *   voxels within MemoryBudget; each folder and file is scanned once (by
 *   inode: links to '..' or to a folder itself add nothing).
 *
 * Errors are reported with vtkErrorMacro as one line, and leave an empty
 * output; GetErrorCode() tells them apart (vtkErrorCode's codes, and
 * SeriesChoiceError when the folder holds several series and SeriesIndex
 * names none of them). VTK's vtkDICOMImageReader trusts its headers and passes truncated
 * slices silently; this reader does neither.
 *
 * By default the series is read whole in a child process (ReadInChildProcess)
 * when the pipeline first asks for information, and handed back with the
 * folder's list of series; RequestData hands the volume over.
 *
 * After UpdateInformation(), GetNumberOfSeries() and GetSeriesDescription()
 * list the folder's series, so that a caller can choose one.
 */
#ifndef vtkMCXDICOMSeriesReader_h
#define vtkMCXDICOMSeriesReader_h

#include "MonteCarloXRayIOModule.h" // for export macro
#include "vtkErrorCode.h"     // for vtkErrorCode::UserError
#include "vtkImageAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string

class MONTECARLOXRAYIO_EXPORT vtkMCXDICOMSeriesReader : public vtkImageAlgorithm
{
public:
  static vtkMCXDICOMSeriesReader* New();
  vtkTypeMacro(vtkMCXDICOMSeriesReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** GetErrorCode() after the folder's series could not be chosen. */
  enum
  {
    SeriesChoiceError = vtkErrorCode::UserError + 1
  };

  ///@{
  /** The folder that holds the series (default: none). */
  vtkSetStringMacro(DirectoryName);
  vtkGetStringMacro(DirectoryName);
  ///@}

  ///@{
  /**
   * Which of the folder's series to read: 0, 1, ... in the order of
   * GetSeriesDescription(); -1 (the default) when the folder must hold
   * exactly one (else an error lists them).
   */
  vtkSetClampMacro(SeriesIndex, int, -1, VTK_INT_MAX);
  vtkGetMacro(SeriesIndex, int);
  ///@}

  ///@{
  /**
   * Bytes the series' voxels may take (0, the default: any); checked with
   * the files' pixel data against their headers before anything is read
   * (and, read in a child, its address space for data).
   */
  vtkSetMacro(MemoryBudget, unsigned long long);
  vtkGetMacro(MemoryBudget, unsigned long long);
  ///@}

  ///@{
  /**
   * Whether to read in a child process (default: on): vtk-dicom's parser
   * reads past its buffer on some damaged files, a fault that depends on
   * what the heap held, so that by default no file is parsed in this
   * process (Python, ParaView). The child reads the whole series under an
   * address-space limit of MemoryBudget and hands it back through shared
   * memory; a crash, or a read past TimeLimit, is one line of error. (A
   * file-size limit, ulimit -f, that keeps it from handing the volume over
   * is an error too, not a read here.) The child's progress is this
   * reader's, and AbortExecute (set from a progress observer) stops it: an
   * empty output and no error, read again after Modified(). Off: read in
   * this process, each file's parse probed in a child first.
   */
  vtkSetMacro(ReadInChildProcess, bool);
  vtkGetMacro(ReadInChildProcess, bool);
  vtkBooleanMacro(ReadInChildProcess, bool);
  ///@}

  ///@{
  /** Seconds the child may read before it is stopped (default: 300). */
  vtkSetClampMacro(TimeLimit, double, 0.001, VTK_DOUBLE_MAX);
  vtkGetMacro(TimeLimit, double);
  ///@}

  /** The number of series the last scan of DirectoryName found. */
  int GetNumberOfSeries();

  /**
   * Series index of the last scan, in words: "CT 'HEAD' (93 images)"
   * (modality, series description, number of images); empty when out of range.
   */
  std::string GetSeriesDescription(int index);

protected:
  vtkMCXDICOMSeriesReader();
  ~vtkMCXDICOMSeriesReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* DirectoryName = nullptr;
  int SeriesIndex = -1;
  unsigned long long MemoryBudget = 0;
  bool ReadInChildProcess = true;
  double TimeLimit = 300.0;

private:
  vtkMCXDICOMSeriesReader(const vtkMCXDICOMSeriesReader&) = delete;
  void operator=(const vtkMCXDICOMSeriesReader&) = delete;

  // The series read whole in a child; "" or the one line of error.
  std::string ReadInChild(unsigned long& code);
  // The series chosen and its information read in this process; "" or the
  // one line of error.
  std::string ReadInformationHere(unsigned long& code);

  // vtk-dicom's directory scan and reader, kept out of the public header.
  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
