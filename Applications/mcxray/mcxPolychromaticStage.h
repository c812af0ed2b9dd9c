// The polychromatic render of mcxray: --spectrum, --materials,
// --detector-material and --photon-counting. The samples are drawn under
// the materials' total density and each deposit is split into the
// materials' channels by its level's mass fractions (vtkMCXProjector's
// channels); vtkMCXPolychromaticRadiograph maps the channels through the
// spectrum and the detector.
#ifndef mcxPolychromaticStage_h
#define mcxPolychromaticStage_h

#include "vtkNew.h"

#include <string>
#include <vector>

class vtkImageData;
class vtkMCXMaterialWeights;
class vtkMCXProjector;
class vtkMCXPolychromaticRadiograph;
class vtkPiecewiseFunction;

namespace mcxapp
{
struct Settings;

/// The detector text of vtkMCXPolychromaticRadiograph and vtkMCXXRayMapper
/// for --photon-counting and --detector-material.
std::string PolychromaticDetector(const Settings& settings);

/// Whether any polychromatic option was given (one line and exit when
/// --materials, --detector-material or --photon-counting come without
/// --spectrum).
bool PolychromaticAsked(const Settings& settings);

class PolychromaticStage
{
public:
  /// Checks the options (one line and exit on a bad one); inactive without --spectrum.
  explicit PolychromaticStage(const Settings& settings);
  ~PolychromaticStage();

  bool Active() const { return this->Enabled; }
  /// The projector's transfer function: the density curve (g/cm^3 per HU).
  vtkPiecewiseFunction* Density() const;
  /// Splits the projector's deposit into the materials' channels.
  void SplitIntoChannels(vtkMCXProjector* projector);
  /// The radiograph of a projection split into channels, pose k's noise seed.
  vtkImageData* Radiograph(
    vtkImageData* channels, const Settings& settings, int k, std::string& line);
  /// A line for the log: the spectrum's mean energy and HVL, the materials.
  std::string Describe() const;

private:
  bool Enabled = false;
  int Count = 0;
  std::string Summary;
  vtkNew<vtkMCXMaterialWeights> Weights;
  vtkNew<vtkMCXPolychromaticRadiograph> Filter;
  vtkNew<vtkPiecewiseFunction> DensityFunction;
};

} // namespace mcxapp

#endif
