// One deposit, several line-integral channels: each fixed-point increment
// of a sample is split by its fractions (the shares of the sample's weight
// that belong to each channel, e.g. the mass fractions of the materials at
// its voxel's CT number), so that one pass of samples drawn under the total
// weight makes the total's image and K channel images at once. The split is
// exact: the channels' increments add up to the total's increment, so their
// integer sums add up to its sums, bit for bit, in every view and deposit.
#ifndef mcxChannelSplit_h
#define mcxChannelSplit_h

#include "mcxFixedPoint.h"
#include "mcxWideInteger.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace mcx
{

/// The most channels a deposit splits into.
constexpr int MaximumChannels = 64;

/// The fractions' fixed point: 2^32 is the whole increment.
constexpr std::uint64_t FractionOne = std::uint64_t(1) << 32;

/// floor(increment * fraction / 2^32) for fraction <= 2^32: below 2^64.
inline std::uint64_t SplitWord(std::uint64_t increment, std::uint64_t fraction)
{
  std::uint64_t high, low;
  Multiply64(increment, fraction, high, low);
  return (high << 32) | (low >> 32);
}

/// The same for a 128-bit increment (below 2^96, far beyond any pixel's).
inline FixedSum SplitSum(const FixedSum& increment, std::uint64_t fraction)
{
  FixedSum part = SplitWord(LowHalf(increment), fraction);
  if (const std::uint64_t high = HighHalf(increment))
  {
    std::uint64_t productHigh, productLow;
    Multiply64(high, fraction, productHigh, productLow);
    part += ((FixedSum(productHigh) << 64) + FixedSum(productLow)) << 32;
  }
  return part;
}

/// Channel fractions of `weights` (each >= 0, one > 0) in fixed point:
/// round(2^32 w / sum) for each positive weight but the last positive one,
/// which takes the rest, and 0 for a weight of 0, so that they sum to
/// exactly 2^32 and a channel of no weight gets nothing. False (nothing
/// written) when no weight is positive, one is negative or not finite, or
/// there are no channels.
inline bool FixedFractions(const double* weights, int channels, std::uint64_t* fractions)
{
  double largest = 0.0;
  int last = -1;
  for (int c = 0; c < channels; ++c)
  {
    if (!(weights[c] >= 0.0) || !std::isfinite(weights[c]))
    {
      return false;
    }
    largest = weights[c] > largest ? weights[c] : largest;
    last = weights[c] > 0.0 ? c : last;
  }
  if (last < 0)
  {
    return false;
  }
  // Relative to the largest, so that the sum cannot overflow.
  double sum = 0.0;
  for (int c = 0; c < channels; ++c)
  {
    sum += weights[c] / largest;
  }
  std::uint64_t given = 0;
  for (int c = 0; c < channels; ++c)
  {
    if (c == last)
    {
      continue;
    }
    std::uint64_t share = static_cast<std::uint64_t>(
      std::floor(weights[c] / largest / sum * static_cast<double>(FractionOne) + 0.5));
    share = share > FractionOne - given ? FractionOne - given : share;
    fractions[c] = share;
    given += share;
  }
  fractions[last] = FractionOne - given;
  return true;
}

/// A sample's parts of the channels it has a share in: Count pairs of a
/// channel and its fraction (> 0), the fractions summing to 2^32. Each
/// pair but the last takes the floor of its fraction of an increment, the
/// last takes the rest, so that the parts add up to the increment exactly
/// and a channel without a share is not touched (materials mixed linearly
/// between neighbouring anchors: two parts, whatever the number of channels).
struct ChannelShares
{
  int Count = 0;
  const std::uint32_t* Channels = nullptr;
  const std::uint64_t* Fractions = nullptr;
};

/// The shares of each level of an index, from its channel fractions
/// (FixedFractions per level; a level of no positive fraction has no
/// shares: its deposits reach no channel).
class ChannelShareTable
{
public:
  // Its shares point into its own vectors: moved, they stay valid; copied, they would not.
  ChannelShareTable() = default;
  ChannelShareTable(const ChannelShareTable&) = delete;
  ChannelShareTable& operator=(const ChannelShareTable&) = delete;
  ChannelShareTable(ChannelShareTable&&) = default;
  ChannelShareTable& operator=(ChannelShareTable&&) = default;

  void Build(const std::vector<std::uint64_t>& fractions, int channels)
  {
    const std::size_t levels = channels > 0 ? fractions.size() / channels : 0;
    this->Channels.clear();
    this->Fractions.clear();
    std::vector<std::size_t> begin(levels + 1, 0);
    for (std::size_t l = 0; l < levels; ++l)
    {
      for (int c = 0; c < channels; ++c)
      {
        const std::uint64_t fraction = fractions[l * channels + c];
        if (fraction > 0)
        {
          this->Channels.push_back(static_cast<std::uint32_t>(c));
          this->Fractions.push_back(fraction);
        }
      }
      begin[l + 1] = this->Channels.size();
    }
    this->Shares.assign(levels, ChannelShares());
    for (std::size_t l = 0; l < levels; ++l)
    {
      this->Shares[l].Count = static_cast<int>(begin[l + 1] - begin[l]);
      this->Shares[l].Channels = this->Channels.data() + begin[l];
      this->Shares[l].Fractions = this->Fractions.data() + begin[l];
    }
  }

  const ChannelShares* Of(std::int64_t level) const
  {
    return &this->Shares[static_cast<std::size_t>(level)];
  }

private:
  std::vector<std::uint32_t> Channels;
  std::vector<std::uint64_t> Fractions;
  std::vector<ChannelShares> Shares;
};

/// The shares of each point of a stored cloud: point i's are row Index[i]
/// of Table (the points of one CT number share a row).
struct PointShares
{
  const std::uint32_t* Index = nullptr;
  const ChannelShareTable* Table = nullptr;

  const ChannelShares* Of(std::uint64_t i) const { return this->Table->Of(this->Index[i]); }
};

} // namespace mcx

#endif
