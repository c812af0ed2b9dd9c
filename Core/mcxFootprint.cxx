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
  // About `subdivisions` nodes across the footprint's longer side, 4 to 64
  // per pixel: the grid's blur (about a quarter of a step) stays a small
  // fraction of the footprint however small the voxel.
  const double longer = 2.0 * std::max(this->Half[0], this->Half[1]);
  this->Q = static_cast<int>(std::min(64.0, std::max(4.0, std::ceil(subdivisions / longer))));
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
  // Convolution with each segment: the mean of f shifted along it, by the
  // midpoint rule at spacing below h / 2, f interpolated bilinearly.
  std::vector<double> g(f.size());
  this->Values.swap(f);
  for (const auto& s : segments)
  {
    const int n = 2 * static_cast<int>(std::ceil(LongestComponent(s.data()) * this->Q));
    for (int j = 0; j < height; ++j)
    {
      for (int i = 0; i < width; ++i)
      {
        double sum = 0.0;
        for (int m = 0; m < n; ++m)
        {
          const double u = (m + 0.5) / n - 0.5;
          sum += this->Evaluate((i - this->N[0]) * h - u * s[0], (j - this->N[1]) * h - u * s[1]);
        }
        g[static_cast<std::size_t>(j) * width + i] = sum / n;
      }
    }
    this->Values.swap(g);
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
