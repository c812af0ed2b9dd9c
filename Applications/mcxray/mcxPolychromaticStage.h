// The polychromatic render of mcxray: --spectrum, --materials,
// --detector-material and --photon-counting. One cloud is drawn under the
// materials' total density; each material's channel is projected from it
// (vtkMCXMaterialWeights), and vtkMCXPolychromaticRadiograph maps the
// channels through the spectrum and the detector.
#ifndef mcxPolychromaticStage_h
#define mcxPolychromaticStage_h

#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkAlgorithmOutput;
class vtkImageData;
class vtkMCXMaterialWeights;
class vtkMCXPolychromaticRadiograph;
class vtkPiecewiseFunction;

namespace mcxapp
{
struct Settings;

/// The detector text of vtkMCXPolychromaticRadiograph and vtkMCXXRayMapper
/// for --photon-counting and --detector-material.
std::string PolychromaticDetector(const Settings& settings);

class PolychromaticStage
{
public:
  /// Checks the options (one line and exit on a bad one); inactive without --spectrum.
  explicit PolychromaticStage(const Settings& settings);
  ~PolychromaticStage();

  bool Active() const { return this->Enabled; }
  int Channels() const { return this->Count; }
  const std::string& Name(int m) const { return this->Names[m]; }
  /// The sampler's transfer function: the density curve (g/cm^3 per HU).
  vtkPiecewiseFunction* Density() const;
  /// The weights of `cloud`'s points for the channel SetChannel picks.
  vtkAlgorithmOutput* Connect(vtkAlgorithmOutput* cloud, vtkImageData* volume);
  void SetChannel(int m);
  /// Keeps a copy of the projection of the current channel.
  void Keep(vtkImageData* projected);
  /// The radiograph of the kept channels (forgets them), pose k's noise seed.
  vtkImageData* Radiograph(const Settings& settings, int k, std::string& line);
  /// A line for the log: the spectrum's mean energy and HVL, the materials.
  std::string Describe() const;

private:
  bool Enabled = false;
  int Count = 0;
  std::vector<std::string> Names;
  std::string Summary;
  vtkNew<vtkMCXMaterialWeights> Weights;
  vtkNew<vtkMCXPolychromaticRadiograph> Filter;
  vtkNew<vtkPiecewiseFunction> DensityFunction;
  std::vector<vtkSmartPointer<vtkImageData>> Kept;
};

} // namespace mcxapp

#endif
