#include "mcxTransferTable.h"

#include <cmath>

namespace mcx
{

double TransferTable::WeightSum() const
{
  return this->Cumulative.empty() ? 0.0 : std::ldexp(this->Cumulative.back(), this->Exponent);
}

TransferTable BuildTransferTable(
  const double* weights, const std::int64_t* levelOffsets, std::int64_t numberOfLevels)
{
  TransferTable table;
  double largest = 0.0;
  for (std::int64_t l = 0; l < numberOfLevels; ++l)
  {
    const double w = weights[l];
    if (std::isnan(w))
    {
      ++table.NaNLevels;
    }
    else if (std::isinf(w) && w > 0)
    {
      ++table.InfiniteLevels;
    }
    else if (w < 0)
    {
      ++table.NegativeLevels;
    }
    else if (w > largest && levelOffsets[l + 1] > levelOffsets[l])
    {
      largest = w;
    }
  }
  table.Cumulative.assign(static_cast<std::size_t>(numberOfLevels + 1), 0.0);
  table.RankScale.assign(static_cast<std::size_t>(numberOfLevels), 0.0);
  table.Guide.assign(1, 1);
  if (table.InfiniteLevels > 0 || largest == 0.0)
  {
    return table;
  }
  // Scale so the largest weight lies in [0.5, 1): the sums stay below the
  // voxel count, and a scaling by a power of two is exact.
  std::frexp(largest, &table.Exponent);
  double sum = 0.0;
  for (std::int64_t l = 0; l < numberOfLevels; ++l)
  {
    const double w = weights[l];
    if (w > 0)
    {
      const double count = static_cast<double>(levelOffsets[l + 1] - levelOffsets[l]);
      sum += std::ldexp(w, -table.Exponent) * count;
    }
    table.Cumulative[static_cast<std::size_t>(l + 1)] = sum;
  }
  for (std::int64_t l = 0; l < numberOfLevels; ++l)
  {
    const double mass = table.Cumulative[static_cast<std::size_t>(l + 1)] -
      table.Cumulative[static_cast<std::size_t>(l)];
    if (mass > 0)
    {
      table.RankScale[static_cast<std::size_t>(l)] =
        static_cast<double>(levelOffsets[l + 1] - levelOffsets[l]) / mass;
    }
  }
  const std::int64_t buckets =
    std::min<std::int64_t>(2 * numberOfLevels + 16, std::int64_t(1) << 22);
  table.Guide.assign(static_cast<std::size_t>(buckets), 1);
  std::int64_t c = 1;
  for (std::int64_t b = 0; b < buckets; ++b)
  {
    const double start = static_cast<double>(b) / static_cast<double>(buckets) * sum;
    while (c < numberOfLevels && table.Cumulative[static_cast<std::size_t>(c)] < start)
    {
      ++c;
    }
    table.Guide[static_cast<std::size_t>(b)] = c;
  }
  return table;
}

} // namespace mcx
