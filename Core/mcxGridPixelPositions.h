// PixelBinner::PixelPosition for the voxel centres of a grid, the same bits
// from tables: a voxel's source coordinates are its indices, so each of the
// projection's products depends on one index alone and is computed once
// per index, not once per voxel (a view order locates every voxel).
#ifndef mcxGridPixelPositions_h
#define mcxGridPixelPositions_h

#include "mcxPixelBinner.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace mcx
{

class GridPixelPositions
{
public:
  /// The voxels (i, j, k) of an nx x ny x nz grid in `binner`'s source frame.
  GridPixelPositions(const PixelBinner& binner, std::int64_t nx, std::int64_t ny, std::int64_t nz)
    : Map(binner.Mapping())
  {
    const std::int64_t counts[3] = { nx, ny, nz };
    for (int c = 0; c < 3; ++c)
    {
      std::vector<Products>& table = this->Tables[c];
      table.resize(static_cast<std::size_t>(counts[c] > 0 ? counts[c] : 0));
      for (std::size_t n = 0; n < table.size(); ++n)
      {
        const double p = static_cast<double>(n);
        for (int row = 0; row < 3; ++row)
        {
          table[n].Row[row] = this->Map.Rows[3 * row + c] * p;
        }
      }
    }
  }

  /// PixelBinner::PixelPosition of the point (i, j, k), bit for bit: the
  /// same products summed in the same order. False for a point off the
  /// grid (an id past the volume, from a damaged index, is never read past
  /// the tables).
  bool PixelPosition(
    std::uint64_t i, std::uint64_t j, std::uint64_t k, double& fx, double& fy) const
  {
    if (i >= this->Tables[0].size() || j >= this->Tables[1].size() || k >= this->Tables[2].size())
    {
      return false;
    }
    const Products& x = this->Tables[0][i];
    const Products& y = this->Tables[1][j];
    const Products& z = this->Tables[2][k];
    if (!this->Map.Perspective)
    {
      fx = x.Row[0] + y.Row[0] + z.Row[0] + this->Map.PixelOffset[0];
      fy = x.Row[1] + y.Row[1] + z.Row[1] + this->Map.PixelOffset[1];
      return std::isfinite(fx) && std::isfinite(fy);
    }
    const double depth = x.Row[2] + y.Row[2] + z.Row[2] + this->Map.Offset[2];
    if (!(depth >= this->Map.Near))
    {
      return false;
    }
    const double inverseDepth = 1.0 / depth;
    const double u = x.Row[0] + y.Row[0] + z.Row[0] + this->Map.Offset[0];
    const double v = x.Row[1] + y.Row[1] + z.Row[1] + this->Map.Offset[1];
    fx = u * inverseDepth * this->Map.PixelScale[0] + this->Map.PixelOffset[0];
    fy = v * inverseDepth * this->Map.PixelScale[1] + this->Map.PixelOffset[1];
    return std::isfinite(fx) && std::isfinite(fy);
  }

private:
  struct Products
  {
    double Row[3];
  };
  PixelBinner::Map Map;
  std::vector<Products> Tables[3]; // per axis: each index times the rows' column
};

} // namespace mcx

#endif
