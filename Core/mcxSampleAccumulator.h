// The one place where samples become image sums, for the off-line projector
// (samples as they are generated, or a stored cloud) and the mapper alike, so
// that their images agree by construction.
//
// A sample k at point p is binned by a PixelBinner (and dropped when it lies
// behind the pixel's depth limit, where opaque geometry hides it); its
// fixed-point increment goes into the calling thread's image. Each pixel
// holds two sums side by side, in one cache line: all samples, and those
// with k below the split (the first Halton half, which the error estimate
// compares with the rest). Collect() adds the threads' images up; integer
// sums make the result independent of the order and the number of threads.
#ifndef mcxSampleAccumulator_h
#define mcxSampleAccumulator_h

#include "mcxFixedPoint.h"
#include "mcxPixelBinner.h"
#include "mcxProjectionGeometry.h"

#include <algorithm>
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
    std::vector<double> depthLimits = std::vector<double>())
  {
    this->Binner.reset(new PixelBinner(geometry, origin, matrix));
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

  /// Samples with k < split count in the second sum as well.
  void SetSplit(std::uint64_t split) { this->Split = split; }

  std::size_t NumberOfPixels() const { return this->Pixels; }

  /// One thread's image; get it once per chunk of work, inside the executor's For.
  class ThreadImage
  {
  public:
    void Deposit(std::uint64_t k, const double p[3]) const
    {
      std::int64_t pixel;
      FixedSum increment;
      if (this->Binner->Bin(p, pixel, increment) &&
        (!this->DepthLimits || this->Binner->Depth(p) < this->DepthLimits[pixel]))
      {
        FixedSum* sums = this->Sums + 2 * pixel;
        sums[0] += increment;
        sums[1] += k < this->Split ? increment : FixedSum(0);
      }
    }

  private:
    friend class SampleAccumulator;
    FixedSum* Sums;
    const PixelBinner* Binner;
    const double* DepthLimits;
    std::uint64_t Split;
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
  std::size_t Pixels = 0;
  std::vector<double> DepthLimits;
  std::uint64_t Split = 0;
  typename Executor::template ThreadLocal<std::vector<FixedSum>> Images;
};

} // namespace mcx

#endif
