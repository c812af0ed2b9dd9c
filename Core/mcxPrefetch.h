// Cache prefetch hints, with no effect where the compiler offers none.
#ifndef mcxPrefetch_h
#define mcxPrefetch_h

namespace mcx
{

/// Hints that the cache line holding `address` is about to be written.
inline void PrefetchForWriting(const void* address)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(address, 1, 3);
#else
  (void)address;
#endif
}

/// Hints that the cache line holding `address` is about to be read.
inline void PrefetchForReading(const void* address)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(address, 0, 3);
#else
  (void)address;
#endif
}

/// PrefetchForReading in a loop that does nothing else (it only computes
/// the addresses): GCC drops such a loop as dead code, so this one also
/// tells the compiler that memory may change.
inline void PrefetchForReadingInALoop(const void* address)
{
  PrefetchForReading(address);
#if defined(__GNUC__) || defined(__clang__)
  asm volatile("" ::: "memory");
#endif
}

} // namespace mcx

#endif
