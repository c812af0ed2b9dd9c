// The polychromatic mode of vtkMCXXRayMapper: the materials' density curve
// the cloud is sampled under, one progressive image per material (the
// cloud's points weighted by that material's fraction at their voxel), and
// the spectrum's model that turns the channels into the effective line
// integral -ln T per pixel. A spectrum or detector change builds another
// model and maps the same channels again; only a materials change (another
// density curve) makes the mapper sample again.
#ifndef vtkMCXPolychromaticChannelsPrivate_h
#define vtkMCXPolychromaticChannelsPrivate_h

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
class vtkPoints;
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
  int Size() const { return static_cast<int>(this->Channels.size()); }

  /// The sampler's transfer function: the materials' density (g/cm^3 per
  /// value); refilled (a new time) only when the materials change.
  vtkPiecewiseFunction* Density() { return this->DensityFunction; }

  /// Each point's material fractions, computed again when the cloud, its
  /// time or the materials changed: `values` holds one value (HU) per voxel
  /// of `grid`. "" or why the cloud has no materials.
  std::string UpdateWeights(vtkPolyData* cloud, vtkImageData* grid, vtkDataArray* values);

  /// The values of a density index's voxels, rebuilt when the index changed.
  vtkDataArray* IndexValues(vtkImageData* index);

  /// Starts every channel over as the total image was (same arguments).
  void Reset(const mcx::ProjectionGeometry& geometry, const double origin[3],
    const double matrix[9], const std::vector<double>& depthLimits,
    const mcx::DepositSettings& settings, double determinant);

  /// Swaps the channels' images, and the prop's |det| they were made
  /// with, with `shelved` and `determinant` (the mapper's image of another
  /// view, set aside with its total's).
  void SwapImages(std::vector<std::unique_ptr<ProgressiveImage>>& shelved, double& determinant)
  {
    this->Channels.swap(shelved);
    std::swap(this->Determinant, determinant);
  }

  /// Adds points [Count(), target) to every channel.
  void Advance(vtkPoints* points, std::uint64_t target);

  std::uint64_t Count() const { return this->Channels.empty() ? 0 : this->Channels[0]->Count(); }

  /// Channel m's line integral (g/cm^3 x world length) per pixel.
  void ChannelValues(int m, double* values) const;

  /// Channel m's relative error estimate (ProgressiveImage's).
  double ChannelError(int m) const { return this->Channels[m]->EstimateRelativeError(); }

  /// The effective line integral -ln T of the channels, NumberOfPixels()
  /// values; with `error`, the relative RMS error propagated from the
  /// channels' estimates as vtkMCXPolychromaticRadiograph states it.
  void EffectiveValues(std::vector<double>& out, double* error = nullptr) const;

  /// Keeps the channels' line integrals now (the automatic window's source)
  /// and maps the kept ones with the current model.
  void KeepWindowSource();
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

  std::vector<std::unique_ptr<ProgressiveImage>> Channels;
  std::vector<std::vector<double>> Weights; // per channel, per point
  std::vector<double> Integrals;            // per channel: the cloud's x (weight sum) / M
  double Determinant = 1.0;                 // |det| of the prop's matrix
  vtkPolyData* WeightedCloud = nullptr;     // compared only, never dereferenced
  vtkMTimeType WeightedTime = 0;
  std::string WeightedMaterials;
  vtkImageData* Index = nullptr; // compared only, never dereferenced
  vtkMTimeType IndexTime = 0;
  vtkSmartPointer<vtkDoubleArray> IndexVoxels;
  std::vector<std::vector<double>> WindowSource;
};

#endif
