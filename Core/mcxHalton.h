// Base-2 Halton (van der Corput) ordering and radical inverses.
//
// The hybrid sampler visits the sorted sequence u_i = (i + 1) / 2^m,
// i = 0 .. 2^m - 2, and stores sample i at the position k it has in the
// base-2 Halton sequence (u_i = RadicalInverse2(k + 1)), so that every
// prefix of 2^j - 1 stored samples holds exactly the Halton points of a
// 2^j - 1 sample run.
#ifndef mcxHalton_h
#define mcxHalton_h

#include <cstdint>

namespace mcx
{

inline std::uint64_t ReverseBits64(std::uint64_t x)
{
  // Byte order by one byte swap, then bits within each byte.
  x = __builtin_bswap64(x);
  x = ((x >> 4) & 0x0F0F0F0F0F0F0F0Full) | ((x & 0x0F0F0F0F0F0F0F0Full) << 4);
  x = ((x >> 2) & 0x3333333333333333ull) | ((x & 0x3333333333333333ull) << 2);
  return ((x >> 1) & 0x5555555555555555ull) | ((x & 0x5555555555555555ull) << 1);
}

/// The lowest `bits` bits of x in reverse order (0 for bits == 0).
inline std::uint64_t ReverseLowBits(std::uint64_t x, unsigned bits)
{
  return bits == 0 ? 0 : ReverseBits64(x) >> (64 - bits);
}

/// Largest supported exponent: M = 2^63 - 1 samples still fits a signed 64-bit count.
constexpr unsigned MaximumSampleExponent = 63;

/// M = 2^m - 1.
inline std::uint64_t SampleCount(unsigned m)
{
  return m == 0 ? 0 : ((std::uint64_t(1) << m) - 1);
}

/// Smallest m with 2^m - 1 >= n (n <= 0 gives 0).
inline unsigned ExponentForSampleCount(long long n)
{
  unsigned m = 0;
  while (m < MaximumSampleExponent && static_cast<long long>(SampleCount(m)) < n)
  {
    ++m;
  }
  return m;
}

/// Halton position of sorted index i for M = 2^m - 1 samples (1 <= m <= 63).
/// The map is an involution: it also turns a Halton position into a sorted index.
inline std::uint64_t HaltonPosition(std::uint64_t i, unsigned m)
{
  return (ReverseBits64(i + 1) >> (64 - m)) - 1;
}

/// Radical inverse of k in the given base, in [0, 1).
inline double RadicalInverse(std::uint64_t k, unsigned base)
{
  const double inverseBase = 1.0 / base;
  double factor = inverseBase;
  double result = 0.0;
  while (k > 0)
  {
    const std::uint64_t next = k / base;
    result += static_cast<double>(k - next * base) * factor;
    factor *= inverseBase;
    k = next;
  }
  return result;
}

} // namespace mcx

#endif
