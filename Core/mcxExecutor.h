// The threading the core runs on, handed in by its caller: the core itself
// starts no threads and sees no threading library. An executor provides
//
//   template <typename F> void For(std::int64_t begin, std::int64_t end,
//                                  std::int64_t grain, const F& f) const;
//     calls f(b, e) on disjoint subranges that cover [begin, end), possibly
//     from several threads at once;
//   template <typename T> using ThreadLocal = ...;
//     one T per thread, made on first use by Local() and visited by a
//     range-for over the container.
//
// The VTK modules hand in mcx::SMPExecutor (vtkSMPTools, in
// Filters/vtkMCXSMPExecutor.h); SerialExecutor runs everything in the
// calling thread. Every kernel that takes an executor gives the same result
// for any executor and any number of threads.
#ifndef mcxExecutor_h
#define mcxExecutor_h

#include <cstdint>

namespace mcx
{

struct SerialExecutor
{
  template <typename F>
  void For(std::int64_t begin, std::int64_t end, std::int64_t, const F& f) const
  {
    if (begin < end)
    {
      f(begin, end);
    }
  }

  template <typename T>
  class ThreadLocal
  {
  public:
    T& Local() { return this->Value; }
    T* begin() { return &this->Value; }
    T* end() { return &this->Value + 1; }

  private:
    T Value{};
  };
};

} // namespace mcx

#endif
