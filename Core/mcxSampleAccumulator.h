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
#ifndef mcxSampleAccumulator_h
#define mcxSampleAccumulator_h

#include "mcxFixedPoint.h"
#include "mcxFootprint.h"
#include "mcxPixelBinner.h"
#include "mcxPrefetch.h"
#include "mcxProjectionGeometry.h"
#include "mcxRandom.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace mcx
{

/// The largest weight of a point of a weighted cloud: a point adds at most
/// 2^40 counts of 2^32 each, so no pixel's 128-bit sum comes near overflow.
constexpr double MaximumPointWeight = 1099511627776.0; // 2^40

/// Empty when each of the `count` weights is finite and in [0,
/// MaximumPointWeight] (what the deposits take); else why not, naming the
/// first point that is not.
template <typename Weight>
std::string PointWeightProblem(const Weight* weights, std::uint64_t count)
{
  for (std::uint64_t i = 0; i < count; ++i)
  {
    const double w = static_cast<double>(weights[i]);
    if (!(w >= 0.0 && w <= MaximumPointWeight)) // NaN too
    {
      std::ostringstream message;
      message << "point " << i << " has the weight " << w
              << " (weights must be finite and in [0, 2^40])";
      return message.str();
    }
  }
  return std::string();
}

/// The sum of weights [begin, end) in fixed point (each rounded to 2^-32, as
/// FixedIncrement): exact, so the same for any split of the work, and the
/// sums of consecutive ranges add up to the sum of their union.
template <typename Executor, typename Weight>
FixedSum PointWeightSum(
  const Executor& executor, const Weight* weights, std::uint64_t begin, std::uint64_t end)
{
  // A class with a zero default: a thread-local built-in integer would be
  // default-initialised (vtkSMPThreadLocal copies such an exemplar).
  struct Sum
  {
    FixedSum Value = 0;
  };
  typename Executor::template ThreadLocal<Sum> sums;
  executor.For(static_cast<std::int64_t>(begin), static_cast<std::int64_t>(end),
    std::int64_t(1) << 16,
    [&](std::int64_t b, std::int64_t e)
    {
      FixedSum& sum = sums.Local().Value;
      for (std::int64_t i = b; i < e; ++i)
      {
        sum += FixedIncrement(static_cast<double>(weights[i]));
      }
    });
  FixedSum total = 0;
  for (const Sum& sum : sums)
  {
    total += sum.Value;
  }
  return total;
}

/// How samples are deposited; the default is the paper's point deposit.
struct DepositSettings
{
  Deposit Mode = Deposit::Point;
  Kernel Reconstruction = Kernel::Tent;
  std::uint64_t Seed = 0; ///< of the footprint's random parts (its own stream)
  /// Pixels a deposited part may reach along each projected voxel axis
  /// (clamped to 0.5..32); a larger kernel is split (FootprintPlan), which
  /// bounds the cost of a sample.
  double Reach = 16.0;
  /// Perspective views: the depths (along the view, from the eye) between
  /// which the footprint is tabulated; samples nearer than Depths[0] are
  /// deposited as points.
  double Depths[2] = { 0.0, 0.0 };
  /// A voxel's edge vectors in the source frame (row-major, column k is
  /// edge k): the identity when samples come in voxel coordinates, the
  /// voxel's world edges for a stored cloud of world points.
  double VoxelMatrix[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  /// Whether the voxel choice is stratified (Hybrid, QuasiMonteCarlo): only
  /// then does the footprint's error fall as about M^-1.
  bool Stratified = true;

  bool operator==(const DepositSettings& o) const
  {
    return this->Mode == o.Mode && this->Reconstruction == o.Reconstruction &&
      this->Seed == o.Seed && this->Reach == o.Reach && this->Depths[0] == o.Depths[0] &&
      this->Depths[1] == o.Depths[1] &&
      std::equal(this->VoxelMatrix, this->VoxelMatrix + 9, o.VoxelMatrix) &&
      this->Stratified == o.Stratified;
  }
  bool operator!=(const DepositSettings& o) const { return !(*this == o); }
};

/// The footprint tables of one view: one in a parallel view, a ladder of
/// inverse depths w_j = W0 r^j in a perspective view.
class FootprintLadder
{
public:
  static constexpr double Ratio = 1.0905077326652577; // 2^(1/8)
  /// At most a depth ratio of 2^6 is tabulated; nearer samples (an eye in
  /// or next to the volume) are deposited as points.
  static constexpr int MaximumTables = 48;
  /// Each of the ladder's tables: its density grid's steps across the
  /// footprint and its size budget (FootprintTable::Build), below a parallel
  /// view's single table (many are built per camera change).
  static constexpr int TableSubdivisions = 160;
  static constexpr std::size_t TableBudget = 1 << 15;

  /// Builds the tables on `executor`, unless they are those of the same axes
  /// and settings (a TF edit or a refinement changes neither: tables are
  /// built once per view). The seed does not enter the tables. Non-finite
  /// axes or depths leave no table: every sample is then a point deposit.
  template <typename Executor>
  void Build(const Executor& executor, const PixelBinner& binner, const DepositSettings& settings)
  {
    double axes[3][2];
    binner.PixelAxes(settings.VoxelMatrix, axes);
    DepositSettings key = settings;
    key.Seed = 0;
    if (this->Built && this->Perspective == binner.IsPerspective() && key == this->BuiltFor &&
      std::equal(&axes[0][0], &axes[0][0] + 6, &this->BuiltAxes[0][0]))
    {
      return;
    }
    this->Built = true;
    this->BuiltFor = key;
    std::copy(&axes[0][0], &axes[0][0] + 6, &this->BuiltAxes[0][0]);
    this->Tables.clear();
    this->InverseDepths.clear();
    this->Perspective = binner.IsPerspective();
    if (!std::all_of(&axes[0][0], &axes[0][0] + 6, [](double a) { return std::isfinite(a); }))
    {
      return;
    }
    const double reach = std::min(32.0, std::max(0.5, settings.Reach));
    if (!this->Perspective)
    {
      this->Tables.emplace_back();
      this->Tables.back().Build(axes, FootprintPlan::For(settings.Reconstruction, axes, reach));
      return;
    }
    const double nearest = settings.Depths[0];
    const double farthest = std::max(settings.Depths[1], nearest);
    if (!(nearest > 0) || !std::isfinite(farthest))
    {
      return;
    }
    // From the farthest depth towards the eye.
    const double first = 1.0 / farthest;
    // Clamped before the cast: a tiny nearest depth makes the ratio infinite.
    const int count = static_cast<int>(std::min<double>(
      MaximumTables, 2 + std::ceil(std::log(farthest / nearest) / std::log(Ratio))));
    this->Tables.resize(static_cast<std::size_t>(count));
    this->InverseDepths.resize(static_cast<std::size_t>(count));
    for (int j = 0; j < count; ++j)
    {
      this->InverseDepths[static_cast<std::size_t>(j)] =
        first * std::pow(Ratio, static_cast<double>(j));
    }
    this->BuildGuide();
    executor.For(0, count, 1,
      [&](std::int64_t begin, std::int64_t end)
      {
        for (std::int64_t j = begin; j < end; ++j)
        {
          const double w = this->InverseDepths[static_cast<std::size_t>(j)];
          double scaled[3][2];
          for (int k = 0; k < 3; ++k)
          {
            scaled[k][0] = axes[k][0] * w;
            scaled[k][1] = axes[k][1] * w;
          }
          this->Tables[static_cast<std::size_t>(j)].Build(scaled,
            FootprintPlan::For(settings.Reconstruction, scaled, reach), TableBudget,
            TableSubdivisions);
        }
      });
  }

  /// True when some table splits its kernel into a random coarse part.
  bool AnyRandomSplit() const
  {
    return std::any_of(this->Tables.begin(), this->Tables.end(),
      [](const FootprintTable& t) { return t.Plan().IsRandom(); });
  }

  /// The table for inverse depth w (0 in parallel views), `u` in [0, 1)
  /// choosing between the two nearest scales so that the mean scale is w
  /// (the mean footprint linear in w between them); null beyond the ladder.
  /// A search, not a logarithm: this runs once per sample.
  const FootprintTable* Select(double w, double u) const
  {
    if (this->Tables.empty())
    {
      return nullptr;
    }
    if (!this->Perspective)
    {
      return &this->Tables.front();
    }
    const std::vector<double>& scales = this->InverseDepths; // at least 2 (Build)
    if (!(w >= scales.front() && w <= scales.back()))
    {
      return nullptr;
    }
    // The last j with scales[j] <= w, below the last scale: the guide's
    // bucket holds at most one scale, so a branch-free step up (or down,
    // where rounding chose the next bucket) finds it; the loops after them
    // only make sure (a bisection, its chain of dependent loads, cost more
    // than the rest of the choice).
    const std::size_t last = scales.size() - 2;
    const double bucket = (w - scales.front()) * this->GuideScale;
    std::size_t j = this->Guide[std::min(this->Guide.size() - 1, static_cast<std::size_t>(bucket))];
    j -= j > 0 && scales[j] > w ? 1 : 0;
    j += j < last && scales[j + 1] <= w ? 1 : 0;
    while (j > 0 && scales[j] > w)
    {
      --j;
    }
    while (j < last && scales[j + 1] <= w)
    {
      ++j;
    }
    const double fraction = (w - scales[j]) / (scales[j + 1] - scales[j]);
    return &this->Tables[u < fraction ? j + 1 : j];
  }

  bool IsEmpty() const { return this->Tables.empty(); }

private:
  // Guide[b]: the last j below the last scale with InverseDepths[j] at or
  // below bucket b's lower end; the buckets are narrower than the smallest
  // step between scales, so that each holds at most one scale.
  void BuildGuide()
  {
    const std::vector<double>& scales = this->InverseDepths;
    const double span = scales.back() - scales.front();
    const double step = scales[1] - scales[0]; // the smallest: the steps grow by Ratio
    const std::size_t buckets = static_cast<std::size_t>(std::ceil(span / step)) + 1;
    this->GuideScale = static_cast<double>(buckets) / span;
    this->Guide.assign(buckets, 0);
    std::size_t j = 0;
    for (std::size_t b = 0; b < buckets; ++b)
    {
      const double lower = scales.front() + static_cast<double>(b) / this->GuideScale;
      while (j + 2 < scales.size() && scales[j + 1] <= lower)
      {
        ++j;
      }
      this->Guide[b] = j;
    }
  }

  bool Built = false;
  DepositSettings BuiltFor;
  double BuiltAxes[3][2] = { { 0, 0 }, { 0, 0 }, { 0, 0 } };
  bool Perspective = false;
  std::vector<FootprintTable> Tables;
  std::vector<double> InverseDepths; // of the tables, rising by Ratio
  std::vector<std::size_t> Guide;
  double GuideScale = 0.0; // buckets per unit of inverse depth
};

/// One thread's image sums: two images, the samples below the split (the
/// first Halton half) and the rest, so that a sample adds to one sum per
/// pixel; a controlled accumulation (SampleAccumulator::SetControlled) keeps
/// two more, the same samples each counted once (images 2 and 3). Each sum
/// is a 64-bit low word per pixel; the high words are allocated at the
/// first carry, which never comes in parallel views (a sample adds 2^32, so
/// a pixel carries only after 2^32 samples of one thread in one round) and
/// only near the eye in perspective views. A sample touches 8 bytes per
/// pixel, not 32 (16 when controlled; a thread's image of 256^2 pixels
/// takes 1 MB, about a core's L2 cache).
class ThreadSums
{
public:
  /// Makes room for `pixels` sums in each of `images` images (2, or 4 when
  /// controlled), zeroed; keeps zeroed ones of that size.
  void Allocate(std::size_t pixels, int images = 2)
  {
    for (int half = 0; half < Images; ++half)
    {
      const std::size_t wanted = half < images ? pixels : 0;
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
  /// both are given and the sums hold them, and zeroes the sums for the
  /// next round.
  void CollectInto(std::size_t pixels, FixedSum* all, FixedSum* firstHalf,
    FixedSum* controlAll = nullptr, FixedSum* controlFirstHalf = nullptr)
  {
    if (this->Low[0].size() != pixels)
    {
      return;
    }
    const bool control = controlAll && controlFirstHalf && this->Low[2].size() == pixels;
    for (int half = 0; half < (control ? 4 : 2); ++half)
    {
      FixedSum* whole = half < 2 ? all : controlAll;
      FixedSum* first = half < 2 ? firstHalf : controlFirstHalf;
      const std::uint64_t* low = this->Low[half].data();
      const std::uint64_t* high = this->High[half].empty() ? nullptr : this->High[half].data();
      for (std::size_t p = 0; p < pixels; ++p)
      {
        const FixedSum sum = high ? (FixedSum(high[p]) << 64) + FixedSum(low[p]) : FixedSum(low[p]);
        whole[p] += sum;
        first[p] += half % 2 == 0 ? sum : FixedSum(0);
      }
      std::fill(this->Low[half].begin(), this->Low[half].end(), 0);
      this->High[half].clear();
    }
  }

private:
  void AddHigh(int half, std::int64_t pixel, std::uint64_t carry)
  {
    if (this->High[half].empty())
    {
      this->High[half].assign(this->Low[half].size(), 0);
    }
    this->High[half][static_cast<std::size_t>(pixel)] += carry;
  }

  static constexpr int Images = 4;
  std::vector<std::uint64_t> Low[Images];
  std::vector<std::uint64_t> High[Images];
};

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

  /// Samples with k < split count in the first half's sums as well.
  void SetSplit(std::uint64_t split) { this->Split = split; }

  std::size_t NumberOfPixels() const { return this->Pixels; }

  /// One thread's image; get it once per chunk of work, inside the executor's For.
  class ThreadImage
  {
  public:
    /// Deposits sample k at p by the accumulator's deposit, counting
    /// `weight` times (finite, >= 0).
    void Deposit(std::uint64_t k, const double p[3], double weight = 1.0) const
    {
      if (this->Ladder)
      {
        this->DepositFootprint(k, p, weight);
      }
      else
      {
        this->DepositPoint(k, p, weight);
      }
    }

    /// One count (times the perspective weight and the point's `weight`)
    /// where p lands.
    void DepositPoint(std::uint64_t k, const double p[3], double weight = 1.0) const
    {
      std::int64_t pixel;
      FixedSum increment;
      if (this->Binner->Bin(p, pixel, increment, weight) &&
        (!this->DepthLimits || this->Binner->Depth(p) < this->DepthLimits[pixel]))
      {
        this->Add(k, pixel, increment);
        if (this->Controlled && this->Binner->Bin(p, pixel, increment))
        {
          this->Sums->Add(k < this->Split ? 2 : 3, pixel, increment);
        }
      }
    }

    /// The footprint of the voxel centred at p (its random part, if the
    /// plan has one, drawn from the footprint stream of sample k), scaled
    /// by `weight`.
    void DepositFootprint(std::uint64_t k, const double centre[3], double weight = 1.0) const
    {
      PreparedFootprint footprint;
      if (this->PrepareFootprint(k, centre, footprint, weight))
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
    /// `weight` (finite, >= 0) scales the footprint.
    bool PrepareFootprint(std::uint64_t k, const double centre[3], PreparedFootprint& footprint,
      double weight = 1.0) const
    {
      CounterRandom random(this->FootprintKey, k);
      double fx, fy, f, w;
      if (!this->Binner->Locate(centre, fx, fy, f, w))
      {
        return false;
      }
      const FootprintTable* table = this->Ladder->Select(w, 1.0 - random.NextOpenClosed());
      double p[3] = { centre[0], centre[1], centre[2] };
      if (!table)
      {
        // Beyond the tabulated depths (an eye inside the volume): a point
        // from the whole kernel, unbiased as well.
        for (double& coordinate : p)
        {
          coordinate +=
            KernelOffsetFromUniform(this->Reconstruction, 1.0 - random.NextOpenClosed());
        }
        this->DepositPoint(k, p, weight);
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
      const int rx = table->Reach(0), ry = table->Reach(1);
      const int width = this->Binner->GetWidth(), height = this->Binner->GetHeight();
      if (!(fx > -rx - 1.0 && fy > -ry - 1.0 && fx < width + rx + 1.0 && fy < height + ry + 1.0))
      {
        return false; // the footprint misses the image (also keeps the casts below defined)
      }
      // The centre's pixel and phase, rounded at random to a tabulated phase.
      // Phases() is a power of two: shifts divide q by it, rounding down
      // (those of the non-negative q or ~q, whose results C++17 defines).
      const int phases = table->Phases(), shift = table->PhaseShift();
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
      const FootprintTable::Support& support = table->SupportOf(phase[0], phase[1]);
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
      footprint.Shares = table->Shares(phase[0], phase[1]);
      footprint.Increments = table->Increments(phase[0], phase[1]);
      footprint.F = f * weight;
      footprint.ControlF = f;
      footprint.Weighted = weight != 1.0;
      footprint.Depth = this->DepthLimits ? this->Binner->Depth(p) : 0.0;
      footprint.FirstHalf = k < this->Split;
      return true;
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
    /// controlled.
    void AddFootprint(const PreparedFootprint& footprint) const
    {
      const bool scales = this->ScalesShares(footprint);
      if (footprint.F != 0.0 || !scales)
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
    friend class SampleAccumulator;

    // Adds the footprint's table entries of its phase to every pixel it
    // reaches that lies in front of the pixel's depth limit, in the
    // thread's image Half (0: the first Halton half; 2 and 3: the control's
    // halves): the shares scaled by F when `scales` (perspective views,
    // weighted points), else the parallel view's exact integer increments.
    template <int Half>
    void AddShares(const PreparedFootprint& footprint, double F, bool scales) const
    {
      const std::int64_t x0 = footprint.Columns[0], x1 = footprint.Columns[1];
      const std::int64_t width = this->Binner->GetWidth();
      const double depth = footprint.Depth;
      // Locals, not members: the rare carry calls out of the loop, after
      // which members would be read again for every pixel.
      ThreadSums& sums = *this->Sums;
      std::uint64_t* low = sums.LowWords(Half);
      const double* limits = this->DepthLimits;
      // The pixels of the support, the depth test hoisted out of the loop.
      auto visit = [&](auto add)
      {
        for (std::int64_t y = footprint.Rows[0]; y <= footprint.Rows[1]; ++y)
        {
          const std::int64_t row =
            (y - footprint.Origin[1]) * footprint.Stride - footprint.Origin[0];
          const std::int64_t first = y * width;
          if (limits)
          {
            for (std::int64_t x = x0; x <= x1; ++x)
            {
              if (depth < limits[first + x])
              {
                add(first + x, row + x);
              }
            }
          }
          else
          {
            for (std::int64_t x = x0; x <= x1; ++x)
            {
              add(first + x, row + x);
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
              sums.AddWord(Half, low, pixel,
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
              sums.AddWord(
                Half, low, pixel, static_cast<std::uint64_t>(static_cast<std::int64_t>(scaled)));
            }
            else
            {
              sums.Add(Half, pixel, UInt128FromDouble(scaled));
            }
          });
        return;
      }
      const std::uint64_t* increments = footprint.Increments;
      visit([&](std::int64_t pixel, std::int64_t entry)
        { sums.AddWord(Half, low, pixel, increments[entry]); });
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

    void Add(std::uint64_t k, std::int64_t pixel, FixedSum increment) const
    {
      this->Sums->Add(k < this->Split ? 0 : 1, pixel, increment);
    }

    ThreadSums* Sums;
    bool Controlled;
    const PixelBinner* Binner;
    const FootprintLadder* Ladder;
    const double* DepthLimits;
    std::uint64_t Split;
    std::uint64_t FootprintKey;
    Kernel Reconstruction;
    const double* VoxelMatrix;
  };

  ThreadImage Local()
  {
    ThreadSums& sums = this->Images.Local();
    sums.Allocate(this->Pixels, this->Controlled ? 4 : 2);
    ThreadImage local;
    local.Sums = &sums;
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
  /// skipped, unless controlled). Footprints are prepared Lookahead samples before they are
  /// added, their cache lines asked for in between: in Halton order
  /// successive samples reach the image at random (3 to 5 % of a TF edit on
  /// the CT body). The sums are integers: the order of the additions leaves
  /// them unchanged.
  template <typename Real, typename Weight = float>
  void DepositRange(
    const Real* points, std::uint64_t begin, std::uint64_t end, const Weight* weights = nullptr)
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
    if (!this->Ladder)
    {
      for (std::uint64_t i = begin; i < end; ++i)
      {
        const double weight = weightOf(i);
        if (weight != 0.0 || image.Controlled) // the control counts every sample
        {
          double p[3];
          point(i, p);
          image.DepositPoint(i, p, weight);
        }
      }
      return;
    }
    constexpr std::uint64_t Lookahead = 8;
    typename ThreadImage::PreparedFootprint ring[Lookahead];
    bool pending[Lookahead] = {};
    for (std::uint64_t i = begin; i < end + Lookahead; ++i)
    {
      const std::uint64_t slot = i % Lookahead;
      if (pending[slot]) // sample i - Lookahead
      {
        image.AddFootprint(ring[slot]);
        pending[slot] = false;
      }
      if (i < end)
      {
        const double weight = weightOf(i);
        if (weight == 0.0 && !image.Controlled) // the control counts every sample
        {
          continue;
        }
        double p[3];
        point(i, p);
        pending[slot] = image.PrepareFootprint(i, p, ring[slot], weight);
        if (pending[slot])
        {
          image.Prefetch(ring[slot]);
        }
      }
    }
  }

  /// The same, in parallel on `executor`.
  template <typename Real, typename Weight = float>
  void DepositPoints(const Executor& executor, const Real* points, std::uint64_t begin,
    std::uint64_t end, const Weight* weights = nullptr)
  {
    executor.For(static_cast<std::int64_t>(begin), static_cast<std::int64_t>(end),
      std::int64_t(1) << 15,
      [&](std::int64_t b, std::int64_t e)
      {
        this->DepositRange(
          points, static_cast<std::uint64_t>(b), static_cast<std::uint64_t>(e), weights);
      });
  }

  /// Adds the threads' sums to all (every sample) and firstHalf (k < split),
  /// NumberOfPixels() each, and the control images to controlAll and
  /// controlFirstHalf when controlled, and zeroes them for the next
  /// deposits; call it after every round of deposits.
  void Collect(FixedSum* all, FixedSum* firstHalf, FixedSum* controlAll = nullptr,
    FixedSum* controlFirstHalf = nullptr)
  {
    for (ThreadSums& sums : this->Images)
    {
      sums.CollectInto(this->Pixels, all, firstHalf, controlAll, controlFirstHalf);
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
  typename Executor::template ThreadLocal<ThreadSums> Images;
};

} // namespace mcx

#endif
