// Runs a long parallel loop in batches so that the calling algorithm can
// report progress and honour an abort request between them (VTK's progress
// events must come from the thread that runs the pipeline).
#ifndef vtkMCXBatchedForPrivate_h
#define vtkMCXBatchedForPrivate_h

#include "vtkAlgorithm.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cstdint>

namespace mcx
{

/// Calls work(begin, end) over [0, total) in parallel; progress goes from
/// progressBegin to progressEnd. Returns false when the algorithm was asked
/// to abort (the work is then incomplete).
template <typename Work>
bool BatchedFor(vtkAlgorithm* algorithm, std::uint64_t total, double progressBegin,
  double progressEnd, const Work& work, std::uint64_t grain = std::uint64_t(1) << 15)
{
  const std::uint64_t batch = std::max<std::uint64_t>(grain * 16, total / 50 + 1);
  for (std::uint64_t begin = 0; begin < total; begin += batch)
  {
    const std::uint64_t end = std::min(total, begin + batch);
    vtkSMPTools::For(static_cast<vtkIdType>(begin), static_cast<vtkIdType>(end),
      static_cast<vtkIdType>(grain),
      [&](vtkIdType b, vtkIdType e)
      { work(static_cast<std::uint64_t>(b), static_cast<std::uint64_t>(e)); });
    algorithm->UpdateProgress(
      progressBegin + (progressEnd - progressBegin) * static_cast<double>(end) / total);
    if (algorithm->GetAbortExecute())
    {
      return false;
    }
  }
  return true;
}

} // namespace mcx

#endif
