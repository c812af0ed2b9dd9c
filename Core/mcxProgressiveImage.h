// The mapper's exact accumulation buffer, free of any graphics API so that the
// tests can check it directly.
//
// It holds the fixed-point image of the first Count() points of a cloud in
// Halton order and grows it by whole prefixes without ever starting over, so
// a refined image only ever adds samples to the one on screen. When it grows
// to 2^m - 1 points it also keeps the image of the first 2^(m-1) - 1, which
// the error estimate compares with the rest (the same halves as the off-line
// projector's). Sums are integers, so the image is the same for any number of
// threads and equals vtkMCXProjector's for the same camera and points: both
// deposit through SampleAccumulator. With a control image (SetControl) it
// also counts each point once and shows the controlled estimate of
// mcxControlImage.h. With channels (SetChannels) each point's deposit is
// also split into them by its shares (mcxChannelSplit.h), in the same pass.
#ifndef mcxProgressiveImage_h
#define mcxProgressiveImage_h

#include "mcxControlImage.h"
#include "mcxErrorEstimate.h"
#include "mcxFixedPoint.h"
#include "mcxProjectionGeometry.h"
#include "mcxSampleAccumulator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace mcx
{

template <typename Executor>
class ProgressiveImage
{
public:
  /// Starts over for a view: see SampleAccumulator::Reset.
  void Reset(const ProjectionGeometry& geometry, const double origin[3], const double matrix[9],
    std::vector<double> depthLimits = std::vector<double>(),
    const DepositSettings& settings = DepositSettings())
  {
    this->Geometry = geometry;
    this->Accumulator.Reset(geometry, origin, matrix, std::move(depthLimits), settings);
    const std::size_t pixels = this->Accumulator.NumberOfPixels();
    this->Total.assign(pixels, 0);
    this->FirstHalf.assign(pixels, 0);
    this->Counted = 0;
    this->FirstHalfCount = 0;
    this->Weights = 0;
    this->FirstHalfWeights = 0;
    this->Weighted = false;
    this->Control.clear();
    this->ControlVariance = 0.0;
    this->OnceTotal.clear();
    this->OnceFirstHalf.clear();
    this->ChannelSums.clear();
  }

  /// Splits the points to come into `channels` images as well (each
  /// Advance then needs the points' shares). Call after Reset(), before the
  /// first Advance().
  void SetChannels(int channels)
  {
    if (this->Counted > 0)
    {
      return;
    }
    this->Accumulator.SetChannels(channels);
    this->ChannelSums.assign(static_cast<std::size_t>(this->Accumulator.GetChannels()),
      std::vector<FixedSum>(2 * this->Total.size(), 0));
  }

  int Channels() const { return static_cast<int>(this->ChannelSums.size()); }

  /// Shows the controlled estimate (mcxControlImage.h) of the points to
  /// come: `control` is the control image H of this view, NumberOfPixels()
  /// line integrals, `integral` the cloud's and `variance` H's own, summed
  /// over the pixels. Call after Reset(), before the first Advance().
  void SetControl(std::vector<double> control, double integral, double variance = 0.0)
  {
    if (control.size() != this->Total.size() || this->Counted > 0)
    {
      return;
    }
    this->Control = std::move(control);
    this->ControlIntegral = integral;
    this->ControlVariance = variance;
    this->OnceTotal.assign(this->Total.size(), 0);
    this->OnceFirstHalf.assign(this->Total.size(), 0);
    this->Accumulator.SetControlled(true);
  }

  bool IsControlled() const { return !this->Control.empty(); }

  /// Adds points [Count(), target) of `points` (x, y, z each) to the image,
  /// each `weights[i]` times (null: once; see SampleAccumulator::DepositRange),
  /// split into the channels by `shares` when there are channels.
  template <typename Real, typename Weight = float>
  void Advance(const Executor& executor, const Real* points, std::uint64_t target,
    const Weight* weights = nullptr, const PointShares* shares = nullptr)
  {
    if (target <= this->Counted)
    {
      return;
    }
    // The image so far lies inside the new first half: it is where that
    // half's sums start.
    const std::uint64_t half = FirstHalfSize(target);
    const bool splitsHere = half >= this->Counted && half > this->FirstHalfCount;
    if (splitsHere)
    {
      this->FirstHalf = this->Total;
      this->OnceFirstHalf = this->OnceTotal;
      for (std::vector<FixedSum>& channel : this->ChannelSums)
      {
        std::copy(channel.begin(), channel.begin() + this->Total.size(),
          channel.begin() + this->Total.size());
      }
      this->FirstHalfCount = half;
    }
    this->Accumulator.SetSplit(splitsHere ? half : 0);
    this->Accumulator.DepositPoints(
      executor, points, this->Counted, target, weights, this->Channels() > 0 ? shares : nullptr);
    if (weights)
    {
      // Fixed-point sums of consecutive ranges add up exactly: the first
      // half's part is summed once.
      const std::uint64_t middle = splitsHere ? half : this->Counted;
      this->Weights += PointWeightSum(executor, weights, this->Counted, middle);
      if (splitsHere)
      {
        this->FirstHalfWeights = this->Weights;
      }
      this->Weights += PointWeightSum(executor, weights, middle, target);
      this->Weighted = true;
    }
    std::vector<FixedSum*> channels;
    for (std::vector<FixedSum>& channel : this->ChannelSums)
    {
      channels.push_back(channel.data());
    }
    this->Accumulator.Collect(this->Total.data(), this->FirstHalf.data(),
      this->IsControlled() ? this->OnceTotal.data() : nullptr,
      this->IsControlled() ? this->OnceFirstHalf.data() : nullptr,
      channels.empty() ? nullptr : channels.data());
    this->Counted = target;
  }

  std::uint64_t Count() const { return this->Counted; }

  /// The points the image holds, counted with their weights: Count() for an
  /// unweighted cloud, else the sum of the weights so far (the image of a
  /// prefix then carries the cloud's integral whatever its mean weight).
  double CountedWeight() const
  {
    return this->Weighted ? ToDouble(this->Weights) / FixedOne : static_cast<double>(this->Counted);
  }
  std::size_t NumberOfPixels() const { return this->Total.size(); }
  const ProjectionGeometry& GetGeometry() const { return this->Geometry; }

  /// The fixed-point sums of the image of all Count() points.
  const std::vector<FixedSum>& Sums() const { return this->Total; }

  /// Relative RMS error of the current image, from its two halves; NaN when
  /// the halves are not known (fewer than 3 points).
  double EstimateRelativeError() const
  {
    if (this->FirstHalfCount != FirstHalfSize(this->Counted))
    {
      return std::nan("");
    }
    if (this->IsControlled())
    {
      const double firstWeight = this->Weighted ? ToDouble(this->FirstHalfWeights) / FixedOne
                                                : static_cast<double>(this->FirstHalfCount);
      return EstimateControlledRelativeError(
        this->Controlled(), this->FirstHalf.data(), this->OnceFirstHalf.data(), firstWeight);
    }
    return (this->Accumulator.ErrorFallsAsInverseM() ? FootprintErrorCalibration : 1.0) *
      mcx::EstimateRelativeError(
        this->Total.data(), this->FirstHalf.data(), this->Total.size(), this->Counted);
  }

  /// Pixel values in physical units: the line integral, each point carrying
  /// `sampleWeight` (the cloud's integral over Count()).
  template <typename Value>
  void ToValues(double sampleWeight, Value* values) const
  {
    if (this->IsControlled())
    {
      // The controlled estimate carries SetControl's integral (the caller's
      // sampleWeight is that integral over CountedWeight(): the same image).
      ControlledSumsToValues(this->Controlled(), values);
      return;
    }
    FixedSumsToValues(this->Total.data(), this->Total.size(), sampleWeight,
      this->Geometry.BeamCrossSection(), values);
  }

  /// Channel c's pixel values, each point carrying `sampleWeight` as in
  /// ToValues (without the control: a channel has none).
  template <typename Value>
  void ChannelToValues(int c, double sampleWeight, Value* values) const
  {
    FixedSumsToValues(this->ChannelSums[static_cast<std::size_t>(c)].data(), this->Total.size(),
      sampleWeight, this->Geometry.BeamCrossSection(), values);
  }

  /// Channel c's relative RMS error from its halves (as the image's without a control).
  double ChannelRelativeError(int c) const
  {
    if (this->FirstHalfCount != FirstHalfSize(this->Counted))
    {
      return std::nan("");
    }
    const std::vector<FixedSum>& sums = this->ChannelSums[static_cast<std::size_t>(c)];
    return (this->Accumulator.ErrorFallsAsInverseM() ? FootprintErrorCalibration : 1.0) *
      mcx::EstimateRelativeError(
        sums.data(), sums.data() + this->Total.size(), this->Total.size(), this->Counted);
  }

private:
  ControlledSums Controlled() const
  {
    ControlledSums sums;
    sums.Weighted = this->Total.data();
    sums.Once = this->OnceTotal.data();
    sums.Control = this->Control.data();
    sums.Pixels = this->Total.size();
    sums.Count = this->Counted;
    sums.CarriedWeight = this->CountedWeight();
    sums.Integral = this->ControlIntegral;
    sums.PixelArea = this->Geometry.BeamCrossSection();
    sums.ControlVariance = this->ControlVariance;
    return sums;
  }

  ProjectionGeometry Geometry;
  SampleAccumulator<Executor> Accumulator;
  std::vector<FixedSum> Total;
  std::vector<FixedSum> FirstHalf;
  std::uint64_t Counted = 0;
  std::uint64_t FirstHalfCount = 0;
  FixedSum Weights = 0; // of the points counted, when weighted
  FixedSum FirstHalfWeights = 0; // of the first half's, when weighted
  bool Weighted = false;
  // The control (SetControl): H, the cloud's integral, H's variance, and
  // the sums of the points counted once.
  std::vector<double> Control;
  double ControlIntegral = 0.0;
  double ControlVariance = 0.0;
  std::vector<FixedSum> OnceTotal;
  std::vector<FixedSum> OnceFirstHalf;
  // Per channel (SetChannels): all points' sums, then the first half's.
  std::vector<std::vector<FixedSum>> ChannelSums;
};

} // namespace mcx

#endif
