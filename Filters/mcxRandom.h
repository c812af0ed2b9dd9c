// Counter-based pseudo-random numbers: sample k of a run draws from a stream
// that depends only on (seed, k), so results do not depend on how samples
// are split among threads.
#ifndef mcxRandom_h
#define mcxRandom_h

#include <cstdint>

namespace mcx
{

/// SplitMix64 finaliser (Steele, Lea, Flood 2014): a bijective 64-bit mixer.
inline std::uint64_t Mix64(std::uint64_t z)
{
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

class CounterRandom
{
public:
  CounterRandom(std::uint64_t seed, std::uint64_t counter)
    : State(Mix64(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) ^ Mix64(counter + 1))
  {
  }

  std::uint64_t Next()
  {
    this->State += 0x9E3779B97F4A7C15ull;
    return Mix64(this->State);
  }

  /// Uniform in (0, 1], 53 random bits.
  double NextOpenClosed() { return static_cast<double>((this->Next() >> 11) + 1) * 0x1.0p-53; }

  /// Two uniforms in [0, 1), 32 random bits each, from one draw.
  void NextPair(double& a, double& b)
  {
    const std::uint64_t r = this->Next();
    a = static_cast<double>(r >> 32) * 0x1.0p-32;
    b = static_cast<double>(r & 0xFFFFFFFFull) * 0x1.0p-32;
  }

private:
  std::uint64_t State;
};

} // namespace mcx

#endif
