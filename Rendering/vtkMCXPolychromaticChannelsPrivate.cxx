#include "vtkMCXPolychromaticChannelsPrivate.h"

#include "mcxFixedPoint.h"
#include "mcxTubeSpectrum.h"
#include "vtkMCXMaterialFractions.h"
#include "vtkMCXTypes.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

vtkMCXPolychromaticChannels::vtkMCXPolychromaticChannels() = default;

vtkMCXPolychromaticChannels::~vtkMCXPolychromaticChannels() = default;

std::string vtkMCXPolychromaticChannels::Configure(
  const std::string& spectrum, const std::string& detector, const std::string& materials)
{
  if (this->Parsed && spectrum == this->SpectrumText && detector == this->DetectorText &&
    materials == this->MaterialsText)
  {
    return this->Built ? "" : this->Problem;
  }
  const bool newMaterials = !this->Parsed || materials != this->MaterialsText;
  this->Parsed = true;
  this->SpectrumText = spectrum;
  this->DetectorText = detector;
  this->MaterialsText = materials;
  this->Built.reset();
  try
  {
    if (newMaterials)
    {
      this->Set = mcx::MaterialsFromText(materials);
      this->DensityFunction->RemoveAllPoints();
      for (std::size_t i = 0; i < this->Set.Density.HU.size(); ++i)
      {
        this->DensityFunction->AddPoint(this->Set.Density.HU[i], this->Set.Density.Value[i]);
      }
      this->WindowSource.clear();
      this->WeightedCloud = nullptr;
    }
    this->Built.reset(new mcx::PolychromaticModel(
      mcx::SpectrumFromText(spectrum), mcx::ParseDetector(detector), this->Set.Names()));
  }
  catch (const std::exception& error)
  {
    if (newMaterials)
    {
      this->Set = mcx::MaterialSet();
      this->MaterialsText.clear();
      this->Parsed = false; // the same materials parse again (and fail) next time
    }
    this->Problem = error.what();
    return this->Problem;
  }
  ++this->Version;
  return "";
}

vtkDataArray* vtkMCXPolychromaticChannels::IndexValues(vtkImageData* index)
{
  if (index != this->Index || index->GetMTime() != this->IndexTime || !this->IndexVoxels)
  {
    this->IndexVoxels = mcx::IndexVoxelValues(index);
    this->Index = index;
    this->IndexTime = index->GetMTime();
  }
  return this->IndexVoxels;
}

std::string vtkMCXPolychromaticChannels::UpdateShares(
  vtkPolyData* cloud, vtkImageData* grid, vtkDataArray* values)
{
  if (cloud == this->WeightedCloud && cloud->GetMTime() == this->WeightedTime &&
    this->MaterialsText == this->WeightedMaterials)
  {
    return "";
  }
  this->WeightedCloud = nullptr;
  const std::size_t k = this->Set.Size();
  const std::size_t count = static_cast<std::size_t>(cloud->GetNumberOfPoints());
  std::vector<std::vector<double>> fractions(k, std::vector<double>(count));
  std::vector<int> channels(k);
  std::iota(channels.begin(), channels.end(), 0);
  std::vector<double*> pointers(k);
  for (std::size_t m = 0; m < k; ++m)
  {
    pointers[m] = fractions[m].data();
  }
  const vtkIdType outside =
    mcx::FillMaterialFractions(this->Set, cloud, grid, values, channels, pointers);
  if (outside >= 0)
  {
    return "point " + std::to_string(outside) +
      " is not at a voxel centre: the polychromatic mode needs the footprint deposit";
  }
  // One row per distinct set of fractions (multiples of 2^-32 summing to
  // 1, MaterialSet::FixedFractionsAt: exact in fixed point), found by a
  // hash of the set and compared in full.
  std::vector<std::uint64_t> rows, tuple(k);
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> byHash;
  this->ShareIndex.resize(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    std::uint64_t hash = 14695981039346656037ull; // FNV-1a
    for (std::size_t m = 0; m < k; ++m)
    {
      tuple[m] = static_cast<std::uint64_t>(fractions[m][i] * mcx::FixedOne);
      hash = (hash ^ tuple[m]) * 1099511628211ull;
    }
    std::vector<std::uint32_t>& candidates = byHash[hash];
    std::uint32_t row = static_cast<std::uint32_t>(rows.size() / std::max<std::size_t>(1, k));
    for (std::uint32_t candidate : candidates)
    {
      if (std::equal(tuple.begin(), tuple.end(), rows.begin() + candidate * k))
      {
        row = candidate;
        break;
      }
    }
    if (row * k == rows.size())
    {
      rows.insert(rows.end(), tuple.begin(), tuple.end());
      candidates.push_back(row);
    }
    this->ShareIndex[i] = row;
  }
  this->ShareRows.Build(rows, static_cast<int>(k));
  this->PointShares.Index = this->ShareIndex.data();
  this->PointShares.Table = &this->ShareRows;
  this->WeightedCloud = cloud;
  this->WeightedTime = cloud->GetMTime();
  this->WeightedMaterials = this->MaterialsText;
  return "";
}

void vtkMCXPolychromaticChannels::Map(const std::vector<std::vector<double>>& channels,
  std::vector<double>& out, double* error, const double* channelErrors) const
{
  const std::size_t pixels = channels.empty() ? 0 : channels[0].size();
  std::vector<const double*> pointers(channels.size());
  for (std::size_t m = 0; m < channels.size(); ++m)
  {
    pointers[m] = channels[m].data();
  }
  out.resize(pixels);
  std::vector<double> errors(error ? pixels : 0);
  this->Built->EffectiveImage(mcx::SMPExecutor(), static_cast<std::int64_t>(pixels),
    pointers.data(), 0.1, out.data(), error ? channelErrors : nullptr,
    error ? errors.data() : nullptr);
  if (!error)
  {
    return;
  }
  // As vtkMCXPolychromaticRadiograph: over the pixels whose error was
  // propagated, sqrt(sum of squared errors / sum of squared values).
  double squaredErrors = 0.0, squaredValues = 0.0;
  for (std::size_t p = 0; p < pixels; p += mcx::PolychromaticModel::ErrorStride)
  {
    if (std::isfinite(out[p]))
    {
      squaredErrors += errors[p] * errors[p];
      squaredValues += out[p] * out[p];
    }
  }
  *error = squaredValues > 0.0 ? std::sqrt(squaredErrors / squaredValues) : 0.0;
}

namespace
{
// Each channel's line integrals of `image`.
std::vector<std::vector<double>> ChannelLines(
  const vtkMCXPolychromaticChannels::ProgressiveImage& image, double sampleWeight)
{
  std::vector<std::vector<double>> channels(static_cast<std::size_t>(image.Channels()));
  for (int m = 0; m < image.Channels(); ++m)
  {
    channels[m].resize(image.NumberOfPixels());
    image.ChannelToValues(m, sampleWeight, channels[m].data());
  }
  return channels;
}
}

void vtkMCXPolychromaticChannels::EffectiveValues(
  const ProgressiveImage& image, double sampleWeight, std::vector<double>& out, double* error) const
{
  std::vector<double> channelErrors(static_cast<std::size_t>(image.Channels()));
  for (int m = 0; m < image.Channels(); ++m)
  {
    channelErrors[m] = image.ChannelRelativeError(m);
  }
  this->Map(ChannelLines(image, sampleWeight), out, error, channelErrors.data());
}

void vtkMCXPolychromaticChannels::KeepWindowSource(
  const ProgressiveImage& image, double sampleWeight)
{
  this->WindowSource = ChannelLines(image, sampleWeight);
}

void vtkMCXPolychromaticChannels::WindowSourceValues(std::vector<double>& out) const
{
  this->Map(this->WindowSource, out, nullptr, nullptr);
}
