// The footprint tables of one view (mcxFootprint.h): one table in a parallel
// view, a ladder of scales in a perspective view, and the choice of a table
// for each sample's inverse depth. Built once per view by the accumulator
// (SampleAccumulator::Reset), read by every thread's deposits.
#ifndef mcxFootprintLadder_h
#define mcxFootprintLadder_h

#include "mcxByteSize.h"
#include "mcxDepositSettings.h"
#include "mcxFootprint.h"
#include "mcxPixelBinner.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace mcx
{

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
  /// axes or depths leave no table: every sample is then a point deposit;
  /// so do voxels too large for the plan's halvings to bring within the
  /// reach (more than 2^40 times it, FootprintPlan::MaximumHalvings), and in
  /// perspective the scales nearer than the first such one. So each table
  /// spans at most 2 ceil(1.5 reach + 1) + 1 pixels a side (99 at the
  /// largest reach, 32): the tables' bytes are bounded by the reach
  /// (MaximumBytes), and are checked against settings.TableMemory before
  /// any is allocated (std::runtime_error "the footprint tables ... need").
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
    this->Steps.clear();
    this->Perspective = binner.IsPerspective();
    if (!std::all_of(&axes[0][0], &axes[0][0] + 6, [](double a) { return std::isfinite(a); }))
    {
      return;
    }
    const double reach = std::min(32.0, std::max(0.5, settings.Reach));
    if (!this->Perspective)
    {
      const FootprintPlan plan = FootprintPlan::For(settings.Reconstruction, axes, reach);
      if (!plan.Within(axes, reach))
      {
        return;
      }
      CheckTableMemory(FootprintTable::PlannedBytes(axes, plan), settings);
      this->Tables.emplace_back();
      this->Tables.back().Build(axes, plan);
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
    int count = static_cast<int>(std::min<double>(
      MaximumTables, 2 + std::ceil(std::log(farthest / nearest) / std::log(Ratio))));
    // The scales grow with j: the first too large to split ends the ladder.
    std::vector<FootprintPlan> plans;
    double bytes = 0.0;
    for (int j = 0; j < count; ++j)
    {
      double scaled[3][2];
      ScaleAxes(axes, first * std::pow(Ratio, static_cast<double>(j)), scaled);
      plans.push_back(FootprintPlan::For(settings.Reconstruction, scaled, reach));
      if (!plans.back().Within(scaled, reach))
      {
        plans.pop_back();
        break;
      }
      bytes += FootprintTable::PlannedBytes(scaled, plans.back(), TableBudget, TableSubdivisions);
    }
    count = static_cast<int>(plans.size());
    if (count < 2)
    {
      return; // a ladder needs two scales: every sample is a point deposit
    }
    CheckTableMemory(bytes, settings);
    this->Tables.resize(static_cast<std::size_t>(count));
    this->InverseDepths.resize(static_cast<std::size_t>(count));
    for (int j = 0; j < count; ++j)
    {
      this->InverseDepths[static_cast<std::size_t>(j)] =
        first * std::pow(Ratio, static_cast<double>(j));
    }
    this->Steps.resize(static_cast<std::size_t>(count - 1));
    for (std::size_t j = 0; j + 1 < this->InverseDepths.size(); ++j)
    {
      this->Steps[j] = this->InverseDepths[j + 1] - this->InverseDepths[j];
    }
    this->BuildGuide();
    executor.For(0, count, 1,
      [&](std::int64_t begin, std::int64_t end)
      {
        for (std::int64_t j = begin; j < end; ++j)
        {
          double scaled[3][2];
          ScaleAxes(axes, this->InverseDepths[static_cast<std::size_t>(j)], scaled);
          this->Tables[static_cast<std::size_t>(j)].Build(
            scaled, plans[static_cast<std::size_t>(j)], TableBudget, TableSubdivisions);
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
    // u < (w - scales[j]) / step, without the division's latency on every
    // footprint's path: the same probability; an exact tie may round the
    // other way.
    return &this->Tables[u * this->Steps[j] < w - scales[j] ? j + 1 : j];
  }

  bool IsEmpty() const { return this->Tables.empty(); }

  /// The most bytes the tables of one view take at the given reach (0.5 to
  /// 32 pixels), work space included: MaximumTables tables of the largest
  /// frame (FootprintTable::PlannedBytes of a footprint of half-width
  /// 0.5 + 1.5 reach).
  static double MaximumBytes(double reach)
  {
    reach = std::min(32.0, std::max(0.5, reach));
    const double half = 0.5 + 1.5 * reach;
    const double side = 2.0 * std::ceil(half + 0.5) + 1.0;
    const double values = std::max(double(1 << 17), 64.0 * side * side);
    const double nodes = 2.0 * (std::max(4.0 * half, 100.0 + half) + 2.0) + 1.0;
    return MaximumTables *
      (16.0 * values + 40.0 * 4096 + 32.0 * side * side + 40.0 * nodes * nodes);
  }

private:
  static void ScaleAxes(const double axes[3][2], double w, double scaled[3][2])
  {
    for (int k = 0; k < 3; ++k)
    {
      scaled[k][0] = axes[k][0] * w;
      scaled[k][1] = axes[k][1] * w;
    }
  }

  // The tables' bytes against the memory they may take (0: no limit).
  static void CheckTableMemory(double bytes, const DepositSettings& settings)
  {
    if (settings.TableMemory > 0 && bytes > settings.TableMemory)
    {
      throw std::runtime_error("the footprint tables of this view need " + DescribeBytes(bytes) +
        ", more than the memory budget of " + DescribeBytes(settings.TableMemory));
    }
  }

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
  std::vector<double> Steps;         // InverseDepths[j + 1] - InverseDepths[j]
  std::vector<std::size_t> Guide;
  double GuideScale = 0.0; // buckets per unit of inverse depth
};

} // namespace mcx

#endif
