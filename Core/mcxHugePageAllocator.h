// An allocator for arrays of hundreds of megabytes that are read or written
// at scattered places (a view order's ids, written through a million
// cursors, and its samples' reads a hundred voxels apart): on Linux it asks
// for transparent huge pages (madvise), whose 2 MB pages keep the
// addresses such a pass touches within the TLB's reach, where the system
// leaves huge pages to madvise (the default). Elsewhere, and for small
// arrays, it is the plain allocator.
#ifndef mcxHugePageAllocator_h
#define mcxHugePageAllocator_h

#include <cstddef>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mcx
{

template <typename T>
struct HugePageAllocator
{
  using value_type = T;

  /// Arrays from this size on are aligned to and advised for huge pages.
  static constexpr std::size_t HugeFrom = std::size_t(32) << 20;
  static constexpr std::size_t HugePage = std::size_t(2) << 20;

  HugePageAllocator() = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept
  {
  }

  T* allocate(std::size_t n)
  {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T))
    {
      throw std::bad_array_new_length();
    }
    const std::size_t bytes = n * sizeof(T);
#if defined(__linux__)
    if (bytes >= HugeFrom)
    {
      void* memory = nullptr;
      const std::size_t rounded = (bytes + HugePage - 1) / HugePage * HugePage;
      if (posix_memalign(&memory, HugePage, rounded) != 0)
      {
        throw std::bad_alloc();
      }
      madvise(memory, rounded, MADV_HUGEPAGE); // advice only: fine if refused
      return static_cast<T*>(memory);
    }
#endif
    return std::allocator<T>().allocate(n);
  }

  /// resize() leaves trivial elements uninitialized: the arrays are written
  /// whole before they are read, and a pass of zeros first touched every
  /// page in one thread (a fifth of a view order's sort). A construction
  /// with a value, vector(n, 0), is std::allocator_traits' own.
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new (static_cast<void*>(p)) U;
  }

  void deallocate(T* p, std::size_t n) noexcept
  {
#if defined(__linux__)
    if (n * sizeof(T) >= HugeFrom)
    {
      std::free(p);
      return;
    }
#endif
    std::allocator<T>().deallocate(p, n);
  }

  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const noexcept
  {
    return true;
  }
  template <typename U>
  bool operator!=(const HugePageAllocator<U>&) const noexcept
  {
    return false;
  }
};

} // namespace mcx

#endif
