// The one place where samples become image sums, for the off-line projector
// (samples as they are generated, or a stored cloud) and the mapper alike, so
// that their images agree by construction.
//
// A sample k at point p is binned by a PixelBinner (and dropped when it lies
// behind the pixel's depth limit, where opaque geometry hides it); its
// fixed-point increment goes into the calling thread's image. With the
// footprint deposit (mcxFootprint.h) p is the voxel's centre and the sample
// adds its kernel's footprint, whose increments add up to exactly the point
// deposit's one count in parallel views (to rounding in perspective views). A
// thread keeps two images (ThreadSums): the samples with k below the split
// (the first Halton half, which the error estimate compares with the rest)
// and the rest; two more when controlled (each sample counted once, for a
// control image: mcxControlImage.h). Collect() adds the threads' images up
// into all samples' sums and the first half's; integer sums make the result
// independent of the order and the number of threads.
//
// This header is the one the others include. Its parts live in headers of
// their own: the settings (mcxDepositSettings.h), the footprint tables of a
// view (mcxFootprintLadder.h), a thread's sums (mcxThreadSums.h) and its
// deposits (mcxThreadImage.h, its footprints in a pipeline:
// mcxFootprintBatch.h, the samples gathered for SIMD lanes:
// mcxGatheredSamples.h), and the weights of weighted clouds
// (mcxPointWeights.h); here is the accumulator that ties them to a view and
// an executor.
#ifndef mcxSampleAccumulator_h
#define mcxSampleAccumulator_h

#include "mcxChannelSplit.h"
#include "mcxDepositSettings.h"
#include "mcxFixedPoint.h"
#include "mcxFootprintBatch.h"
#include "mcxFootprintLadder.h"
#include "mcxPixelBinner.h"
#include "mcxPointWeights.h"
#include "mcxProjectionGeometry.h"
#include "mcxRandom.h"
#include "mcxThreadImage.h"
#include "mcxThreadSums.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace mcx
{

template <typename Executor>
class SampleAccumulator
{
public:
  /// Starts over for a view: the geometry, the map from sample coordinates
  /// to world (origin, row-major 3x3), and, when opaque geometry hides part
  /// of the scene, each pixel's depth (along the view direction, from the
  /// eye) beyond which samples are hidden; empty when nothing is hidden.
  void Reset(const ProjectionGeometry& geometry, const double origin[3], const double matrix[9],
    std::vector<double> depthLimits = std::vector<double>(),
    const DepositSettings& settings = DepositSettings())
  {
    this->Binner.reset(new PixelBinner(geometry, origin, matrix));
    this->Settings = settings;
    this->FootprintKey = SeedKey(settings.Seed ^ 0x6A09E667F3BCC909ull);
    if (settings.Mode == Deposit::Footprint)
    {
      if (!this->Ladder)
      {
        this->Ladder.reset(new FootprintLadder);
      }
      this->Ladder->Build(Executor(), *this->Binner, settings);
    }
    else
    {
      this->Ladder.reset();
    }
    this->Pixels = static_cast<std::size_t>(geometry.Size[0]) * geometry.Size[1];
    this->DepthLimits = std::move(depthLimits);
    this->Split = 0;
    this->Controlled = false;
    this->Channels = 0;
    // Collect() leaves the images zeroed: only another size is reallocated.
    for (ThreadSums& sums : this->Images)
    {
      sums.Allocate(this->Pixels);
    }
  }

  /// Whether every sample is also counted once, whatever its weight, in the
  /// control images (Collect's controlAll and controlFirstHalf): the cloud's
  /// own estimate of a control image known exactly (mcxControlImage.h).
  /// Reset() turns it off.
  void SetControlled(bool controlled) { this->Controlled = controlled; }
  bool IsControlled() const { return this->Controlled; }

  /// True when the image's error falls about as M^-1 (footprints of whole
  /// kernels with a stratified voxel choice), so that the halves' error
  /// estimate needs mcx::FootprintErrorCalibration; false for M^-1/2.
  bool ErrorFallsAsInverseM() const
  {
    return this->Ladder && this->Settings.Stratified && !this->Ladder->IsEmpty() &&
      !this->Ladder->AnyRandomSplit();
  }

  /// Deposits given fractions (ThreadImage::Deposit) are split into
  /// `channels` images as well (mcxChannelSplit.h; 0 to MaximumChannels),
  /// which Collect's `channels` receive. Reset() sets none.
  void SetChannels(int channels)
  {
    this->Channels = std::min(std::max(channels, 0), MaximumChannels);
  }
  int GetChannels() const { return this->Channels; }

  /// Samples with k < split count in the first half's sums as well.
  void SetSplit(std::uint64_t split) { this->Split = split; }

  std::size_t NumberOfPixels() const { return this->Pixels; }

  /// One thread's image (mcxThreadImage.h); get it once per chunk of work,
  /// inside the executor's For.
  using ThreadImage = mcx::ThreadImage;

  ThreadImage Local()
  {
    ThreadSums& sums = this->Images.Local();
    sums.Allocate(this->Pixels, this->Controlled ? 4 : 2, this->Channels);
    ThreadImage local;
    local.Sums = &sums;
    local.Channels = this->Channels;
    local.Controlled = this->Controlled;
    local.Binner = this->Binner.get();
    local.Ladder = this->Ladder.get();
    local.FootprintKey = this->FootprintKey;
    local.Reconstruction = this->Settings.Reconstruction;
    local.VoxelMatrix = this->Settings.VoxelMatrix;
    local.DepthLimits = this->DepthLimits.empty() ? nullptr : this->DepthLimits.data();
    local.Split = this->Split;
    return local;
  }

  /// Deposits points [begin, end) of a stored cloud (x, y, z each), point i
  /// being sample i, in the calling thread; point i counts weights[i] times
  /// (finite, >= 0: see PointWeightProblem; null: once each; weight 0 is
  /// skipped, unless controlled), split into the channels by `shares` when
  /// given (SetChannels). Footprints go through a FootprintBatch, their
  /// cache lines asked for between their preparation and their addition:
  /// in Halton order successive samples reach the image at random. The
  /// sums are integers: the order of the additions leaves them unchanged.
  template <typename Real, typename Weight = float>
  void DepositRange(const Real* points, std::uint64_t begin, std::uint64_t end,
    const Weight* weights = nullptr, const PointShares* shares = nullptr)
  {
    const ThreadImage image = this->Local();
    auto point = [points](std::uint64_t i, double p[3])
    {
      for (int r = 0; r < 3; ++r)
      {
        p[r] = static_cast<double>(points[3 * i + r]);
      }
    };
    auto weightOf = [weights](std::uint64_t i)
    { return weights ? static_cast<double>(weights[i]) : 1.0; };
    auto sharesOf = [shares](std::uint64_t i) { return shares ? shares->Of(i) : nullptr; };
    // A perspective view's points go on SIMD lanes (their division and
    // square root); a parallel view's three products are cheaper one
    // point at a time. Footprints go in batches in either view.
    const bool lanes = this->Binner->IsPerspective();
    typename ThreadImage::PointBatch pointBatch(image);
    FootprintBatch footprintBatch(image);
    for (std::uint64_t i = begin; i < end; ++i)
    {
      const double weight = weightOf(i);
      if (weight == 0.0 && !image.Controlled) // the control counts every sample
      {
        continue;
      }
      double p[3];
      point(i, p);
      if (this->Ladder)
      {
        footprintBatch.Add(i, p, weight, sharesOf(i));
      }
      else if (lanes)
      {
        pointBatch.AddWeighted(i, p, weight, sharesOf(i));
      }
      else
      {
        image.DepositPoint(i, p, weight, sharesOf(i));
      }
    }
    pointBatch.Flush();
    footprintBatch.Flush();
  }

  /// The same, in parallel on `executor`.
  template <typename Real, typename Weight = float>
  void DepositPoints(const Executor& executor, const Real* points, std::uint64_t begin,
    std::uint64_t end, const Weight* weights = nullptr, const PointShares* shares = nullptr)
  {
    executor.For(static_cast<std::int64_t>(begin), static_cast<std::int64_t>(end),
      std::int64_t(1) << 15,
      [&](std::int64_t b, std::int64_t e)
      {
        this->DepositRange(
          points, static_cast<std::uint64_t>(b), static_cast<std::uint64_t>(e), weights, shares);
      });
  }

  /// Adds the threads' sums to all (every sample) and firstHalf (k < split),
  /// NumberOfPixels() each, and the control images to controlAll and
  /// controlFirstHalf when controlled, channel c's to channels[c] (all,
  /// then the first half: 2 x NumberOfPixels()) when split, and zeroes them
  /// for the next deposits; call it after every round of deposits.
  void Collect(FixedSum* all, FixedSum* firstHalf, FixedSum* controlAll = nullptr,
    FixedSum* controlFirstHalf = nullptr, FixedSum* const* channels = nullptr)
  {
    for (ThreadSums& sums : this->Images)
    {
      sums.CollectInto(this->Pixels, all, firstHalf, controlAll, controlFirstHalf, channels,
        channels ? this->Channels : 0);
    }
  }

private:
  std::unique_ptr<PixelBinner> Binner;
  std::unique_ptr<FootprintLadder> Ladder;
  DepositSettings Settings;
  std::uint64_t FootprintKey = 0;
  std::size_t Pixels = 0;
  std::vector<double> DepthLimits;
  std::uint64_t Split = 0;
  bool Controlled = false;
  int Channels = 0;
  typename Executor::template ThreadLocal<ThreadSums> Images;
};

} // namespace mcx

#endif
