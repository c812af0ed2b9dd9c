// The samples a deposit on SIMD lanes gathers (ThreadImage::PointBatch,
// FootprintBatch).
#ifndef mcxGatheredSamples_h
#define mcxGatheredSamples_h

#include "mcxChannelSplit.h"
#include "mcxPixelBinner.h"

#include <cstddef>
#include <cstdint>

namespace mcx
{

/// Samples gathered for a deposit on SIMD lanes (ThreadImage::PointBatch,
/// FootprintBatch): their numbers, shares, centres and weights, the
/// centres readable up to Capacity (PixelBinner::LocatePoints).
struct GatheredSamples
{
  static constexpr std::size_t Capacity = 64;
  static_assert(Capacity % PixelBinner::LanePadding == 0, "LocatePoints reads whole vectors");

  /// Adds a sample; true when the gathering is full.
  bool Push(std::uint64_t k, const double p[3], double weight, const ChannelShares* shares)
  {
    this->K[this->Count] = k;
    this->Shares[this->Count] = shares;
    this->X[this->Count] = p[0];
    this->Y[this->Count] = p[1];
    this->Z[this->Count] = p[2];
    this->Weights[this->Count] = weight;
    return ++this->Count == Capacity;
  }

  std::size_t Count = 0;
  std::uint64_t K[Capacity];
  const ChannelShares* Shares[Capacity];
  double X[Capacity] = {};
  double Y[Capacity] = {};
  double Z[Capacity] = {};
  double Weights[Capacity];
};

} // namespace mcx

#endif
