// The automatic display window of an X-ray image: 0 to the 99.5th
// percentile of the positive means of its 4 x 4 pixel blocks. The blocks
// average out most of a coarse image's noise, which would otherwise push a
// high percentile up. The mapper's display and ParaView's projector share it.
#ifndef mcxAutomaticWindow_h
#define mcxAutomaticWindow_h

#include <algorithm>
#include <cstddef>
#include <vector>

namespace mcx
{

/// Sets window to the percentile for the width x height image whose pixel p
/// (rows of `width`) is pixel(p); false (window unchanged) when no block is
/// positive.
template <typename Pixel>
bool AutomaticWindow(const Pixel& pixel, int width, int height, double& window)
{
  std::vector<double> blocks;
  for (int by = 0; by < height; by += 4)
  {
    for (int bx = 0; bx < width; bx += 4)
    {
      double sum = 0;
      int n = 0;
      for (int y = by; y < std::min(height, by + 4); ++y)
      {
        for (int x = bx; x < std::min(width, bx + 4); ++x, ++n)
        {
          sum += pixel(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + x);
        }
      }
      if (sum > 0)
      {
        blocks.push_back(sum / n);
      }
    }
  }
  if (blocks.empty())
  {
    return false;
  }
  auto rank =
    blocks.begin() + static_cast<std::ptrdiff_t>(0.995 * static_cast<double>(blocks.size() - 1));
  std::nth_element(blocks.begin(), rank, blocks.end());
  window = *rank;
  return true;
}

} // namespace mcx

#endif
