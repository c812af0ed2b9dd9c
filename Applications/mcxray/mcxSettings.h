// What the command line says: the options of both commands in one place,
// filled by the option table. Each command reads the part it accepts.
#ifndef mcxSettings_h
#define mcxSettings_h

#include "mcxContainedReader.h"
#include "mcxImageOutput.h"
#include "mcxRadiographSettings.h"
#include "vtkMCXMemoryCheck.h"

#include <string>

namespace mcxapp
{

struct Settings
{
  std::string Input; // empty: the bundled CT
  std::string TF = "raw";
  long long Samples = 0; // each command sets its default before parsing
  bool SamplesGiven = false;
  std::string Method = "hybrid";
  std::string Kernel = "tent";
  std::string Deposit = "footprint";
  bool DepositGiven = false; // without it a target chooses the deposit by measurement
  unsigned long long Seed = 0;
  double ReorderAngle = -1.0; // --reorder-angle, degrees; below 0: the mapper's default
  int Threads = 0;            // 0: all cores
  double MemoryLimit = 0.0;   // bytes; 0: the machine's physical memory
  double ReadTimeout = 300.0; // seconds the volume reader may take
  int DicomSeries = 0;        // --series: a DICOM folder's series (1, 2, ...); 0: its only one
  bool SizeGiven = false;
  int Size[2] = { 0, 0 };
  RadiographSettings Radiograph;
  bool RASCoordinates =
    false; // --coordinates ras: the view's points, directions and matrices in RAS (else LPS)

  // render only
  std::string View = "+z";
  bool ViewGiven = false;
  std::string Camera;
  std::string OutputGeometry; // --output-geometry: the poses' matrices as JSON
  double PixelSpacing = 0.0;
  std::string Output = "mcxray.png";
  PngWindow Window;
  double Tolerance = 1e-3;
  bool ToleranceGiven = false; // the reference method's alone
  bool Quiet = false;
  bool StoredPoints = false;
  double TargetError = 0.0;
  int QuantizationLevels = 0;
  std::string Spectrum; // --spectrum: a polychromatic radiograph (mcxPolychromaticStage.h)
  std::string Materials = "default"; // --materials
  bool MaterialsGiven = false;
  std::string DetectorMaterial; // --detector-material M:mm[:g/cm3]
  bool PhotonCounting = false;  // --photon-counting

  // view only
  std::string Screenshot;
};

/// The reader's limits the options set: --read-timeout and --memory-limit
/// (else the machine's physical memory).
inline mcxio::ReadLimits ReadLimitsOf(const Settings& settings)
{
  mcxio::ReadLimits limits;
  limits.Seconds = settings.ReadTimeout;
  limits.SecondsName = "--read-timeout";
  // Both at most 2^62 bytes (--memory-limit 2^60), so the cast is exact.
  limits.MemoryBytes = static_cast<unsigned long long>(
    settings.MemoryLimit > 0 ? settings.MemoryLimit : mcx::MemoryBudget());
  return limits;
}

/// How the options ask the input to be read (--series).
inline mcxio::VolumeReadOptions ReadOptionsOf(const Settings& settings)
{
  mcxio::VolumeReadOptions options;
  options.DicomSeries = settings.DicomSeries;
  options.MemoryBudgetName = "--memory-limit";
  options.DicomSeriesName = "--series N";
  return options;
}

} // namespace mcxapp

#endif
