#include "vtkMCXPatientSpace.h"

#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkObjectFactory.h"

#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkMCXPatientSpace);

namespace
{
const char* const AxisName[3] = { "first", "second", "third" };

// Unit directions whose parallelepiped is thinner than this span no volume:
// the axes lie within about 0.06 degrees of one plane.
const double SmallestDeterminant = 1e-3;

std::string DescribeDirections(const double direction[9])
{
  for (int i = 0; i < 9; ++i)
  {
    if (!std::isfinite(direction[i]))
    {
      return "the direction matrix is not finite";
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    const double length = std::sqrt(direction[a] * direction[a] +
      direction[3 + a] * direction[3 + a] + direction[6 + a] * direction[6 + a]);
    if (std::abs(length - 1.0) > 1e-3)
    {
      std::ostringstream text;
      text << "the direction of the " << AxisName[a] << " axis is not a unit vector (length "
           << length << ")";
      return text.str();
    }
  }
  if (!(std::abs(vtkMatrix3x3::Determinant(direction)) >= SmallestDeterminant))
  {
    return "the direction matrix is singular: its axes span no volume";
  }
  return std::string();
}
}

std::string vtkMCXPatientSpace::SplitAxisSteps(
  const double steps[9], double spacing[3], double direction[9])
{
  for (int a = 0; a < 3; ++a)
  {
    const double x = steps[a], y = steps[3 + a], z = steps[6 + a];
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
    {
      return std::string("the ") + AxisName[a] + " axis's direction is not finite";
    }
    // Scaled first, so that neither 1e200 nor 1e-200 over- or underflows.
    const double largest = std::max(std::abs(x), std::max(std::abs(y), std::abs(z)));
    const double length = largest > 0 ? largest *
        std::sqrt((x / largest) * (x / largest) + (y / largest) * (y / largest) +
          (z / largest) * (z / largest))
                                      : 0.0;
    if (!(length > 0) || !std::isfinite(length))
    {
      return std::string("the ") + AxisName[a] + " axis's direction is a zero vector";
    }
    spacing[a] = length;
    for (int r = 0; r < 3; ++r)
    {
      direction[3 * r + a] = steps[3 * r + a] / length;
    }
  }
  return DescribeDirections(direction);
}

std::string vtkMCXPatientSpace::DescribeUnusableExtent(
  const double origin[3], const double spacing[3], const double direction[9], const int extent[6])
{
  if (!std::isfinite(origin[0]) || !std::isfinite(origin[1]) || !std::isfinite(origin[2]))
  {
    return "the origin is not finite";
  }
  const double largest = GetLargestCoordinate();
  for (int corner = 0; corner < 8; ++corner)
  {
    const double index[3] = { double(extent[(corner & 1) ? 1 : 0]),
      double(extent[(corner & 2) ? 3 : 2]), double(extent[(corner & 4) ? 5 : 4]) };
    for (int r = 0; r < 3; ++r)
    {
      double x = origin[r];
      for (int a = 0; a < 3; ++a)
      {
        x += direction[3 * r + a] * spacing[a] * index[a];
      }
      if (!(std::abs(x) <= largest))
      {
        std::ostringstream text;
        text << "the volume reaches " << x << " along world axis "
             << "xyz"[r] << ", beyond the largest coordinate, " << largest;
        return text.str();
      }
    }
  }
  return std::string();
}

std::string vtkMCXPatientSpace::PlaceAxisSteps(const double steps[9], const double origin[3],
  const int extent[6], double spacing[3], double direction[9])
{
  std::string problem = SplitAxisSteps(steps, spacing, direction);
  if (problem.empty())
  {
    problem = DescribeUnusableExtent(origin, spacing, direction, extent);
  }
  return problem.empty() ? problem : "the header's placement cannot be used: " + problem;
}

std::string vtkMCXPatientSpace::DescribeUnusablePlacement(vtkImageData* volume)
{
  if (!volume)
  {
    return "no volume";
  }
  const double* spacing = volume->GetSpacing();
  for (int a = 0; a < 3; ++a)
  {
    if (!(spacing[a] > 0) || !std::isfinite(spacing[a]))
    {
      std::ostringstream text;
      text << "the spacing along the " << AxisName[a] << " axis, " << spacing[a]
           << ", is not a positive number";
      return text.str();
    }
  }
  double direction[9];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      direction[3 * r + c] = volume->GetDirectionMatrix()->GetElement(r, c);
    }
  }
  std::string problem = DescribeDirections(direction);
  if (problem.empty())
  {
    problem = DescribeUnusableExtent(volume->GetOrigin(), spacing, direction, volume->GetExtent());
  }
  return problem;
}

void vtkMCXPatientSpace::FlipRightAnterior(double point[3])
{
  point[0] = -point[0];
  point[1] = -point[1];
}

void vtkMCXPatientSpace::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LargestCoordinate: " << GetLargestCoordinate() << "\n";
}
