// One thread's deposits into its image sums (ThreadSums): a sample as a
// point where it lands or as its voxel's footprint (a FootprintLadder's
// table), each also counted once in the control images when controlled. A
// SampleAccumulator hands one to each chunk of work (Local()); it is a view
// of the accumulator's state, cheap to copy. Apart from the accumulator
// because this is the per-sample inner loop, read and tuned on its own.
#ifndef mcxThreadImage_h
#define mcxThreadImage_h

#include "mcxChannelSplit.h"
#include "mcxDepositSettings.h"
#include "mcxFixedPoint.h"
#include "mcxFootprint.h"
#include "mcxFootprintLadder.h"
#include "mcxGatheredSamples.h"
#include "mcxPixelBinner.h"
#include "mcxPrefetch.h"
#include "mcxRandom.h"
#include "mcxSampleGenerator.h"
#include "mcxThreadSums.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace mcx
{

template <typename Executor>
class SampleAccumulator;

/// One thread's image; get it once per chunk of work, inside the executor's For.
class ThreadImage
{
public:
  /// Deposits sample k at p by the accumulator's deposit, counting
  /// `weight` times (finite, >= 0). With channels (SampleAccumulator::
  /// SetChannels), `shares` are the sample's (mcxChannelSplit.h).
  void Deposit(std::uint64_t k, const double p[3], double weight = 1.0,
    const ChannelShares* shares = nullptr) const
  {
    if (this->Ladder)
    {
      this->DepositFootprint(k, p, weight, shares);
    }
    else
    {
      this->DepositPoint(k, p, weight, shares);
    }
  }

  /// One count (times the perspective weight and the point's `weight`)
  /// where p lands.
  void DepositPoint(std::uint64_t k, const double p[3], double weight = 1.0,
    const ChannelShares* shares = nullptr) const
  {
    std::int64_t pixel;
    FixedSum increment;
    if (this->Binner->Bin(p, pixel, increment, weight) &&
      (!this->DepthLimits || this->Binner->Depth(p) < this->DepthLimits[pixel]))
    {
      this->Add(k, pixel, increment, shares);
      if (this->Controlled && this->Binner->Bin(p, pixel, increment))
      {
        this->Sums->Add(k < this->Split ? 2 : 3, pixel, increment);
      }
    }
  }

  /// DepositPoint for the n samples k[i] at (x[i], y[i], z[i]), each of
  /// weight weights[i] (null: 1) and shares[i] with channels, their
  /// projection done on SIMD lanes (PixelBinner::LocatePoints: the arrays
  /// readable up to its padding): the same sums, bit for bit.
  void DepositPoints(const std::uint64_t* k, const double* x, const double* y, const double* z,
    std::size_t n, const ChannelShares* const* shares = nullptr,
    const double* weights = nullptr) const
  {
    constexpr std::size_t Most = PointBatch::Capacity;
    double fx[Most], fy[Most], f[Most];
    std::uint8_t located[Most];
    const PixelBinner& binner = *this->Binner;
    binner.LocatePoints(x, y, z, n, fx, fy, f, located);
    for (std::size_t i = 0; i < n; ++i)
    {
      std::int64_t pixel;
      FixedSum increment;
      if (!located[i] ||
        !binner.PixelOf(fx[i], fy[i], f[i], pixel, increment, weights ? weights[i] : 1.0))
      {
        continue;
      }
      if (this->DepthLimits)
      {
        const double p[3] = { x[i], y[i], z[i] };
        if (!(binner.Depth(p) < this->DepthLimits[pixel]))
        {
          continue;
        }
      }
      this->Add(k[i], pixel, increment, shares ? shares[i] : nullptr);
      if (this->Controlled)
      {
        if (weights) // the control counts the sample once, unweighted
        {
          binner.PixelOf(fx[i], fy[i], f[i], pixel, increment);
        }
        this->Sums->Add(k[i] < this->Split ? 2 : 3, pixel, increment);
      }
    }
  }

  /// Samples gathered for DepositPoints, Capacity at a time: the point
  /// deposit of a sample source's sink (Add, weight 1) and of a stored
  /// cloud in a perspective view (AddWeighted), Flush()ed at the end of
  /// each chunk of work.
  class PointBatch
  {
  public:
    static constexpr std::size_t Capacity = GatheredSamples::Capacity;

    explicit PointBatch(const ThreadImage& image)
      : Image(image)
    {
    }

    void Add(std::uint64_t k, const double p[3], const ChannelShares* shares = nullptr)
    {
      this->Push(k, p, 1.0, shares);
    }

    void AddWeighted(
      std::uint64_t k, const double p[3], double weight, const ChannelShares* shares = nullptr)
    {
      this->Weighted = true;
      this->Push(k, p, weight, shares);
    }

    void Flush()
    {
      GatheredSamples& s = this->Samples;
      this->Image.DepositPoints(s.K, s.X, s.Y, s.Z, s.Count,
        this->Image.Channels > 0 ? s.Shares : nullptr, this->Weighted ? s.Weights : nullptr);
      s.Count = 0;
    }

  private:
    void Push(std::uint64_t k, const double p[3], double weight, const ChannelShares* shares)
    {
      if (this->Samples.Push(k, p, weight, shares))
      {
        this->Flush();
      }
    }

    const ThreadImage& Image;
    GatheredSamples Samples;
    bool Weighted = false; // once AddWeighted was called: Flush passes the weights
  };

  /// The footprint of the voxel centred at p (its random part, if the
  /// plan has one, drawn from the footprint stream of sample k), scaled
  /// by `weight`.
  void DepositFootprint(std::uint64_t k, const double centre[3], double weight = 1.0,
    const ChannelShares* shares = nullptr) const
  {
    PreparedFootprint footprint;
    if (this->PrepareFootprint(k, centre, footprint, weight, shares))
    {
      this->AddFootprint(footprint);
    }
  }

  /// A footprint located and ready to add (PrepareFootprint).
  struct PreparedFootprint
  {
    const double* Shares = nullptr;            // of its phase, over its support
    const std::uint64_t* Increments = nullptr; // the same, in fixed point
    std::int64_t Entries = 0;                  // of either
    std::int64_t Origin[2] = { 0, 0 };         // the pixel of their first entry
    std::int64_t Stride = 0;                   // entries per row
    std::int64_t Columns[2] = { 0, -1 };       // the image's pixels it reaches, inclusive
    std::int64_t Rows[2] = { 0, -1 };
    double F = 1.0;        // the perspective scale of the shares, times the point's weight
    double ControlF = 1.0; // the perspective scale alone (the control images' F)
    double Depth = 0.0;    // along the view, for the depth limits
    bool FirstHalf = false;
    bool Weighted = false; // a weight other than 1: the shares scaled by F in any view
    const ChannelShares* Split = nullptr; // the sample's channel shares, if split
  };

  /// Whether AddFootprint scales the shares (by F) rather than adding the
  /// parallel view's exact integer increments.
  bool ScalesShares(const PreparedFootprint& footprint) const
  {
    return this->Binner->IsPerspective() || footprint.Weighted;
  }

  /// Everything of DepositFootprint but the pixel updates: true when a
  /// footprint is left to add (AddFootprint); false when the sample misses
  /// the image or was deposited as a point (beyond the tabulated depths).
  /// `weight` (finite, >= 0) scales the footprint; `shares` split it
  /// into the channels.
  bool PrepareFootprint(std::uint64_t k, const double centre[3], PreparedFootprint& footprint,
    double weight = 1.0, const ChannelShares* shares = nullptr) const
  {
    double fx, fy, f, w;
    return this->Binner->Locate(centre, fx, fy, f, w) &&
      this->PrepareLocatedFootprint(k, centre, fx, fy, f, w, footprint, weight, shares);
  }

  /// PrepareFootprint of a centre already located (PixelBinner::Locate or
  /// LocatePoints: its pixel coordinates, perspective weight and inverse
  /// depth).
  bool PrepareLocatedFootprint(std::uint64_t k, const double centre[3], double fx, double fy,
    double f, double w, PreparedFootprint& footprint, double weight = 1.0,
    const ChannelShares* shares = nullptr) const
  {
    CounterRandom random(this->FootprintKey, k);
    const FootprintTable* table = this->Ladder->Select(w, 1.0 - random.NextOpenClosed());
    double p[3] = { centre[0], centre[1], centre[2] };
    if (!table)
    {
      // Beyond the tabulated depths (an eye inside the volume): a point
      // from the whole kernel, unbiased as well.
      for (double& coordinate : p)
      {
        coordinate += KernelOffsetFromUniform(this->Reconstruction, 1.0 - random.NextOpenClosed());
      }
      this->DepositPoint(k, p, weight, shares);
      return false;
    }
    if (table->Plan().IsRandom())
    {
      double uniform[3][2], offset[3];
      for (auto& pair : uniform)
      {
        pair[0] = 1.0 - random.NextOpenClosed();
        pair[1] = 1.0 - random.NextOpenClosed();
      }
      table->Plan().RandomOffset(uniform, offset);
      this->Offset(offset, p);
      if (!this->Binner->Locate(p, fx, fy, f, w))
      {
        return false;
      }
    }
    footprint.Split = shares;
    return this->PlaceFootprint(*table, k, p, fx, fy, f, weight, random, footprint);
  }

  /// Asks for the cache lines that AddFootprint(footprint) will touch, so
  /// that a stored cloud, whose samples reach the image at random (Halton
  /// order), does not wait for them one footprint at a time.
  void Prefetch(const PreparedFootprint& footprint) const
  {
    const std::int64_t width = this->Binner->GetWidth();
    const std::uint64_t* low = this->Sums->LowWords(footprint.FirstHalf ? 0 : 1);
    const std::uint64_t* control =
      this->Controlled ? this->Sums->LowWords(footprint.FirstHalf ? 2 : 3) : nullptr;
    for (std::int64_t y = footprint.Rows[0]; y <= footprint.Rows[1]; ++y)
    {
      const std::int64_t first = y * width + footprint.Columns[0];
      const std::int64_t last = y * width + footprint.Columns[1];
      for (std::int64_t pixel = first; pixel <= last; pixel += 8) // 8 sums per 64-byte line
      {
        PrefetchForWriting(low + pixel);
        if (control)
        {
          PrefetchForWriting(control + pixel);
        }
      }
      PrefetchForWriting(low + last);
      if (control)
      {
        PrefetchForWriting(control + last);
      }
      if (this->DepthLimits)
      {
        PrefetchForReading(this->DepthLimits + first);
        PrefetchForReading(this->DepthLimits + last);
      }
    }
    const char* values = this->ScalesShares(footprint)
      ? reinterpret_cast<const char*>(footprint.Shares)
      : reinterpret_cast<const char*>(footprint.Increments);
    for (std::int64_t byte = 0; byte < 8 * footprint.Entries; byte += 64)
    {
      PrefetchForReading(values + byte);
    }
  }

  /// Adds a prepared footprint to the thread's image (a weight of 0 adds
  /// nothing there), and once, unweighted, to its control image when
  /// controlled. Kept out of line (GCC's attribute; other compilers ignore
  /// it): inlined into the sample source's loop it left its share loops out
  /// of line and the loop itself too, 4 % more instructions per footprint.
  [[gnu::noinline]] void AddFootprint(const PreparedFootprint& footprint) const
  {
    const bool scales = this->ScalesShares(footprint);
    if (footprint.Split && footprint.Split->Count > 0 && this->Channels > 0)
    {
      if (footprint.F != 0.0 || !scales)
      {
        this->AddSharesToChannels(footprint, footprint.F, scales);
      }
    }
    else if (footprint.F != 0.0 || !scales)
    {
      if (footprint.FirstHalf)
      {
        this->AddShares<0>(footprint, footprint.F, scales);
      }
      else
      {
        this->AddShares<1>(footprint, footprint.F, scales);
      }
    }
    if (this->Controlled)
    {
      const bool perspective = this->Binner->IsPerspective();
      if (footprint.FirstHalf)
      {
        this->AddShares<2>(footprint, footprint.ControlF, perspective);
      }
      else
      {
        this->AddShares<3>(footprint, footprint.ControlF, perspective);
      }
    }
  }

private:
  template <typename Executor>
  friend class SampleAccumulator;
  friend class FootprintBatch;

  // The rest of PrepareFootprint, once the sample's table is chosen and its
  // point p (pixel coordinates fx, fy, perspective scale f) is located:
  // the centre's pixel and phase, rounded at random from `random`, and the
  // part of the phase's support within the image.
  bool PlaceFootprint(const FootprintTable& table, std::uint64_t k, const double p[3], double fx,
    double fy, double f, double weight, CounterRandom& random, PreparedFootprint& footprint) const
  {
    const int rx = table.Reach(0), ry = table.Reach(1);
    const int width = this->Binner->GetWidth(), height = this->Binner->GetHeight();
    if (!(fx > -rx - 1.0 && fy > -ry - 1.0 && fx < width + rx + 1.0 && fy < height + ry + 1.0))
    {
      return false; // the footprint misses the image (also keeps the casts below defined)
    }
    // The centre's pixel and phase, rounded at random to a tabulated phase.
    // Phases() is a power of two: shifts divide q by it, rounding down
    // (those of the non-negative q or ~q, whose results C++17 defines).
    const int phases = table.Phases(), shift = table.PhaseShift();
    std::int64_t cell[2];
    int phase[2];
    const double position[2] = { fx, fy };
    for (int a = 0; a < 2; ++a)
    {
      const double t = position[a] * phases;
      const double lower = std::floor(t);
      std::int64_t q =
        static_cast<std::int64_t>(lower) + ((1.0 - random.NextOpenClosed()) < t - lower ? 1 : 0);
      cell[a] = q >= 0 ? q >> shift : ~(~q >> shift);
      phase[a] = static_cast<int>(q - cell[a] * phases);
    }
    if (cell[0] + rx < 0 || cell[1] + ry < 0 || cell[0] - rx >= width || cell[1] - ry >= height)
    {
      return false;
    }
    // Only the phase's support, within the image: the table has room for
    // every phase, a footprint fills only part of it.
    const FootprintTable::Support& support = table.SupportOf(phase[0], phase[1]);
    const std::int64_t left = cell[0] - rx, bottom = cell[1] - ry;
    footprint.Columns[0] = std::max<std::int64_t>(0, left + support.Columns[0]);
    footprint.Columns[1] = std::min<std::int64_t>(width - 1, left + support.Columns[1]);
    footprint.Rows[0] = std::max<std::int64_t>(0, bottom + support.Rows[0]);
    footprint.Rows[1] = std::min<std::int64_t>(height - 1, bottom + support.Rows[1]);
    if (footprint.Columns[0] > footprint.Columns[1] || footprint.Rows[0] > footprint.Rows[1])
    {
      return false; // the support misses the image, or the phase has no shares
    }
    footprint.Origin[0] = left + support.Columns[0];
    footprint.Origin[1] = bottom + support.Rows[0];
    footprint.Stride = support.Width();
    footprint.Entries = static_cast<std::int64_t>(support.Width()) * support.Height();
    footprint.Shares = table.Shares(phase[0], phase[1]);
    footprint.Increments = table.Increments(phase[0], phase[1]);
    footprint.F = f * weight;
    footprint.ControlF = f;
    footprint.Weighted = weight != 1.0;
    footprint.Depth = this->DepthLimits ? this->Binner->Depth(p) : 0.0;
    footprint.FirstHalf = k < this->Split;
    return true;
  }

  // Adds the footprint's table entries of its phase to every pixel it
  // reaches that lies in front of the pixel's depth limit, in the
  // thread's image Half (0: the first Halton half; 2 and 3: the control's
  // halves): the shares scaled by F when `scales` (perspective views,
  // weighted points), else the parallel view's exact integer increments.
  template <int Half>
  void AddShares(const PreparedFootprint& footprint, double F, bool scales) const
  {
    // Locals, not members: the rare carry calls out of the loop, after
    // which members would be read again for every pixel.
    ThreadSums& sums = *this->Sums;
    std::uint64_t* low = sums.LowWords(Half);
    this->VisitIncrements(
      footprint, F, scales,
      [&](std::int64_t pixel, std::uint64_t increment)
      { sums.AddWord(Half, low, pixel, increment); },
      [&](std::int64_t pixel, const FixedSum& increment) { sums.Add(Half, pixel, increment); });
  }

  // Calls add(pixel, increment) for every pixel of the footprint's support
  // in front of its depth limit, increment the fixed-point value AddShares
  // adds there (the shares scaled by F when `scales`, else the parallel
  // view's exact integer increments); addWide(pixel, increment) for one of
  // 2^63 or more.
  template <typename Add, typename AddWide>
  void VisitIncrements(
    const PreparedFootprint& footprint, double F, bool scales, Add&& add, AddWide&& addWide) const
  {
    const std::int64_t x0 = footprint.Columns[0], x1 = footprint.Columns[1];
    const std::int64_t width = this->Binner->GetWidth();
    const double depth = footprint.Depth;
    const double* limits = this->DepthLimits;
    // The pixels of the support, the depth test hoisted out of the loop.
    auto visit = [&](auto entryAdd)
    {
      for (std::int64_t y = footprint.Rows[0]; y <= footprint.Rows[1]; ++y)
      {
        const std::int64_t row = (y - footprint.Origin[1]) * footprint.Stride - footprint.Origin[0];
        const std::int64_t first = y * width;
        if (limits)
        {
          for (std::int64_t x = x0; x <= x1; ++x)
          {
            if (depth < limits[first + x])
            {
              entryAdd(first + x, row + x);
            }
          }
        }
        else
        {
          for (std::int64_t x = x0; x <= x1; ++x)
          {
            entryAdd(first + x, row + x);
          }
        }
      }
    };
    if (scales)
    {
      // round(2^32 F share), as FixedIncrement(F * share): scaling by 2^32 is exact.
      const double scale = F * FixedOne;
      const double* shares = footprint.Shares;
      if (scale < 9.2e18)
      {
        // Shares are at most 1, so scale * share + 0.5 stays below 9.2e18
        // (doubles there are 1024 apart): every increment fits the signed
        // cast, the same values as below without a test per pixel.
        visit(
          [&](std::int64_t pixel, std::int64_t entry)
          {
            add(pixel,
              static_cast<std::uint64_t>(static_cast<std::int64_t>(scale * shares[entry] + 0.5)));
          });
        return;
      }
      visit(
        [&](std::int64_t pixel, std::int64_t entry)
        {
          const double scaled = scale * shares[entry] + 0.5;
          if (scaled < 9.2e18)
          {
            // Through a signed cast: one instruction where an unsigned
            // one branches on 2^63 (the same truncation in this range).
            add(pixel, static_cast<std::uint64_t>(static_cast<std::int64_t>(scaled)));
          }
          else
          {
            addWide(pixel, UInt128FromDouble(scaled));
          }
        });
      return;
    }
    const std::uint64_t* increments = footprint.Increments;
    visit([&](std::int64_t pixel, std::int64_t entry) { add(pixel, increments[entry]); });
  }

  // p += the voxel matrix times an offset in voxels (the source frame is
  // voxel coordinates for the fused projector, world for a stored cloud).
  void Offset(const double offset[3], double p[3]) const
  {
    for (int r = 0; r < 3; ++r)
    {
      const double* row = this->VoxelMatrix + 3 * r;
      p[r] += row[0] * offset[0] + row[1] * offset[1] + row[2] * offset[2];
    }
  }

  void Add(std::uint64_t k, std::int64_t pixel, FixedSum increment,
    const ChannelShares* shares = nullptr) const
  {
    const int half = k < this->Split ? 0 : 1;
    if (shares && shares->Count > 0 && this->Channels > 0)
    {
      this->AddToChannels(half, pixel, increment, *shares); // the total is their sum
    }
    else
    {
      this->Sums->Add(half, pixel, increment);
    }
  }

  // The increment split by the shares, the last taking the rest: the
  // channels' increments add up to it exactly, so the total's sums are
  // theirs, added when collected (ThreadSums::CollectInto).
  void AddToChannels(
    int half, std::int64_t pixel, const FixedSum& increment, const ChannelShares& shares) const
  {
    FixedSum rest = increment;
    for (int i = 0; i + 1 < shares.Count; ++i)
    {
      const FixedSum part = SplitSum(increment, shares.Fractions[i]);
      this->Sums->Add(
        ThreadSums::ChannelImage(static_cast<int>(shares.Channels[i]), half), pixel, part);
      rest = rest - part;
    }
    this->Sums->Add(
      ThreadSums::ChannelImage(static_cast<int>(shares.Channels[shares.Count - 1]), half), pixel,
      rest);
  }

  // AddShares with each pixel's increment split into the channels instead
  // (the footprint's half, of shares of at least one channel; the control
  // is AddFootprint's). One or two parts (a level of one material, or mixed
  // between two neighbouring ones) have loops of their own, the words of
  // their images fetched once; more parts are rare.
  void AddSharesToChannels(const PreparedFootprint& footprint, double F, bool scales) const
  {
    const int half = footprint.FirstHalf ? 0 : 1;
    const ChannelShares& shares = *footprint.Split;
    auto wide = [&](std::int64_t pixel, const FixedSum& increment)
    { this->AddToChannels(half, pixel, increment, shares); };
    if (shares.Count > 2)
    {
      this->VisitIncrements(
        footprint, F, scales,
        [&](std::int64_t pixel, std::uint64_t increment) { wide(pixel, FixedSum(increment)); },
        wide);
      return;
    }
    ThreadSums& sums = *this->Sums;
    int image[2] = { 0, 0 };
    std::uint64_t* low[2] = { nullptr, nullptr };
    for (int i = 0; i < shares.Count; ++i)
    {
      image[i] = ThreadSums::ChannelImage(static_cast<int>(shares.Channels[i]), half);
      low[i] = sums.LowWords(image[i]);
    }
    if (shares.Count == 1)
    {
      this->VisitIncrements(
        footprint, F, scales,
        [&](std::int64_t pixel, std::uint64_t increment)
        { sums.AddWord(image[0], low[0], pixel, increment); },
        wide);
      return;
    }
    const std::uint64_t fraction = shares.Fractions[0];
    this->VisitIncrements(
      footprint, F, scales,
      [&](std::int64_t pixel, std::uint64_t increment)
      {
        const std::uint64_t part = SplitWord(increment, fraction);
        sums.AddWord(image[0], low[0], pixel, part);
        sums.AddWord(image[1], low[1], pixel, increment - part);
      },
      wide);
  }

  ThreadSums* Sums;
  int Channels = 0;
  bool Controlled;
  const PixelBinner* Binner;
  const FootprintLadder* Ladder;
  const double* DepthLimits;
  std::uint64_t Split;
  std::uint64_t FootprintKey;
  Kernel Reconstruction;
  const double* VoxelMatrix;
};

} // namespace mcx

#endif
