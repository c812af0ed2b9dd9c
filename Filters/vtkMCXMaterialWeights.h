/**
 * @class   vtkMCXMaterialWeights
 * @brief   One material's share of each sample of a cloud drawn under the
 *          total density: the cloud of one line-integral channel.
 *
 * Input 0: a footprint cloud of vtkMCXPointSampler (voxel centres, the
 * default deposit) sampled under the materials' total transfer function,
 * the density curve (FillDensityFunction gives it).
 * Input 1: the volume the index was built from (its first scalar component
 * is the CT number in HU). Output: the same points with PointWeight = the
 * Channel-th material's mass fraction at each point's voxel (multiples of
 * 2^-32 that sum to exactly 1 over the materials), and the Integral field
 * scaled by (sum of those weights) / M, so that vtkMCXProjector turns the
 * cloud into that material's line integral (g/cm^3 x mm) with the very
 * samples of the total. Channel -1 gives every point the weight 1 (the total's
 * image through the same weighted deposit): the channels' fixed-point pixel
 * sums add up to its sums exactly.
 *
 * Materials: "default", "default,iodine=<HU>,titanium=<HU>" or a materials
 * file (Documentation/polychromatic.md). A Channel change re-executes this
 * filter alone (O(M)), never the sampler.
 */
#ifndef vtkMCXMaterialWeights_h
#define vtkMCXMaterialWeights_h

#include "MonteCarloXRayFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // for the density function

#include <memory> // for the material set
#include <string> // for the parsed text

class vtkPiecewiseFunction;
namespace mcx
{
struct MaterialSet;
}

class MONTECARLOXRAYFILTERS_EXPORT vtkMCXMaterialWeights : public vtkPolyDataAlgorithm
{
public:
  static vtkMCXMaterialWeights* New();
  vtkTypeMacro(vtkMCXMaterialWeights, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The material decomposition (default "default"). */
  vtkSetStringMacro(Materials);
  vtkGetStringMacro(Materials);
  ///@}

  ///@{
  /** The material whose weights the output carries; -1 (default): all 1. */
  vtkSetClampMacro(Channel, int, -1, 63);
  vtkGetMacro(Channel, int);
  ///@}

  /** The volume of input 1. */
  void SetVolumeConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  ///@{
  /**
   * The materials of Materials: their number (0 with an error when Materials
   * is not usable), the xraylib name of material m (null outside 0..number -
   * 1), the density curve (HU -> g/cm^3) as the sampler's transfer
   * function, and material m's mass fraction curve (HU -> [0, 1]), the
   * channel fraction of vtkMCXProjector's split deposit (both false, with an
   * error when Materials is not usable).
   */
  int GetNumberOfMaterials();
  const char* GetMaterialName(int m);
  bool FillDensityFunction(vtkPiecewiseFunction* density);
  bool FillFractionFunction(int m, vtkPiecewiseFunction* fraction);
  ///@}

protected:
  vtkMCXMaterialWeights();
  ~vtkMCXMaterialWeights() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMCXMaterialWeights(const vtkMCXMaterialWeights&) = delete;
  void operator=(const vtkMCXMaterialWeights&) = delete;

  // The set of Materials, parsed again only when the text changes.
  const mcx::MaterialSet* Set();

  char* Materials = nullptr;
  int Channel = -1;
  std::unique_ptr<mcx::MaterialSet> Parsed;
  std::string ParsedText;
};

#endif
