#include "mcxFootprint.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mcx
{

namespace
{
double LongestComponent(const double a[2])
{
  return std::max(std::fabs(a[0]), std::fabs(a[1]));
}

// The smallest box of columns and rows that holds every non-zero share.
FootprintTable::Support SupportOfShares(const double* shares, int columns, int rows)
{
  FootprintTable::Support support;
  support.Columns[0] = columns;
  support.Rows[0] = rows;
  for (int j = 0; j < rows; ++j)
  {
    for (int i = 0; i < columns; ++i)
    {
      if (shares[j * columns + i] > 0)
      {
        support.Columns[0] = std::min(support.Columns[0], i);
        support.Columns[1] = std::max(support.Columns[1], i);
        support.Rows[0] = std::min(support.Rows[0], j);
        support.Rows[1] = std::max(support.Rows[1], j);
      }
    }
  }
  return support;
}

// The linear interpolant of a line of n nodes (stride step) at index c: 0
// outside [0, n - 1), as FootprintDensity::Evaluate reads its grid.
double Interpolate(const double* line, int n, std::size_t step, double c)
{
  if (!(c >= 0) || !(c < n - 1))
  {
    return 0.0;
  }
  const int k = static_cast<int>(c);
  const double t = c - k;
  return (1 - t) * line[k * step] + t * line[(k + 1) * step];
}

// Replaces each node c of a line (n nodes, stride step) by the mean of its
// linear interpolant (0 outside [0, n - 1)) over [c - radius, c + radius]:
// (F(c + radius) - F(c - radius)) / (2 radius), F the antiderivative, with
// P_k the trapezoids below node k and F(k + t) = P_k + v_k t + (v_{k+1} - v_k) t^2 / 2.
// `buffer` (2 n values: the line and P) is reused from line to line.
void MeanOverIntervals(
  double* line, int n, std::size_t step, double radius, std::vector<double>& buffer)
{
  buffer.resize(2 * static_cast<std::size_t>(n));
  double* v = buffer.data();
  double* prefix = v + n;
  for (int k = 0; k < n; ++k)
  {
    v[k] = line[k * step];
  }
  prefix[0] = 0.0;
  for (int k = 1; k < n; ++k)
  {
    prefix[k] = prefix[k - 1] + 0.5 * (v[k - 1] + v[k]);
  }
  const auto antiderivative = [&](double c)
  {
    if (!(c > 0))
    {
      return 0.0;
    }
    if (c >= n - 1)
    {
      return prefix[n - 1];
    }
    const int k = static_cast<int>(c);
    const double t = c - k;
    return prefix[k] + t * (v[k] + 0.5 * t * (v[k + 1] - v[k]));
  };
  for (int k = 0; k < n; ++k)
  {
    line[k * step] = (antiderivative(k + radius) - antiderivative(k - radius)) / (2.0 * radius);
  }
}

// One line layout: `lines` lines of `count` nodes, line i starting at
// i * lineStep, its nodes `step` apart.
struct LineLayout
{
  int Lines;
  int Count;
  std::size_t LineStep;
  std::size_t Step;
};

// Node j of line i of `to` = the interpolant of line i of `from` at index
// j + slope * i + intercept: a shear of the grid (lines of both run along
// the same axis, index for index).
void ShearLines(const double* from, const LineLayout& in, double* to, const LineLayout& out,
  double slope, double intercept)
{
  for (int i = 0; i < in.Lines; ++i)
  {
    const double shift = slope * i + intercept;
    for (int j = 0; j < out.Count; ++j)
    {
      to[i * out.LineStep + j * out.Step] =
        Interpolate(from + i * in.LineStep, in.Count, in.Step, j + shift);
    }
  }
}

// Fraction of the cell [x - h / 2, x + h / 2] inside [-1/2, 1/2], over h.
double Coverage(double x, double h)
{
  const double overlap = std::min(x + 0.5 * h, 0.5) - std::max(x - 0.5 * h, -0.5);
  return std::max(0.0, overlap) / h;
}
}

FootprintPlan FootprintPlan::For(Kernel kernel, const double axes[3][2], double reach)
{
  FootprintPlan plan;
  plan.Reconstruction = kernel;
  for (int k = 0; k < 3; ++k)
  {
    const double length = LongestComponent(axes[k]);
    if (kernel == Kernel::Tent && 2.0 * length <= reach)
    {
      plan.Halvings[k] = -1;
      continue;
    }
    int halvings = 0;
    while (length * std::ldexp(1.0, -halvings) > reach && halvings < MaximumHalvings)
    {
      ++halvings;
    }
    plan.Halvings[k] = halvings;
  }
  return plan;
}

bool FootprintPlan::Within(const double axes[3][2], double reach) const
{
  for (int k = 0; k < 3; ++k)
  {
    const double length = LongestComponent(axes[k]);
    const double deposited =
      this->Halvings[k] < 0 ? 2.0 * length : length * std::ldexp(1.0, -this->Halvings[k]);
    if (!(deposited <= reach))
    {
      return false;
    }
  }
  return true;
}

void FootprintPlan::RandomOffset(const double uniform[3][2], double offset[3]) const
{
  for (int k = 0; k < 3; ++k)
  {
    offset[k] = 0.0;
    const int halvings = this->Halvings[k];
    if (halvings < 0)
    {
      continue; // the whole tent is deposited
    }
    if (this->Reconstruction == Kernel::Tent)
    {
      offset[k] += uniform[k][0] - 0.5; // the tent's second box factor
    }
    const double parts = std::ldexp(1.0, halvings);
    offset[k] += (std::floor(uniform[k][1] * parts) + 0.5) / parts - 0.5; // a sub-box's centre
  }
}

namespace
{
// The deposited part of plan: the tent is two uniform segments along its
// axis, a box (or sub-box) one.
std::vector<std::array<double, 2>> SegmentsOf(const double axes[3][2], const FootprintPlan& plan)
{
  std::vector<std::array<double, 2>> segments;
  for (int k = 0; k < 3; ++k)
  {
    const double scale = plan.Halvings[k] < 0 ? 1.0 : std::ldexp(1.0, -plan.Halvings[k]);
    const std::array<double, 2> segment = { axes[k][0] * scale, axes[k][1] * scale };
    if (LongestComponent(segment.data()) < 1e-12)
    {
      continue; // along the view: no extent on the detector
    }
    segments.push_back(segment);
    if (plan.Halvings[k] < 0)
    {
      segments.push_back(segment);
    }
  }
  return segments;
}

// The density grid of segments: half its support (pixels), its nodes per
// pixel q and its nodes -n..n per axis.
void GridOf(const std::vector<std::array<double, 2>>& segments, int subdivisions, double half[2],
  int& q, int n[2])
{
  half[0] = half[1] = 0.5;
  for (const auto& s : segments)
  {
    half[0] += 0.5 * std::fabs(s[0]);
    half[1] += 0.5 * std::fabs(s[1]);
  }
  // About `subdivisions` steps across the footprint's longer side, 4 to 128
  // per pixel: the grid's blur (a fraction of a step from the interpolation
  // that reads it, and from the two of each oblique segment's shears) stays
  // a small fraction of the footprint however small the voxel.
  const double longer = 2.0 * std::max(half[0], half[1]);
  q = static_cast<int>(std::min(128.0, std::max(4.0, std::ceil(subdivisions / longer))));
  for (int a = 0; a < 2; ++a)
  {
    n[a] = static_cast<int>(std::ceil(half[a] * q)) + 1;
  }
}

// Phases per pixel (log2) of a table of `size` pixels a phase: the most of
// 64, 32, 16 or 8 within budget values.
int PhaseBitsFor(std::size_t size, std::size_t budget)
{
  int bits = 6;
  while (bits > 3 && size * (std::size_t(1) << (2 * bits)) > budget)
  {
    --bits;
  }
  return bits;
}
}

void FootprintDensity::Build(const double axes[3][2], const FootprintPlan& plan, int subdivisions)
{
  if (!std::all_of(&axes[0][0], &axes[0][0] + 6, [](double v) { return std::isfinite(v); }))
  {
    // No density (0 everywhere) rather than casts of infinities; the ladder
    // keeps no table for such axes and deposits points instead.
    this->N[0] = this->N[1] = 0;
    this->Half[0] = this->Half[1] = 0.5;
    this->Values.assign(1, 0.0);
    return;
  }
  const std::vector<std::array<double, 2>> segments = SegmentsOf(axes, plan);
  GridOf(segments, subdivisions, this->Half, this->Q, this->N);
  const double h = 1.0 / this->Q;
  const int width = 2 * this->N[0] + 1, height = 2 * this->N[1] + 1;
  std::vector<double> f(static_cast<std::size_t>(width) * height);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      f[static_cast<std::size_t>(j) * width + i] =
        Coverage((i - this->N[0]) * h, h) * Coverage((j - this->N[1]) * h, h);
    }
  }
  // Convolution with each segment: the mean of f shifted along it.
  std::vector<double> sheared, line;
  this->Values.swap(f);
  for (const auto& s : segments)
  {
    this->Convolve(s.data(), sheared, line);
  }
}

void FootprintDensity::Convolve(
  const double s[2], std::vector<double>& sheared, std::vector<double>& line)
{
  // Along image axis a (the segment's longer component), across it b. Node
  // (i, j) is i along a, j along b (index units, step 1 / Q pixel).
  const int a = std::fabs(s[0]) >= std::fabs(s[1]) ? 0 : 1, b = 1 - a;
  const int width = 2 * this->N[0] + 1;
  const int na = 2 * this->N[a] + 1, nb = 2 * this->N[b] + 1;
  const std::size_t stepA = a == 0 ? 1 : static_cast<std::size_t>(width);
  const std::size_t stepB = a == 0 ? static_cast<std::size_t>(width) : 1;
  const double radius = 0.5 * std::fabs(s[a]) * this->Q;
  if (radius < 1e-6)
  {
    // The mean over so short an interval moves a node by about radius / 4
    // times the interpolant's change of slope there (under 1e-6 of the
    // values), while its antiderivatives' difference would cancel in
    // rounding: the segment is left out.
    return;
  }
  // A component a billion times smaller moves the footprint by less than
  // 1e-9 of the segment's length: such a segment is along a, convolved in place.
  if (std::fabs(s[b]) <= 1e-9 * std::fabs(s[a]))
  {
    for (int j = 0; j < nb; ++j)
    {
      MeanOverIntervals(this->Values.data() + j * stepB, na, stepA, radius, line);
    }
    return;
  }
  // Sheared frame: b' = b - r (i - N[a]), r = s[b] / s[a] (|r| <= 1), in
  // which the segment runs along a. Line i of the sheared copy holds
  // b' = j' - margin for j' = 0..nb + 2 margin - 1: every node of the grid,
  // whatever its shift.
  const double r = s[b] / s[a];
  const int margin = static_cast<int>(std::ceil(std::fabs(r) * this->N[a])) + 1;
  const int shearedCount = nb + 2 * margin;
  sheared.assign(static_cast<std::size_t>(na) * shearedCount, 0.0);
  const LineLayout grid = { na, nb, stepA, stepB };
  const LineLayout copy = { na, shearedCount, static_cast<std::size_t>(shearedCount), 1 };
  ShearLines(this->Values.data(), grid, sheared.data(), copy, r, -r * this->N[a] - margin);
  for (int j = 0; j < shearedCount; ++j)
  {
    MeanOverIntervals(sheared.data() + j, na, copy.LineStep, radius, line);
  }
  ShearLines(sheared.data(), copy, this->Values.data(), grid, -r, r * this->N[a] + margin);
}

double FootprintTable::PlannedBytes(
  const double axes[3][2], const FootprintPlan& plan, std::size_t budget, int subdivisions)
{
  if (!std::all_of(&axes[0][0], &axes[0][0] + 6, [](double v) { return std::isfinite(v); }))
  {
    return 0.0;
  }
  double half[2];
  int q = 0, n[2];
  GridOf(SegmentsOf(axes, plan), subdivisions, half, q, n);
  // The density grid, its first copy and the sheared copy (at most three
  // times as tall, with its margins), each of doubles.
  const double grid = (2.0 * n[0] + 1) * (2.0 * n[1] + 1);
  const double density = 8.0 * grid * 5.0;
  // The table's frame: every phase's shares and increments (16 bytes a
  // value, at most the whole frame each), its blocks, and two frames of
  // work space.
  const double size = (2.0 * std::ceil(half[0] + 0.5) + 1) * (2.0 * std::ceil(half[1] + 0.5) + 1);
  const double phases =
    std::ldexp(1.0, 2 * PhaseBitsFor(static_cast<std::size_t>(std::min(size, 1e15)), budget));
  return density + 16.0 * size * phases + sizeof(Block) * phases + 32.0 * size;
}

void FootprintTable::Build(
  const double axes[3][2], const FootprintPlan& plan, std::size_t budget, int subdivisions)
{
  this->SplitPlan = plan;
  FootprintDensity density;
  density.Build(axes, plan, subdivisions);
  for (int a = 0; a < 2; ++a)
  {
    // Pixel i's centre lies (i - c) + 1/2 - phase from a centre in pixel c.
    this->PixelReach[a] = static_cast<int>(std::ceil(density.HalfExtent(a) + 0.5));
  }
  const int columns = this->Columns(), rows = this->Rows();
  const std::size_t size = static_cast<std::size_t>(columns) * rows;
  this->PhaseShiftBits = PhaseBitsFor(size, budget); // 64 phases, down to 8
  const int Phases = this->Phases();
  this->ShareValues.clear();
  this->IncrementValues.clear();
  this->Blocks.assign(static_cast<std::size_t>(Phases) * Phases, Block());
  // Each phase in the whole frame first, then its support kept.
  std::vector<double> shares(size);
  std::vector<std::uint64_t> increments(size);
  for (int b = 0; b < Phases; ++b)
  {
    for (int a = 0; a < Phases; ++a)
    {
      double sum = 0.0;
      for (int j = 0; j < rows; ++j)
      {
        for (int i = 0; i < columns; ++i)
        {
          const double v = density.Evaluate(i - this->PixelReach[0] + 0.5 - double(a) / Phases,
            j - this->PixelReach[1] + 0.5 - double(b) / Phases);
          shares[j * columns + i] = v;
          sum += v;
        }
      }
      Block& block = this->Blocks[this->Phase(a, b)];
      block.Offset = this->ShareValues.size();
      if (!(sum > 0))
      {
        continue;
      }
      // Shares of one; increments of exactly 2^32, the rounding remainder
      // on the largest share.
      const std::uint64_t one = std::uint64_t(1) << 32;
      std::uint64_t given = 0;
      std::size_t largest = 0;
      for (std::size_t n = 0; n < size; ++n)
      {
        shares[n] /= sum;
        increments[n] = static_cast<std::uint64_t>(shares[n] * 4294967296.0 + 0.5);
        given += increments[n];
        largest = shares[n] > shares[largest] ? n : largest;
      }
      // Unsigned arithmetic: a remainder of either sign lands exactly, since
      // the rounding errors (at most 1/2 each) sum to far less than 2^32.
      increments[largest] += one - given;
      block.Extent = SupportOfShares(shares.data(), columns, rows);
      for (int j = block.Extent.Rows[0]; j <= block.Extent.Rows[1]; ++j)
      {
        const std::size_t first = static_cast<std::size_t>(j) * columns + block.Extent.Columns[0];
        const std::size_t last = static_cast<std::size_t>(j) * columns + block.Extent.Columns[1];
        this->ShareValues.insert(
          this->ShareValues.end(), shares.begin() + first, shares.begin() + last + 1);
        this->IncrementValues.insert(
          this->IncrementValues.end(), increments.begin() + first, increments.begin() + last + 1);
      }
    }
  }
}

} // namespace mcx
