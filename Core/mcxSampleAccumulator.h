// The one place where samples become image sums, for the off-line projector
// (samples as they are generated, or a stored cloud) and the mapper alike, so
// that their images agree by construction.
//
// A sample k at point p is binned by a PixelBinner (and dropped when it lies
// behind the pixel's depth limit, where opaque geometry hides it); its
// fixed-point increment goes into the calling thread's image. With the
// footprint deposit (mcxFootprint.h) p is the voxel's centre and the sample
// adds its kernel's footprint, whose increments add up to exactly the point
// deposit's one count in parallel views (to rounding in perspective views). Each pixel
// holds two sums side by side, in one cache line: all samples, and those
// with k below the split (the first Halton half, which the error estimate
// compares with the rest). Collect() adds the threads' images up; integer
// sums make the result independent of the order and the number of threads.
#ifndef mcxSampleAccumulator_h
#define mcxSampleAccumulator_h

#include "mcxFixedPoint.h"
#include "mcxFootprint.h"
#include "mcxPixelBinner.h"
#include "mcxProjectionGeometry.h"
#include "mcxRandom.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

namespace mcx
{

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
    this->First = 1.0 / farthest;
    const int count = std::min(MaximumTables,
      2 + static_cast<int>(std::ceil(std::log(farthest / nearest) / std::log(Ratio))));
    this->Tables.resize(static_cast<std::size_t>(count));
    executor.For(0, count, 1,
      [&](std::int64_t begin, std::int64_t end)
      {
        for (std::int64_t j = begin; j < end; ++j)
        {
          const double w = this->First * std::pow(Ratio, static_cast<double>(j));
          double scaled[3][2];
          for (int k = 0; k < 3; ++k)
          {
            scaled[k][0] = axes[k][0] * w;
            scaled[k][1] = axes[k][1] * w;
          }
          this->Tables[static_cast<std::size_t>(j)].Build(
            scaled, FootprintPlan::For(settings.Reconstruction, scaled, reach), 1 << 15, 64);
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
  /// choosing between the two nearest scales so that the mean is linear in
  /// log w; null beyond the ladder.
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
    const double t = std::log(w / this->First) / std::log(Ratio);
    if (!(t >= 0) || !(t <= static_cast<double>(this->Tables.size() - 1)))
    {
      return nullptr;
    }
    std::size_t j = static_cast<std::size_t>(t);
    j += (u < t - static_cast<double>(j) && j + 1 < this->Tables.size()) ? 1 : 0;
    return &this->Tables[j];
  }

  bool IsEmpty() const { return this->Tables.empty(); }

private:
  bool Built = false;
  DepositSettings BuiltFor;
  double BuiltAxes[3][2] = { { 0, 0 }, { 0, 0 }, { 0, 0 } };
  bool Perspective = false;
  double First = 0.0;
  std::vector<FootprintTable> Tables;
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
    // Collect() leaves the images zeroed: only another size is reallocated.
    for (std::vector<FixedSum>& image : this->Images)
    {
      if (image.size() != 2 * this->Pixels)
      {
        image.clear();
      }
    }
  }

  /// True when the image's error falls about as M^-1 (footprints of whole
  /// kernels with a stratified voxel choice), so that the halves' error
  /// estimate needs mcx::FootprintErrorCalibration; false for M^-1/2.
  bool ErrorFallsAsInverseM() const
  {
    return this->Ladder && this->Settings.Stratified && !this->Ladder->IsEmpty() &&
      !this->Ladder->AnyRandomSplit();
  }

  /// Samples with k < split count in the second sum as well.
  void SetSplit(std::uint64_t split) { this->Split = split; }

  std::size_t NumberOfPixels() const { return this->Pixels; }

  /// One thread's image; get it once per chunk of work, inside the executor's For.
  class ThreadImage
  {
  public:
    /// Deposits sample k at p by the accumulator's deposit.
    void Deposit(std::uint64_t k, const double p[3]) const
    {
      if (this->Ladder)
      {
        this->DepositFootprint(k, p);
      }
      else
      {
        this->DepositPoint(k, p);
      }
    }

    /// One count (times the perspective weight) where p lands.
    void DepositPoint(std::uint64_t k, const double p[3]) const
    {
      std::int64_t pixel;
      FixedSum increment;
      if (this->Binner->Bin(p, pixel, increment) &&
        (!this->DepthLimits || this->Binner->Depth(p) < this->DepthLimits[pixel]))
      {
        this->Add(k, pixel, increment);
      }
    }

    /// The footprint of the voxel centred at p (its random part, if the
    /// plan has one, drawn from the footprint stream of sample k).
    void DepositFootprint(std::uint64_t k, const double centre[3]) const
    {
      CounterRandom random(this->FootprintKey, k);
      double fx, fy, f, w;
      if (!this->Binner->Locate(centre, fx, fy, f, w))
      {
        return;
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
        this->DepositPoint(k, p);
        return;
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
          return;
        }
      }
      const int rx = table->Reach(0), ry = table->Reach(1);
      const int width = this->Binner->GetWidth(), height = this->Binner->GetHeight();
      if (!(fx > -rx - 1.0 && fy > -ry - 1.0 && fx < width + rx + 1.0 && fy < height + ry + 1.0))
      {
        return; // the footprint misses the image (also keeps the casts below defined)
      }
      // The centre's pixel and phase, rounded at random to a tabulated phase.
      const int phases = table->Phases();
      std::int64_t cell[2];
      int phase[2];
      const double position[2] = { fx, fy };
      for (int a = 0; a < 2; ++a)
      {
        const double t = position[a] * phases;
        const double lower = std::floor(t);
        std::int64_t q =
          static_cast<std::int64_t>(lower) + ((1.0 - random.NextOpenClosed()) < t - lower ? 1 : 0);
        cell[a] = q >= 0 ? q / phases : -((-q + phases - 1) / phases);
        phase[a] = static_cast<int>(q - cell[a] * phases);
      }
      if (cell[0] + rx < 0 || cell[1] + ry < 0 || cell[0] - rx >= width || cell[1] - ry >= height)
      {
        return;
      }
      const int columns = table->Columns();
      const double* shares = table->Shares(phase[0], phase[1]);
      const std::uint64_t* increments = table->Increments(phase[0], phase[1]);
      const bool perspective = this->Binner->IsPerspective();
      const double depth = this->DepthLimits ? this->Binner->Depth(p) : 0.0;
      const std::int64_t x0 = std::max<std::int64_t>(0, cell[0] - rx);
      const std::int64_t x1 = std::min<std::int64_t>(width - 1, cell[0] + rx);
      const std::int64_t y0 = std::max<std::int64_t>(0, cell[1] - ry);
      const std::int64_t y1 = std::min<std::int64_t>(height - 1, cell[1] + ry);
      for (std::int64_t y = y0; y <= y1; ++y)
      {
        const std::int64_t row = (y - cell[1] + ry) * columns - (cell[0] - rx);
        for (std::int64_t x = x0; x <= x1; ++x)
        {
          const std::int64_t n = row + x;
          if (perspective ? !(shares[n] > 0) : increments[n] == 0)
          {
            continue;
          }
          const std::int64_t pixel = x + y * static_cast<std::int64_t>(width);
          if (!this->DepthLimits || depth < this->DepthLimits[pixel])
          {
            this->Add(
              k, pixel, perspective ? FixedIncrement(f * shares[n]) : FixedSum(increments[n]));
          }
        }
      }
    }

  private:
    friend class SampleAccumulator;
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
      FixedSum* sums = this->Sums + 2 * pixel;
      sums[0] += increment;
      sums[1] += k < this->Split ? increment : FixedSum(0);
    }

    FixedSum* Sums;
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
    std::vector<FixedSum>& image = this->Images.Local();
    if (image.size() != 2 * this->Pixels)
    {
      image.assign(2 * this->Pixels, FixedSum(0));
    }
    ThreadImage local;
    local.Sums = image.data();
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
  /// being sample i, in the calling thread.
  template <typename Real>
  void DepositRange(const Real* points, std::uint64_t begin, std::uint64_t end)
  {
    const ThreadImage image = this->Local();
    for (std::uint64_t i = begin; i < end; ++i)
    {
      const double p[3] = { static_cast<double>(points[3 * i]),
        static_cast<double>(points[3 * i + 1]), static_cast<double>(points[3 * i + 2]) };
      image.Deposit(i, p);
    }
  }

  /// The same, in parallel on `executor`.
  template <typename Real>
  void DepositPoints(
    const Executor& executor, const Real* points, std::uint64_t begin, std::uint64_t end)
  {
    executor.For(static_cast<std::int64_t>(begin), static_cast<std::int64_t>(end),
      std::int64_t(1) << 15,
      [&](std::int64_t b, std::int64_t e) {
        this->DepositRange(points, static_cast<std::uint64_t>(b), static_cast<std::uint64_t>(e));
      });
  }

  /// Adds the threads' sums to all (every sample) and firstHalf (k < split),
  /// NumberOfPixels() each, and zeroes them for the next deposits; call it
  /// after every round of deposits.
  void Collect(FixedSum* all, FixedSum* firstHalf)
  {
    for (std::vector<FixedSum>& image : this->Images)
    {
      if (image.size() != 2 * this->Pixels)
      {
        continue;
      }
      for (std::size_t p = 0; p < this->Pixels; ++p)
      {
        all[p] += image[2 * p];
        firstHalf[p] += image[2 * p + 1];
      }
      std::fill(image.begin(), image.end(), FixedSum(0));
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
  typename Executor::template ThreadLocal<std::vector<FixedSum>> Images;
};

} // namespace mcx

#endif
