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
void MeanOverIntervals(double* line, int n, std::size_t step, double radius)
{
  std::vector<double> v(static_cast<std::size_t>(n)), prefix(static_cast<std::size_t>(n), 0.0);
  for (int k = 0; k < n; ++k)
  {
    v[k] = line[k * step];
  }
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
    while (length * std::ldexp(1.0, -halvings) > reach && halvings < 20)
    {
      ++halvings;
    }
    plan.Halvings[k] = halvings;
  }
  return plan;
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

void FootprintDensity::Build(const double axes[3][2], const FootprintPlan& plan, int subdivisions)
{
  // The deposited part: the tent is two uniform segments along its axis, a
  // box (or sub-box) one.
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
  this->Half[0] = this->Half[1] = 0.5;
  for (const auto& s : segments)
  {
    this->Half[0] += 0.5 * std::fabs(s[0]);
    this->Half[1] += 0.5 * std::fabs(s[1]);
  }
  // About `subdivisions` nodes across the footprint's longer side, 4 to 128
  // per pixel: the grid's blur (about a quarter of a step) stays a small
  // fraction of the footprint however small the voxel.
  const double longer = 2.0 * std::max(this->Half[0], this->Half[1]);
  this->Q = static_cast<int>(std::min(128.0, std::max(4.0, std::ceil(subdivisions / longer))));
  const double h = 1.0 / this->Q;
  for (int a = 0; a < 2; ++a)
  {
    this->N[a] = static_cast<int>(std::ceil(this->Half[a] * this->Q)) + 1;
  }
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
  std::vector<double> scratch;
  this->Values.swap(f);
  for (const auto& s : segments)
  {
    this->Convolve(s.data(), scratch);
  }
}

void FootprintDensity::Convolve(const double s[2], std::vector<double>& scratch)
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
    // The mean over so short an interval is the interpolant's value to
    // about radius^2 (1e-12), and its antiderivatives' difference would
    // cancel in rounding: the segment changes nothing.
    return;
  }
  // A component a billion times smaller moves the footprint by less than
  // 1e-9 pixel: such a segment is along a, and convolved in place.
  if (std::fabs(s[b]) <= 1e-9 * std::fabs(s[a]))
  {
    for (int j = 0; j < nb; ++j)
    {
      MeanOverIntervals(this->Values.data() + j * stepB, na, stepA, radius);
    }
    return;
  }
  // Sheared frame: b' = b - r (i - N[a]), r = s[b] / s[a] (|r| <= 1), in
  // which the segment runs along a. Column i of the sheared copy holds nodes
  // b' = j' - E, j' = 0..nb + 2E - 1, wide enough for every node of the grid.
  const double r = s[b] / s[a];
  const int E = static_cast<int>(std::ceil(std::fabs(r) * this->N[a])) + 1;
  const int nbs = nb + 2 * E;
  scratch.assign(static_cast<std::size_t>(na) * nbs, 0.0);
  for (int i = 0; i < na; ++i)
  {
    const double shift = r * (i - this->N[a]) - E;
    const double* column = this->Values.data() + i * stepA;
    for (int j = 0; j < nbs; ++j)
    {
      scratch[static_cast<std::size_t>(i) * nbs + j] = Interpolate(column, nb, stepB, j + shift);
    }
  }
  for (int j = 0; j < nbs; ++j)
  {
    MeanOverIntervals(scratch.data() + j, na, static_cast<std::size_t>(nbs), radius);
  }
  for (int i = 0; i < na; ++i)
  {
    const double shift = E - r * (i - this->N[a]);
    const double* column = scratch.data() + static_cast<std::size_t>(i) * nbs;
    for (int j = 0; j < nb; ++j)
    {
      this->Values[i * stepA + j * stepB] = Interpolate(column, nbs, 1, j + shift);
    }
  }
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
  this->PhaseShiftBits = 6; // 64 phases, down to 8
  while (this->PhaseShiftBits > 3 &&
    size * static_cast<std::size_t>(this->Phases() * this->Phases()) > budget)
  {
    --this->PhaseShiftBits;
  }
  const int Phases = this->Phases();
  this->ShareValues.assign(size * Phases * Phases, 0.0);
  this->IncrementValues.assign(size * Phases * Phases, 0);
  this->Supports.assign(static_cast<std::size_t>(Phases) * Phases, Support());
  for (int b = 0; b < Phases; ++b)
  {
    for (int a = 0; a < Phases; ++a)
    {
      double* shares = this->ShareValues.data() + this->Offset(a, b);
      std::uint64_t* increments = this->IncrementValues.data() + this->Offset(a, b);
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
      this->Supports[static_cast<std::size_t>(b * Phases + a)] =
        SupportOfShares(shares, columns, rows);
    }
  }
}

} // namespace mcx
