#include "vtkMCXPolychromaticChannelsPrivate.h"

#include "mcxFixedPoint.h"
#include "mcxPointWeights.h"
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

#include <cmath>
#include <numeric>
#include <stdexcept>

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
      this->Channels.clear();
      this->Weights.clear();
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

std::string vtkMCXPolychromaticChannels::UpdateWeights(
  vtkPolyData* cloud, vtkImageData* grid, vtkDataArray* values)
{
  if (cloud == this->WeightedCloud && cloud->GetMTime() == this->WeightedTime &&
    this->MaterialsText == this->WeightedMaterials)
  {
    return "";
  }
  this->WeightedCloud = nullptr;
  const std::size_t k = this->Set.Size();
  const vtkIdType count = cloud->GetNumberOfPoints();
  this->Weights.assign(k, std::vector<double>(static_cast<std::size_t>(count)));
  std::vector<int> channels(k);
  std::iota(channels.begin(), channels.end(), 0);
  std::vector<double*> weights(k);
  for (std::size_t m = 0; m < k; ++m)
  {
    weights[m] = this->Weights[m].data();
  }
  const vtkIdType outside =
    mcx::FillMaterialFractions(this->Set, cloud, grid, values, channels, weights);
  if (outside >= 0)
  {
    return "point " + std::to_string(outside) +
      " is not at a voxel centre: the polychromatic mode needs the footprint deposit";
  }
  // Each channel's integral as vtkMCXMaterialWeights scales it: the cloud's
  // times the channel's weight sum over M.
  vtkDataArray* integral = cloud->GetFieldData()->GetArray(vtkMCXTypes::IntegralName());
  const double total = integral ? integral->GetComponent(0, 0) : 0.0;
  this->Integrals.assign(k, 0.0);
  for (std::size_t m = 0; m < k && count > 0; ++m)
  {
    const mcx::FixedSum sum =
      mcx::PointWeightSum(mcx::SMPExecutor(), weights[m], 0, static_cast<std::uint64_t>(count));
    this->Integrals[m] = total * (mcx::ToDouble(sum) / mcx::FixedOne) / static_cast<double>(count);
  }
  this->WeightedCloud = cloud;
  this->WeightedTime = cloud->GetMTime();
  this->WeightedMaterials = this->MaterialsText;
  return "";
}

void vtkMCXPolychromaticChannels::Reset(const mcx::ProjectionGeometry& geometry,
  const double origin[3], const double matrix[9], const std::vector<double>& depthLimits,
  const mcx::DepositSettings& settings, double determinant)
{
  this->Channels.resize(this->Set.Size());
  for (auto& channel : this->Channels)
  {
    if (!channel)
    {
      channel.reset(new ProgressiveImage);
    }
    channel->Reset(geometry, origin, matrix, depthLimits, settings);
  }
  this->Determinant = determinant;
}

void vtkMCXPolychromaticChannels::Advance(vtkPoints* points, std::uint64_t target)
{
  for (std::size_t m = 0; m < this->Channels.size(); ++m)
  {
    const double* weights = this->Weights[m].data();
    if (points->GetDataType() == VTK_FLOAT)
    {
      this->Channels[m]->Advance(
        mcx::SMPExecutor(), static_cast<const float*>(points->GetVoidPointer(0)), target, weights);
    }
    else
    {
      this->Channels[m]->Advance(
        mcx::SMPExecutor(), static_cast<const double*>(points->GetVoidPointer(0)), target, weights);
    }
  }
}

void vtkMCXPolychromaticChannels::ChannelValues(int m, double* values) const
{
  const ProgressiveImage& channel = *this->Channels[m];
  const double carried = channel.CountedWeight();
  channel.ToValues(carried > 0 ? this->Integrals[m] * this->Determinant / carried : 0.0, values);
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

void vtkMCXPolychromaticChannels::EffectiveValues(std::vector<double>& out, double* error) const
{
  std::vector<std::vector<double>> channels(this->Channels.size());
  std::vector<double> channelErrors(this->Channels.size());
  for (std::size_t m = 0; m < this->Channels.size(); ++m)
  {
    channels[m].resize(this->Channels[m]->NumberOfPixels());
    this->ChannelValues(static_cast<int>(m), channels[m].data());
    channelErrors[m] = this->ChannelError(static_cast<int>(m));
  }
  this->Map(channels, out, error, channelErrors.data());
}

void vtkMCXPolychromaticChannels::KeepWindowSource()
{
  this->WindowSource.resize(this->Channels.size());
  for (std::size_t m = 0; m < this->Channels.size(); ++m)
  {
    this->WindowSource[m].resize(this->Channels[m]->NumberOfPixels());
    this->ChannelValues(static_cast<int>(m), this->WindowSource[m].data());
  }
}

void vtkMCXPolychromaticChannels::WindowSourceValues(std::vector<double>& out) const
{
  this->Map(this->WindowSource, out, nullptr, nullptr);
}
