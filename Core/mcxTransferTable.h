// The transfer function evaluated once per density level, as the discrete
// distribution the samplers draw voxels from (equation 6 of the paper).
#ifndef mcxTransferTable_h
#define mcxTransferTable_h

#include <cstdint>
#include <vector>

namespace mcx
{

struct TransferTable
{
  /// Cumulative[0] = 0, Cumulative[l + 1] = Cumulative[l] + w_l * n_l, where
  /// w_l is the level's weight divided by 2^Exponent (an exact power-of-two
  /// scaling that keeps the sums finite for weights up to the double range).
  std::vector<double> Cumulative;
  /// Per level: voxel count / (Cumulative[l + 1] - Cumulative[l]), 0 for empty levels.
  std::vector<double> RankScale;
  /// Guide table (Chen and Asau): Guide[b] is the smallest c >= 1 with
  /// Cumulative[c] >= b / Guide.size() * Cumulative.back(), so that finding
  /// the level of a target takes O(1) expected steps.
  std::vector<std::int64_t> Guide;
  /// True sum of weight times count = ldexp(Cumulative.back(), Exponent).
  int Exponent = 0;
  /// Levels whose weight was negative or NaN and was replaced by zero.
  std::int64_t NegativeLevels = 0;
  std::int64_t NaNLevels = 0;
  std::int64_t InfiniteLevels = 0;

  /// Sum over voxels of the weight (in TF units), possibly +inf if it overflows.
  double WeightSum() const;
  bool IsEmpty() const { return Cumulative.empty() || !(Cumulative.back() > 0.0); }
};

/// Builds the table from the weight of each level (TF at the level's value)
/// and the level offsets of the sorted ids (numberOfLevels + 1 entries).
/// Negative and NaN weights count as zero; an infinite weight makes the
/// table empty (InfiniteLevels > 0) because no finite distribution exists.
TransferTable BuildTransferTable(
  const double* weights, const std::int64_t* levelOffsets, std::int64_t numberOfLevels);

} // namespace mcx

#endif
