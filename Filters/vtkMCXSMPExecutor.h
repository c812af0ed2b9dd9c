// The executor (see Core/mcxExecutor.h) through which the VTK modules hand
// vtkSMPTools threads to the plain C++ core.
#ifndef vtkMCXSMPExecutor_h
#define vtkMCXSMPExecutor_h

#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <cstdint>

namespace mcx
{

struct SMPExecutor
{
  template <typename F>
  void For(std::int64_t begin, std::int64_t end, std::int64_t grain, const F& f) const
  {
    vtkSMPTools::For(static_cast<vtkIdType>(begin), static_cast<vtkIdType>(end),
      static_cast<vtkIdType>(grain),
      [&](vtkIdType b, vtkIdType e)
      { f(static_cast<std::int64_t>(b), static_cast<std::int64_t>(e)); });
  }

  template <typename T>
  using ThreadLocal = vtkSMPThreadLocal<T>;
};

} // namespace mcx

#endif
