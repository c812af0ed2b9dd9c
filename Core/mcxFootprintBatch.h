// The footprint deposit of many samples (ThreadImage::DepositFootprint's
// work in a pipeline): beside ThreadImage::PointBatch, kept apart for the
// file's length.
#ifndef mcxFootprintBatch_h
#define mcxFootprintBatch_h

#include "mcxThreadImage.h"

#include <cstddef>
#include <cstdint>

namespace mcx
{

/// DepositFootprint for a stream of samples (Add, then Flush() at the end
/// of each chunk of work): the footprint deposit of a sample source's sink,
/// of a stored cloud and of the view order's control image. Each footprint
/// is prepared, its cache lines asked for, and added Lookahead footprints
/// later, so that the next preparations overlap the additions' waits (in
/// Halton order successive samples reach the image at random; the control
/// image's voxels come in pixel order, where only the overlap counts); in
/// perspective views the samples are first located Capacity at a time on
/// SIMD lanes (PixelBinner::LocatePoints), a parallel view's three products
/// one at a time. The same sums as DepositFootprint one sample at a time,
/// bit for bit: fixed-point additions commute.
class FootprintBatch
{
public:
  static constexpr std::size_t Capacity = GatheredSamples::Capacity;
  /// Far enough for the asked-for lines to arrive, near enough that they
  /// are still in the first level of cache: a few footprints of a few
  /// lines each (the stored cloud's ring had the same).
  static constexpr std::size_t Lookahead = 8;

  explicit FootprintBatch(const ThreadImage& image)
    : Image(image)
    , Lanes(image.Binner->IsPerspective())
  {
  }

  void Add(
    std::uint64_t k, const double p[3], double weight = 1.0, const ChannelShares* shares = nullptr)
  {
    if (!this->Lanes)
    {
      this->Prepare([&](ThreadImage::PreparedFootprint& footprint)
        { return this->Image.PrepareFootprint(k, p, footprint, weight, shares); });
      return;
    }
    if (this->Samples.Push(k, p, weight, shares))
    {
      this->PrepareGathered();
    }
  }

  /// Deposits every footprint added so far.
  void Flush()
  {
    this->PrepareGathered();
    for (std::size_t i = 0; i < Lookahead; ++i)
    {
      this->AddDue();
      ++this->Prepared;
    }
  }

private:
  // Locates the gathered samples on lanes and prepares them.
  void PrepareGathered()
  {
    const GatheredSamples& s = this->Samples;
    double fx[Capacity], fy[Capacity], f[Capacity], w[Capacity];
    std::uint8_t located[Capacity];
    this->Image.Binner->LocatePoints(s.X, s.Y, s.Z, s.Count, fx, fy, f, located, w);
    for (std::size_t i = 0; i < s.Count; ++i)
    {
      if (located[i])
      {
        const double p[3] = { s.X[i], s.Y[i], s.Z[i] };
        this->Prepare(
          [&](ThreadImage::PreparedFootprint& footprint)
          {
            return this->Image.PrepareLocatedFootprint(
              s.K[i], p, fx[i], fy[i], f[i], w[i], footprint, s.Weights[i], s.Shares[i]);
          });
      }
    }
    this->Samples.Count = 0;
  }

  // Prepares a footprint in the ring's next slot (prepare(footprint):
  // whether there is one to add), after adding the one there, prepared
  // Lookahead preparations before.
  template <typename PrepareInto>
  void Prepare(const PrepareInto& prepare)
  {
    this->AddDue();
    const std::size_t slot = this->Prepared++ % Lookahead;
    this->Pending[slot] = prepare(this->Ring[slot]);
    if (this->Pending[slot])
    {
      this->Image.Prefetch(this->Ring[slot]);
    }
  }

  // Adds the footprint in the ring's next slot, if one is there.
  void AddDue()
  {
    const std::size_t slot = this->Prepared % Lookahead;
    if (this->Pending[slot])
    {
      this->Image.AddFootprint(this->Ring[slot]);
      this->Pending[slot] = false;
    }
  }

  const ThreadImage& Image;
  const bool Lanes; // perspective: located on SIMD lanes
  ThreadImage::PreparedFootprint Ring[Lookahead];
  bool Pending[Lookahead] = {};
  std::size_t Prepared = 0; // footprints prepared so far
  GatheredSamples Samples;  // for the lanes
};

} // namespace mcx

#endif
