#include "mcxTransferFunctionSpec.h"

#include "vtkMCXAttenuationFunction.h"
#include "vtkPiecewiseFunction.h"

#include "vtkNew.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace mcxapp
{

const char* TransferFunctionPresetHelp()
{
  return "raw (g = value - minimum: density above the darkest voxel), "
         "bone (CT in HU: 0 below 150 HU, rising to 1 at 700 HU and above), "
         "soft-tissue (CT in HU: 1 from -50 to 150 HU, 0 below -200 and above 300), "
         "mu or mu=MU_WATER (CT in HU to linear attenuation, mu = MU_WATER (1 + HU/1000) per world "
         "unit, "
         "0 at air; default MU_WATER 0.02 per mm, water at about 70 keV; read as HU even where no "
         "value "
         "is at or below -500, with a warning)";
}

namespace
{
// Whether tf has a point at `value` with another weight than `weight`
// (AddPoint would silently replace it).
bool HasOtherPointAt(vtkPiecewiseFunction* tf, double value, double weight)
{
  for (int i = 0; i < tf->GetSize(); ++i)
  {
    double node[4];
    tf->GetNodeValue(i, node);
    if (node[0] == value && node[1] != weight)
    {
      return true;
    }
  }
  return false;
}
}

vtkSmartPointer<vtkPiecewiseFunction> MakeTransferFunction(
  const std::string& spec, const double dataRange[2], std::string& error)
{
  auto tf = vtkSmartPointer<vtkPiecewiseFunction>::New();
  tf->ClampingOn();
  if (spec == "raw")
  {
    tf->AddPoint(dataRange[0], 0.0);
    tf->AddPoint(
      dataRange[1] > dataRange[0] ? dataRange[1] : dataRange[0] + 1, dataRange[1] - dataRange[0]);
    return tf;
  }
  if (spec == "bone")
  {
    tf->AddPoint(150, 0);
    tf->AddPoint(700, 1);
    return tf;
  }
  if (spec == "soft-tissue")
  {
    tf->AddPoint(-200, 0);
    tf->AddPoint(-50, 1);
    tf->AddPoint(150, 1);
    tf->AddPoint(300, 0);
    return tf;
  }
  if (IsAttenuationSpec(spec))
  {
    vtkNew<vtkMCXAttenuationFunction> mu;
    if (spec != "mu")
    {
      char* end = nullptr;
      const std::string text = spec.substr(3);
      const double water = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || !std::isfinite(water) || !(water > 0))
      {
        error =
          "bad --tf '" + spec + "' (expected mu=MU_WATER with a positive number, e.g. mu=0.02)";
        return nullptr;
      }
      mu->SetWaterAttenuation(water);
    }
    // Exact over the whole data range (and at least the usual CT range).
    mu->SetHounsfieldRange(std::min(-1024.0, dataRange[0]), std::max(3071.0, dataRange[1]));
    mu->FillTransferFunction(tf);
    return tf;
  }
  std::stringstream items(spec);
  std::string item;
  int count = 0;
  while (std::getline(items, item, ','))
  {
    const std::size_t colon = item.find(':');
    char* end1 = nullptr;
    char* end2 = nullptr;
    const std::string valueText = item.substr(0, colon);
    const std::string weightText = colon == std::string::npos ? "" : item.substr(colon + 1);
    const double value = std::strtod(valueText.c_str(), &end1);
    const double weight = std::strtod(weightText.c_str(), &end2);
    if (colon == std::string::npos || valueText.empty() || weightText.empty() || *end1 != '\0' ||
      *end2 != '\0' || !std::isfinite(value) || !std::isfinite(weight))
    {
      error = "bad --tf point '" + item +
        "' (expected value:weight with finite numbers, or a preset: raw, bone, soft-tissue, mu)";
      return nullptr;
    }
    if (HasOtherPointAt(tf, value, weight))
    {
      error = "bad --tf: density " + valueText +
        " is given twice with different weights (a step needs two densities, e.g. 999.9:0,1000:1)";
      return nullptr;
    }
    tf->AddPoint(value, weight);
    ++count;
  }
  if (count == 0)
  {
    error = "empty --tf";
    return nullptr;
  }
  return tf;
}

namespace
{
// Where the product of mu and the weight changes slope: the data range's
// ends, air, and the weight's points inside the range.
std::vector<double> ProductNodes(vtkPiecewiseFunction* weight, double air, const double range[2])
{
  std::vector<double> nodes = { range[0], range[1] };
  if (air > range[0] && air < range[1])
  {
    nodes.push_back(air);
  }
  for (int i = 0; weight && i < weight->GetSize(); ++i)
  {
    double node[4];
    weight->GetNodeValue(i, node);
    if (node[0] > range[0] && node[0] < range[1])
    {
      nodes.push_back(node[0]);
    }
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}
}

bool IsAttenuationSpec(const std::string& spec)
{
  return spec == "mu" || spec.rfind("mu=", 0) == 0;
}

double AirValueOf(const double dataRange[2])
{
  return dataRange[0] <= -500.0 ? -1000.0 : dataRange[0];
}

std::string NoAirNote(const double dataRange[2])
{
  if (AirValueOf(dataRange) == -1000.0)
  {
    return std::string();
  }
  std::ostringstream note;
  note << "the values " << dataRange[0] << " .. " << dataRange[1]
       << " hold no air (none at or below -500)";
  return note.str();
}

vtkSmartPointer<vtkPiecewiseFunction> MakeWeightedAttenuation(
  vtkPiecewiseFunction* weight, double water, double airValue, const double dataRange[2])
{
  const double shift = airValue + 1000.0; // value = HU + shift
  vtkNew<vtkPiecewiseFunction> mu;
  vtkNew<vtkMCXAttenuationFunction> attenuation;
  attenuation->SetWaterAttenuation(water);
  attenuation->SetHounsfieldRange(
    std::min(-1000.0, dataRange[0] - shift), std::max(-999.0, dataRange[1] - shift));
  attenuation->FillTransferFunction(mu);
  auto product = vtkSmartPointer<vtkPiecewiseFunction>::New();
  product->ClampingOn();
  const std::vector<double> nodes = ProductNodes(weight, -1000.0 + shift, dataRange);
  // Between nodes mu and the weight are linear, their product quadratic:
  // 16 chords hold it within 0.1 %.
  const int chords = nodes.size() > 1 ? 16 : 1;
  for (std::size_t n = 0; n < nodes.size(); ++n)
  {
    const double step = n + 1 < nodes.size() ? (nodes[n + 1] - nodes[n]) / chords : 0.0;
    for (int c = 0; c < (n + 1 < nodes.size() ? chords : 1); ++c)
    {
      const double value = nodes[n] + c * step;
      const double w = weight ? std::min(1.0, std::max(0.0, weight->GetValue(value))) : 1.0;
      product->AddPoint(value, mu->GetValue(value - shift) * w);
    }
  }
  return product;
}

} // namespace mcxapp
