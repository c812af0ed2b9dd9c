// The footprint deposit: a sample adds its voxel's reconstruction kernel,
// integrated along the view and averaged over each pixel's area, to every
// pixel the kernel reaches, instead of one count where a random offset from
// the kernel lands. The voxel choice is unchanged; the random offset, which
// dominates the point deposit's variance, is gone (or, for voxels much
// larger than a pixel, reduced to a coarse part: see FootprintPlan); only
// the sub-pixel phase (and in perspective the scale) is rounded at random.
//
// In pixel units (pixel i covering [i, i + 1)), the expected contribution of
// a point deposit of a voxel centred at c to the pixel centred at x is
//   G(x - c) = P(c + offset lies in that pixel) = density of (offset + B) at x - c,
// with B uniform on the unit square. G is what the footprint deposit adds.
// The offset is a sum of uniform segments along the voxel's projected edge
// vectors a_k (the tent is the sum of two uniforms per axis, the box one),
// so G is the convolution of the unit square with those segments: a box
// spline. It is tabulated once per view on a grid of step 1 / Q pixel by
// successive convolutions and read by bilinear interpolation; each sample's
// values are renormalised to its exact weight, so mass is conserved.
//
// Bias: the grid's interpolations (reading it, shearing it) err by O(Q^-2)
// of G's curvature (measured in the tests against the exact reference: far below
// the Monte Carlo error of any affordable sample count). In perspective
// views the footprint is the central direction's scaled by D / z (tables on
// a ladder of scales, chosen at random between the two nearest so that the
// mean scale is the sample's); the change of the footprint's shape with the
// ray's angle is neglected (bias stated and tested there too).
#ifndef mcxFootprint_h
#define mcxFootprint_h

#include "mcxSampleGenerator.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mcx
{

enum class Deposit : int
{
  Point = 0,    ///< one count where the sample's random offset lands (the paper's)
  Footprint = 1 ///< the voxel's kernel footprint over every pixel it reaches
};

/// How one voxel's kernel is split between a random offset and the part
/// deposited as a footprint, per voxel axis: the deposited part of axis k is
/// the full kernel (Halvings[k] < 0, tent only) or a box 2^-Halvings[k]
/// voxels wide; the rest of the kernel (the tent's second box factor, and
/// the centres of the 2^Halvings[k] sub-boxes) is drawn at random. The
/// expectation over the random part is the full kernel's footprint, so every
/// split is unbiased; coarser splits cost fewer pixels per sample.
struct FootprintPlan
{
  Kernel Reconstruction = Kernel::Tent;
  int Halvings[3] = { -1, -1, -1 };

  /// The most halvings of an axis: a voxel up to 2^40 times the reach (in
  /// pixels) is split; the random sub-box choice, from a uniform number of
  /// 53 bits, stays exact.
  static constexpr int MaximumHalvings = 40;

  /// The split whose deposited part reaches at most about `reach` pixels
  /// along each projected axis (axes in pixels), within MaximumHalvings.
  static FootprintPlan For(Kernel kernel, const double axes[3][2], double reach);

  /// True when the deposited part reaches at most `reach` pixels along each
  /// axis (false for voxels too large to split that far, or non-finite
  /// axes): only then is the table's size bounded by the reach.
  bool Within(const double axes[3][2], double reach) const;

  /// The random part's offset in voxels along each axis, from two uniform
  /// numbers per axis in [0, 1).
  void RandomOffset(const double uniform[3][2], double offset[3]) const;

  bool IsRandom() const
  {
    return this->Halvings[0] >= 0 || this->Halvings[1] >= 0 || this->Halvings[2] >= 0;
  }
};

/// The footprint of one plan and one set of projected axes, ready to add:
/// for each of Phases() x Phases() sub-pixel positions of the voxel centre
/// (phase (a, b) at a / Phases(), b / Phases() of a pixel from its lower
/// left corner), the shares of the pixels around it (summing to 1) and, for
/// parallel views, their fixed-point increments (summing to exactly one
/// count, 2^32). A sample's phase is rounded at random to one of the four
/// nearest, with the bilinear weights, so that the mean deposit is the
/// bilinear interpolation of G in the centre's position.
class FootprintTable
{
public:
  /// axes[k]: voxel edge vector k (spacing times direction) projected on the
  /// detector, in pixels along image axes 0 and 1.
  /// The phases are the most of 64, 32, 16 or 8 per pixel whose tables, in
  /// the whole frame (Columns() x Rows() a phase), would hold at most
  /// `budget` values (at least 8; the supports stored take less): fine
  /// phases for small footprints,
  /// whose shape changes fastest with the phase. `subdivisions`: the density
  /// grid's steps across the footprint (FootprintDensity::Build).
  void Build(const double axes[3][2], const FootprintPlan& plan, std::size_t budget = 1 << 17,
    int subdivisions = 200);

  /// The most bytes Build(axes, plan, budget, subdivisions) takes at once
  /// (the table and its work space), found before anything is allocated.
  static double PlannedBytes(const double axes[3][2], const FootprintPlan& plan,
    std::size_t budget = 1 << 17, int subdivisions = 200);

  /// Pixels reached beyond the centre's pixel along image axis a.
  int Reach(int a) const { return this->PixelReach[a]; }
  int Columns() const { return 2 * this->PixelReach[0] + 1; }
  int Rows() const { return 2 * this->PixelReach[1] + 1; }
  int Phases() const { return 1 << this->PhaseShiftBits; }
  /// log2 of Phases().
  int PhaseShift() const { return this->PhaseShiftBits; }

  /// The columns and rows (inclusive, 0..Columns() - 1 and 0..Rows() - 1)
  /// that hold every non-zero share of phase (a, b): only these are stored
  /// and visited (a kernel's support is narrower than the table's frame,
  /// which has room for every phase). Empty (Columns[1] < Columns[0]) for a
  /// phase without shares.
  struct Support
  {
    int Columns[2] = { 0, -1 };
    int Rows[2] = { 0, -1 };
    int Width() const { return this->Columns[1] - this->Columns[0] + 1; }
    int Height() const { return this->Rows[1] - this->Rows[0] + 1; }
  };
  const Support& SupportOf(int a, int b) const { return this->Blocks[this->Phase(a, b)].Extent; }

  /// Shares and increments of phase (a, b) over its support, Height() rows
  /// of Width() values: entry (i, j) is that of the pixel
  /// (i + Columns[0] - Reach(0), j + Rows[0] - Reach(1)) from the centre's.
  /// Stored only over the supports, the tables of a perspective ladder take
  /// half the cache they took in the whole frame.
  const double* Shares(int a, int b) const
  {
    return this->ShareValues.data() + this->Blocks[this->Phase(a, b)].Offset;
  }
  const std::uint64_t* Increments(int a, int b) const
  {
    return this->IncrementValues.data() + this->Blocks[this->Phase(a, b)].Offset;
  }

  const FootprintPlan& Plan() const { return this->SplitPlan; }

private:
  std::size_t Phase(int a, int b) const { return static_cast<std::size_t>(b * this->Phases() + a); }

  struct Block
  {
    Support Extent;
    std::size_t Offset = 0; // of its first value in ShareValues and IncrementValues
  };

  FootprintPlan SplitPlan;
  int PixelReach[2] = { 0, 0 };
  int PhaseShiftBits = 4; // Phases() = 2^PhaseShiftBits
  std::vector<double> ShareValues;
  std::vector<std::uint64_t> IncrementValues;
  std::vector<Block> Blocks;
};

/// G, the pixel-averaged footprint density (see above), on a grid of step
/// 1 / Q pixel (about `subdivisions` steps across the footprint, 4 to 128 per
/// pixel): built by successive convolutions of the unit square with the
/// plan's segments, read by bilinear interpolation. A segment along an image
/// axis is convolved exactly, by the antiderivative of the interpolant along
/// the rows or columns (O(1) per node); an oblique one the same way after a
/// shear that turns it along an axis (each shear interpolates linearly).
class FootprintDensity
{
public:
  void Build(const double axes[3][2], const FootprintPlan& plan, int subdivisions = 200);

  /// G at offset (dx, dy) pixels from the voxel centre, 0 outside.
  double Evaluate(double dx, double dy) const
  {
    const double gx = dx * this->Q + this->N[0];
    const double gy = dy * this->Q + this->N[1];
    if (!(gx >= 0 && gy >= 0 && gx < 2 * this->N[0] && gy < 2 * this->N[1]))
    {
      return 0.0;
    }
    const int ix = static_cast<int>(gx), iy = static_cast<int>(gy);
    const double tx = gx - ix, ty = gy - iy;
    const int stride = 2 * this->N[0] + 1;
    const double* row = this->Values.data() + static_cast<std::size_t>(iy) * stride + ix;
    return (1 - ty) * ((1 - tx) * row[0] + tx * row[1]) +
      ty * ((1 - tx) * row[stride] + tx * row[stride + 1]);
  }

  /// Half the extent of G's support along image axis a, in pixels.
  double HalfExtent(int a) const { return this->Half[a]; }

private:
  // Values = Values convolved with the segment s (pixels); the buffers are
  // reused from segment to segment.
  void Convolve(const double s[2], std::vector<double>& sheared, std::vector<double>& line);

  int Q = 8;
  int N[2] = { 0, 0 }; // nodes -N..N per axis
  double Half[2] = { 0, 0 };
  std::vector<double> Values;
};

} // namespace mcx

#endif
