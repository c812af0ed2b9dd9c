// The polychromatic mode of vtkMCXXRayMapper: the materials' density curve
// the cloud is sampled under, each point's shares of the materials (its
// voxel's mass fractions), by which the mapper's one progressive image
// splits every deposit into a channel per material, and the spectrum's
// model that turns the channels into the effective line integral -ln T per
// pixel. A spectrum or detector change builds another
// model and maps the same channels again; only a materials change (another
// density curve) makes the mapper sample again.
#ifndef vtkMCXPolychromaticChannelsPrivate_h
#define vtkMCXPolychromaticChannelsPrivate_h

#include "mcxChannelSplit.h"
#include "mcxMaterialDecomposition.h"
#include "mcxPolychromaticModel.h"
#include "mcxProgressiveImage.h"
#include "vtkMCXSMPExecutor.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

class vtkDataArray;
class vtkDoubleArray;
class vtkImageData;
class vtkPiecewiseFunction;
class vtkPolyData;

class vtkMCXPolychromaticChannels
{
public:
  using ProgressiveImage = mcx::ProgressiveImage<mcx::SMPExecutor>;

  vtkMCXPolychromaticChannels();
  ~vtkMCXPolychromaticChannels();
  vtkMCXPolychromaticChannels(const vtkMCXPolychromaticChannels&) = delete;
  vtkMCXPolychromaticChannels& operator=(const vtkMCXPolychromaticChannels&) = delete;

  /// Parses what changed since the last call; "" when the three make a
  /// model, else the one-line reason (reported by the caller once per text).
  std::string Configure(
    const std::string& spectrum, const std::string& detector, const std::string& materials);

  /// Counts the models built: a change re-maps the channels.
  std::uint64_t ModelVersion() const { return this->Version; }
  const mcx::PolychromaticModel& Model() const { return *this->Built; }
  /// The materials' number: the channels.
  int Size() const { return static_cast<int>(this->Set.Size()); }

  /// The sampler's transfer function: the materials' density (g/cm^3 per
  /// value); refilled (a new time) only when the materials change.
  vtkPiecewiseFunction* Density() { return this->DensityFunction; }

  /// Each point's shares of the materials (mcxChannelSplit.h: its mass
  /// fractions, one row per distinct set of them), computed again when the
  /// cloud, its time or the materials changed: `values` holds one value (HU)
  /// per voxel of `grid`. "" or why the cloud has no materials.
  std::string UpdateShares(vtkPolyData* cloud, vtkImageData* grid, vtkDataArray* values);

  /// The points' shares for ProgressiveImage::Advance (after UpdateShares).
  const mcx::PointShares* Shares() const { return &this->PointShares; }

  /// The values of a density index's voxels, rebuilt when the index changed.
  vtkDataArray* IndexValues(vtkImageData* index);

  /// The effective line integral -ln T of `image`'s channels (each point
  /// carrying `sampleWeight`), NumberOfPixels() values; with `error`, the
  /// relative RMS error propagated from the channels' estimates as
  /// vtkMCXPolychromaticRadiograph states it.
  void EffectiveValues(const ProgressiveImage& image, double sampleWeight, std::vector<double>& out,
    double* error = nullptr) const;

  /// Keeps `image`'s channel line integrals now (the automatic window's
  /// source) and maps the kept ones with the current model.
  void KeepWindowSource(const ProgressiveImage& image, double sampleWeight);
  void WindowSourceValues(std::vector<double>& out) const;

private:
  // -ln T of per-channel line integrals in world units (mm: 0.1 of g/cm^3
  // x mm is g/cm^2).
  void Map(const std::vector<std::vector<double>>& channels, std::vector<double>& out,
    double* error, const double* channelErrors) const;

  std::string SpectrumText, DetectorText, MaterialsText;
  std::string Problem; // why the texts make no model
  bool Parsed = false;
  std::unique_ptr<mcx::PolychromaticModel> Built;
  std::uint64_t Version = 0;
  mcx::MaterialSet Set;
  vtkNew<vtkPiecewiseFunction> DensityFunction;

  mcx::ChannelShareTable ShareRows;      // one row per distinct set of fractions
  std::vector<std::uint32_t> ShareIndex; // per point, its row
  mcx::PointShares PointShares;
  vtkPolyData* WeightedCloud = nullptr; // compared only, never dereferenced
  vtkMTimeType WeightedTime = 0;
  std::string WeightedMaterials;
  vtkImageData* Index = nullptr; // compared only, never dereferenced
  vtkMTimeType IndexTime = 0;
  vtkSmartPointer<vtkDoubleArray> IndexVoxels;
  std::vector<std::vector<double>> WindowSource;
};

#endif
