// 128-bit unsigned arithmetic, the one place that knows about compiler
// extensions: the exact image sums and the 64 x 64 -> 128 multiplies of the
// random streams and the fast divider.
//
// mcx::UInt128 is the compiler's unsigned __int128 where it has one (GCC,
// Clang) and mcx::PortableUInt128 elsewhere (MSVC); defining
// MCX_PORTABLE_WIDE_INTEGER forces the portable one. Both are always
// compiled, so the tests compare them on every platform.
#ifndef mcxWideInteger_h
#define mcxWideInteger_h

#include <cmath>
#include <cstdint>

namespace mcx
{

/// Two 64-bit halves with the few operations the project needs: addition,
/// comparison, left shift, conversion from and to double.
class PortableUInt128
{
public:
  constexpr PortableUInt128() = default;
  constexpr PortableUInt128(std::uint64_t value) // NOLINT: implicit, as the built-in type
    : Low(value)
  {
  }
  constexpr PortableUInt128(std::uint64_t high, std::uint64_t low)
    : Low(low)
    , High(high)
  {
  }

  constexpr std::uint64_t LowHalf() const { return this->Low; }
  constexpr std::uint64_t HighHalf() const { return this->High; }

  PortableUInt128& operator+=(const PortableUInt128& other)
  {
    const std::uint64_t low = this->Low + other.Low;
    this->High += other.High + (low < this->Low ? 1 : 0);
    this->Low = low;
    return *this;
  }
  friend PortableUInt128 operator+(PortableUInt128 a, const PortableUInt128& b) { return a += b; }
  /// Modulo 2^128, as the built-in type.
  friend PortableUInt128 operator-(const PortableUInt128& a, const PortableUInt128& b)
  {
    return PortableUInt128(a.High - b.High - (a.Low < b.Low ? 1 : 0), a.Low - b.Low);
  }

  friend constexpr PortableUInt128 operator<<(const PortableUInt128& a, unsigned shift)
  {
    return shift == 0 ? a
      : shift >= 128  ? PortableUInt128()
      : shift >= 64   ? PortableUInt128(a.Low << (shift - 64), 0)
                    : PortableUInt128((a.High << shift) | (a.Low >> (64 - shift)), a.Low << shift);
  }

  friend constexpr bool operator==(const PortableUInt128& a, const PortableUInt128& b)
  {
    return a.Low == b.Low && a.High == b.High;
  }
  friend constexpr bool operator!=(const PortableUInt128& a, const PortableUInt128& b)
  {
    return !(a == b);
  }
  friend constexpr bool operator<(const PortableUInt128& a, const PortableUInt128& b)
  {
    return a.High < b.High || (a.High == b.High && a.Low < b.Low);
  }

  /// The nearest double (as a conversion of the built-in type gives).
  explicit operator double() const
  {
    if (this->High == 0)
    {
      return static_cast<double>(this->Low);
    }
    // Round the top 64 significant bits once, keeping a sticky bit for the
    // rest, so the result is correctly rounded.
    int shift = 0;
    for (std::uint64_t h = this->High; h != 0; h >>= 1)
    {
      ++shift;
    }
    const std::uint64_t top =
      shift == 64 ? this->High : (this->High << (64 - shift)) | (this->Low >> shift);
    const std::uint64_t rest = shift == 64 ? this->Low : this->Low << (64 - shift);
    // 64 bits to 53: round half to even on bit 11, with everything below as sticky.
    const std::uint64_t kept = top >> 11;
    const std::uint64_t dropped = top & 0x7FF;
    const bool sticky = rest != 0;
    std::uint64_t rounded = kept;
    if (dropped > 0x400 || (dropped == 0x400 && (sticky || (kept & 1))))
    {
      ++rounded;
    }
    return std::ldexp(static_cast<double>(rounded), shift + 11);
  }

  /// Truncates a non-negative double below 2^128 towards zero.
  static PortableUInt128 FromDouble(double value)
  {
    if (!(value >= 1.0))
    {
      return PortableUInt128();
    }
    const double two64 = 18446744073709551616.0;
    const double high = std::floor(value / two64);
    const double low = value - high * two64;
    return PortableUInt128(static_cast<std::uint64_t>(high), static_cast<std::uint64_t>(low));
  }

private:
  std::uint64_t Low = 0;
  std::uint64_t High = 0;
};

/// High and low 64 bits of a * b, portably.
inline void PortableMultiply64(
  std::uint64_t a, std::uint64_t b, std::uint64_t& high, std::uint64_t& low)
{
  const std::uint64_t a0 = a & 0xFFFFFFFFu, a1 = a >> 32;
  const std::uint64_t b0 = b & 0xFFFFFFFFu, b1 = b >> 32;
  const std::uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
  const std::uint64_t middle = (p00 >> 32) + (p01 & 0xFFFFFFFFu) + (p10 & 0xFFFFFFFFu);
  low = (middle << 32) | (p00 & 0xFFFFFFFFu);
  high = p11 + (p01 >> 32) + (p10 >> 32) + (middle >> 32);
}

#if defined(__SIZEOF_INT128__) && !defined(MCX_PORTABLE_WIDE_INTEGER)
using UInt128 = unsigned __int128;

inline double ToDouble(UInt128 value)
{
  return static_cast<double>(value);
}
inline UInt128 UInt128FromDouble(double value)
{
  return value >= 1.0 ? static_cast<UInt128>(value) : UInt128(0);
}
inline void Multiply64(std::uint64_t a, std::uint64_t b, std::uint64_t& high, std::uint64_t& low)
{
  const UInt128 product = static_cast<UInt128>(a) * b;
  high = static_cast<std::uint64_t>(product >> 64);
  low = static_cast<std::uint64_t>(product);
}
inline std::uint64_t LowHalf(UInt128 value)
{
  return static_cast<std::uint64_t>(value);
}
inline std::uint64_t HighHalf(UInt128 value)
{
  return static_cast<std::uint64_t>(value >> 64);
}
#else
using UInt128 = PortableUInt128;

inline double ToDouble(const UInt128& value)
{
  return static_cast<double>(value);
}
inline UInt128 UInt128FromDouble(double value)
{
  return PortableUInt128::FromDouble(value);
}
inline void Multiply64(std::uint64_t a, std::uint64_t b, std::uint64_t& high, std::uint64_t& low)
{
  PortableMultiply64(a, b, high, low);
}
inline std::uint64_t LowHalf(const UInt128& value)
{
  return value.LowHalf();
}
inline std::uint64_t HighHalf(const UInt128& value)
{
  return value.HighHalf();
}
#endif

} // namespace mcx

#endif
