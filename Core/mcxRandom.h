// Counter-based pseudo-random numbers: sample k of a run draws from a stream
// that depends only on (seed, k), so results do not depend on how samples
// are split among threads.
#ifndef mcxRandom_h
#define mcxRandom_h

#include "mcxWideInteger.h"

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

/// The per-run part of a stream's start, computed once per run.
inline std::uint64_t SeedKey(std::uint64_t seed)
{
  return Mix64(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull);
}

/// Stream k of a run is the wyrand sequence (Wang Yi, public domain; passes
/// BigCrush and PractRand) started at seedKey + (k + 1) * G, G odd: one
/// 64x64->128 multiply per draw. Draw j of stream k hashes
/// seedKey + (k + 1) G + j A; two draws coincide only if (k - k') G = +-A
/// mod 2^64, i.e. for one stream distance far beyond 2^63.
class CounterRandom
{
public:
  CounterRandom(std::uint64_t seedKey, std::uint64_t counter)
    : State(seedKey + (counter + 1) * 0x9E3779B97F4A7C15ull)
  {
  }

  std::uint64_t Next()
  {
    this->State += 0xA0761D6478BD642Full;
    std::uint64_t high, low;
    Multiply64(this->State, this->State ^ 0xE7037ED1A0B428DBull, high, low);
    return high ^ low;
  }

  /// Uniform in (0, 1], 53 random bits.
  double NextOpenClosed() { return static_cast<double>((this->Next() >> 11) + 1) * 0x1.0p-53; }

private:
  std::uint64_t State;
};

} // namespace mcx

#endif
