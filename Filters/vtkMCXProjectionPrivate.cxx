#include "vtkMCXProjectionPrivate.h"

#include <sstream>

namespace mcx
{
std::string RandomPartsOf(
  const Accumulator& accumulator, const mcx::DepositSettings& settings, double footprintReach)
{
  if (accumulator.ErrorFallsAsInverseM())
  {
    return std::string();
  }
  if (settings.Mode == mcx::Deposit::Point)
  {
    return "the point deposit draws each kernel offset at random";
  }
  std::ostringstream parts;
  parts << "voxels reach more than FootprintReach (" << footprintReach
        << ") pixels here, so their footprints are split with a random part";
  return parts.str();
}

void CollectSums(Accumulator& accumulator, Projection& projection)
{
  const std::size_t pixels = accumulator.NumberOfPixels();
  projection.Sums.assign(2 * pixels, mcx::FixedSum(0));
  projection.ChannelSums.assign(static_cast<std::size_t>(accumulator.GetChannels()),
    std::vector<mcx::FixedSum>(2 * pixels, mcx::FixedSum(0)));
  std::vector<mcx::FixedSum*> channels;
  for (std::vector<mcx::FixedSum>& channel : projection.ChannelSums)
  {
    channels.push_back(channel.data());
  }
  mcx::FixedSum* const* channelSums = channels.empty() ? nullptr : channels.data();
  if (accumulator.IsControlled())
  {
    projection.OnceSums.assign(2 * pixels, mcx::FixedSum(0));
    accumulator.Collect(projection.Sums.data(), projection.Sums.data() + pixels,
      projection.OnceSums.data(), projection.OnceSums.data() + pixels, channelSums);
    return;
  }
  accumulator.Collect(
    projection.Sums.data(), projection.Sums.data() + pixels, nullptr, nullptr, channelSums);
}
}
