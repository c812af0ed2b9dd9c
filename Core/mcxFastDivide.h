// Voxel id to (i, j, k) without hardware division on the sampling hot path.
#ifndef mcxFastDivide_h
#define mcxFastDivide_h

#include "mcxWideInteger.h"

#include <cstdint>
#include <type_traits>

namespace mcx
{

/// Exact n / d for n, d < 2^32 with one 64x64->128 multiply:
/// magic = floor(2^64 / d) + 1 overestimates 2^64 / d by less than 1, and
/// n * (magic - 2^64/d) / 2^64 < 2^-32 < 1/d cannot carry past the next integer.
class Divider32
{
public:
  explicit Divider32(std::uint64_t d = 1)
    : Divisor(d)
    , Magic(d <= 1 ? 0 : (~std::uint64_t(0) / d) + 1)
  {
  }
  std::uint64_t Quotient(std::uint64_t n) const
  {
    if (this->Magic == 0)
    {
      return n;
    }
    std::uint64_t high, low;
    Multiply64(n, this->Magic, high, low);
    return high;
  }
  std::uint64_t Divisor;

private:
  std::uint64_t Magic;
};

/// Decodes raster voxel ids (id = (k * ny + j) * nx + i) of an nx x ny x nz grid.
/// 32-bit ids use the multiply-shift divider; 64-bit ids divide in hardware.
template <typename IdType>
class VoxelDecoder
{
public:
  VoxelDecoder() = default;
  VoxelDecoder(std::uint64_t nx, std::uint64_t ny)
    : X(nx)
    , XY(nx * ny)
  {
  }

  void Decode(IdType id, std::uint64_t& i, std::uint64_t& j, std::uint64_t& k) const
  {
    const std::uint64_t n = static_cast<std::uint64_t>(id);
    if (std::is_same<IdType, std::uint32_t>::value)
    {
      k = this->XY.Quotient(n);
      const std::uint64_t r = n - k * this->XY.Divisor;
      j = this->X.Quotient(r);
      i = r - j * this->X.Divisor;
    }
    else
    {
      k = n / this->XY.Divisor;
      const std::uint64_t r = n - k * this->XY.Divisor;
      j = r / this->X.Divisor;
      i = r - j * this->X.Divisor;
    }
  }

private:
  Divider32 X;
  Divider32 XY;
};

} // namespace mcx

#endif
