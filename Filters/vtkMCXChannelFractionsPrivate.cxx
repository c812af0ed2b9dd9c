#include "vtkMCXChannelFractionsPrivate.h"

#include "mcxChannelSplit.h"
#include "vtkMCXIndexView.h"
#include "vtkMCXProjector.h"

#include "vtkPiecewiseFunction.h"

#include <sstream>

namespace mcx
{
std::string ChannelFractionTable(vtkMCXProjector* self, const IndexView& view,
  vtkPiecewiseFunction* tf, std::vector<std::uint64_t>& fractions)
{
  const int channels = self->GetNumberOfChannels();
  std::vector<vtkPiecewiseFunction*> functions(static_cast<std::size_t>(channels));
  for (int c = 0; c < channels; ++c)
  {
    functions[static_cast<std::size_t>(c)] = self->GetChannelFraction(c);
    if (!functions[static_cast<std::size_t>(c)])
    {
      return "channel " + std::to_string(c) + " has no fraction function (SetChannelFraction)";
    }
  }
  const std::vector<double> weights = view.EvaluateTransferFunction(tf);
  fractions.assign(static_cast<std::size_t>(view.NumberOfLevels) * channels, 0);
  std::vector<double> values(static_cast<std::size_t>(channels));
  for (std::int64_t l = 0; l < view.NumberOfLevels; ++l)
  {
    if (!(weights[static_cast<std::size_t>(l)] > 0.0))
    {
      continue; // never sampled
    }
    const double value = view.LevelValues[l];
    for (int c = 0; c < channels; ++c)
    {
      values[static_cast<std::size_t>(c)] = functions[static_cast<std::size_t>(c)]->GetValue(value);
    }
    if (!FixedFractions(
          values.data(), channels, fractions.data() + static_cast<std::size_t>(l) * channels))
    {
      std::ostringstream problem;
      problem << "at the data value " << value
              << ", which the transfer function weighs, the channel fractions are";
      for (double v : values)
      {
        problem << " " << v;
      }
      problem << " (each must be >= 0 and finite, and one > 0)";
      return problem.str();
    }
  }
  return std::string();
}
}
