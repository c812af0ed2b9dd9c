// The channel fractions of a projector's split deposit (vtkMCXProjector::
// SetNumberOfChannels), per level of the index it samples: the fraction
// functions evaluated at each level's value, in the fixed point that splits
// an increment exactly (mcxChannelSplit.h).
#ifndef vtkMCXChannelFractionsPrivate_h
#define vtkMCXChannelFractionsPrivate_h

#include <cstdint>
#include <string>
#include <vector>

class vtkMCXProjector;
class vtkPiecewiseFunction;

namespace mcx
{
struct IndexView;

/// Fills `fractions` with GetNumberOfChannels() fixed-point fractions per
/// level of `view` (levels the TF `tf` gives no weight get all 0, never
/// sampled); returns "" or why the channels cannot be made (a missing
/// function, a negative fraction, or none positive where the TF weighs).
std::string ChannelFractionTable(vtkMCXProjector* self, const IndexView& view,
  vtkPiecewiseFunction* tf, std::vector<std::uint64_t>& fractions);
}

#endif
