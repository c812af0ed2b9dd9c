// What the accuracy benchmarks measure with: wall time, medians, the exact
// reference, a Monte Carlo projector for one view, the relative RMS error of
// an image against the reference, and plastimatch's DRRs read back.
#ifndef mcxAccuracyMeasures_h
#define mcxAccuracyMeasures_h

#include "vtkMCXPointSampler.h"
#include "vtkMCXProjector.h"
#include "vtkSmartPointer.h"

#include <chrono>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkCamera;
class vtkDataObject;
class vtkImageData;
class vtkPiecewiseFunction;

namespace mcxbench
{
using Clock = std::chrono::steady_clock;

/// Seconds since start.
double Since(Clock::time_point start);

/// The median (the upper one for an even count); 0 for none.
double Median(std::vector<double> values);

/// The first value of a field-data array (a projector's SampleCount, ...).
double FieldValue(vtkDataObject* data, const char* name);

/// The LineIntegral values of an image, in VTK's point order.
std::vector<double> Values(vtkImageData* image);

/// Relative RMS difference of estimate from the reference's LineIntegral.
double RelativeRMS(const std::vector<double>& estimate, vtkImageData* reference);

/// The exact reference of one view (timed, in seconds).
vtkSmartPointer<vtkImageData> Reference(vtkAlgorithm* index, vtkPiecewiseFunction* tf,
  vtkCamera* camera, int size, double tolerance, int maximumSubdivision, double& seconds);

/// A Monte Carlo projector on an index, configured for one size x size view.
vtkSmartPointer<vtkMCXProjector> MakeProjector(vtkAlgorithm* index, vtkPiecewiseFunction* tf,
  vtkCamera* camera, int size, int exponent, int strategy = vtkMCXTypes::HYBRID,
  int deposit = vtkMCXTypes::POINT);

/// Reads a plastimatch PFM (top row first) into VTK's row order (bottom row
/// first); false when it is not a size x size PFM.
bool ReadPlastimatchPFM(const std::string& path, int size, std::vector<double>& values);

/// A volume for comparing with plastimatch, which reads the array in its
/// stored frame: read by mcxray's reader with the direction made identity;
/// null (the reason printed, naming the case) when it cannot be read.
vtkSmartPointer<vtkImageData> ReadInStoredFrame(const std::string& path, const std::string& name);

/// Peak resident memory of this process.
long PeakResidentMegabytes();

/// The accuracy benchmarks' command line: [--quick] [--output DIR] [--data DIR].
struct BenchmarkArguments
{
  bool Quick = false;
  std::string Output = "benchmark-results";
  std::string Data; // the shared volumes
};

/// Parses argv into arguments (Data defaulting to sharedData) and makes the
/// output folder; false, with the usage printed, on anything else.
bool ParseArguments(int argc, char* argv[], const char* program, const std::string& sharedData,
  BenchmarkArguments& arguments);
}

#endif
