// One thread's exact image sums (64-bit low words, high words at the first
// carry): the memory the accumulator's deposits add to, apart from the
// deposits themselves (mcxThreadImage.h).
#ifndef mcxThreadSums_h
#define mcxThreadSums_h

#include "mcxFixedPoint.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mcx
{

/// One thread's image sums: two images, the samples below the split (the
/// first Halton half) and the rest, so that a sample adds to one sum per
/// pixel; a controlled accumulation (SampleAccumulator::SetControlled) keeps
/// two more, the same samples each counted once (images 2 and 3); a
/// deposit split into channels (mcxChannelSplit.h) two more per channel
/// (ChannelImage). Each sum
/// is a 64-bit low word per pixel; the high words are allocated at the
/// first carry, which never comes in parallel views (a sample adds 2^32, so
/// a pixel carries only after 2^32 samples of one thread in one round) and
/// only near the eye in perspective views. A sample touches 8 bytes per
/// pixel, not 32 (16 when controlled; a thread's image of 256^2 pixels
/// takes 1 MB, about a core's L2 cache).
class ThreadSums
{
public:
  /// The image of channel c's half (0: below the split).
  static int ChannelImage(int c, int half) { return 4 + 2 * c + half; }

  /// Makes room for `pixels` sums in each of `images` images (2, or 4 when
  /// controlled) and each channel's two, zeroed; keeps zeroed ones of that
  /// size.
  void Allocate(std::size_t pixels, int images = 2, int channels = 0)
  {
    const int count = ChannelImage(channels, 0);
    if (static_cast<int>(this->Low.size()) < count)
    {
      this->Low.resize(static_cast<std::size_t>(count));
      this->High.resize(static_cast<std::size_t>(count));
    }
    for (int half = 0; half < static_cast<int>(this->Low.size()); ++half)
    {
      const std::size_t wanted = half < images || (half >= 4 && half < count) ? pixels : 0;
      if (this->Low[half].size() != wanted)
      {
        // Swapped, not assigned: an image no longer used gives its memory back.
        std::vector<std::uint64_t>(wanted, 0).swap(this->Low[half]);
        this->High[half].clear();
      }
    }
  }

  /// Adds `increment` to pixel `pixel` of half `half` (0: below the split).
  void Add(int half, std::int64_t pixel, const FixedSum& increment)
  {
    std::uint64_t& low = this->Low[half][static_cast<std::size_t>(pixel)];
    const std::uint64_t part = LowHalf(increment);
    low += part;
    const std::uint64_t carry = HighHalf(increment) + (low < part ? 1 : 0);
    if (carry != 0)
    {
      this->AddHigh(half, pixel, carry);
    }
  }

  /// The same for an increment below 2^64, `low` being LowWords(half)
  /// (fetched once per footprint): the footprint's inner loop.
  void AddWord(int half, std::uint64_t* low, std::int64_t pixel, std::uint64_t increment)
  {
    low[pixel] += increment;
    if (low[pixel] < increment)
    {
      this->AddHigh(half, pixel, 1);
    }
  }

  std::uint64_t* LowWords(int half) { return this->Low[half].data(); }

  /// Adds both halves to `all` and the first to `firstHalf` (`pixels` each),
  /// the control images likewise to controlAll and controlFirstHalf when
  /// both are given and the sums hold them, each channel's to `all` and
  /// `firstHalf` as well (a split deposit adds its parts there only) and
  /// channel c's to channels[c] (2 x `pixels`: all, then the first half)
  /// for each of `channelCount`, and zeroes the sums for the next round.
  void CollectInto(std::size_t pixels, FixedSum* all, FixedSum* firstHalf,
    FixedSum* controlAll = nullptr, FixedSum* controlFirstHalf = nullptr,
    FixedSum* const* channels = nullptr, int channelCount = 0)
  {
    if (this->Low.empty() || this->Low[0].size() != pixels)
    {
      return;
    }
    const bool control = controlAll && controlFirstHalf && this->Low[2].size() == pixels;
    for (int half = 0; half < static_cast<int>(this->Low.size()); ++half)
    {
      if (this->Low[half].size() != pixels || (half >= 2 && half < 4 && !control))
      {
        continue;
      }
      if (half < 2 || half >= 4)
      {
        this->AddInto(half, pixels, all, firstHalf);
      }
      if (half >= 2 && half < 4)
      {
        this->AddInto(half, pixels, controlAll, controlFirstHalf);
      }
      else if (half >= 4 && (half - 4) / 2 < channelCount)
      {
        FixedSum* channel = channels[(half - 4) / 2];
        this->AddInto(half, pixels, channel, channel + pixels);
      }
      std::fill(this->Low[half].begin(), this->Low[half].end(), 0);
      this->High[half].clear();
    }
  }

private:
  // Adds image `half` to `whole`, and to `first` when it is a first half's.
  void AddInto(int half, std::size_t pixels, FixedSum* whole, FixedSum* first) const
  {
    const std::uint64_t* low = this->Low[half].data();
    const std::uint64_t* high = this->High[half].empty() ? nullptr : this->High[half].data();
    for (std::size_t p = 0; p < pixels; ++p)
    {
      const FixedSum sum = high ? (FixedSum(high[p]) << 64) + FixedSum(low[p]) : FixedSum(low[p]);
      whole[p] += sum;
      first[p] += half % 2 == 0 ? sum : FixedSum(0);
    }
  }

  void AddHigh(int half, std::int64_t pixel, std::uint64_t carry)
  {
    if (this->High[half].empty())
    {
      this->High[half].assign(this->Low[half].size(), 0);
    }
    this->High[half][static_cast<std::size_t>(pixel)] += carry;
  }

  std::vector<std::vector<std::uint64_t>> Low{ 4 };
  std::vector<std::vector<std::uint64_t>> High{ 4 };
};

} // namespace mcx

#endif
