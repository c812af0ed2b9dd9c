#include "mcxOptionValues.h"

#include "mcxFail.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace mcxapp
{

double ParseNumber(const std::string& text, const std::string& option)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value))
  {
    Fail("bad value '" + text + "' for " + option);
  }
  return value;
}

double ParsePositive(const std::string& text, const std::string& option)
{
  const double value = ParseNumber(text, option);
  if (!(value > 0))
  {
    Fail(option + " must be positive");
  }
  return value;
}

double ParseOpenUnitFraction(const std::string& text, const std::string& option)
{
  const double value = ParseNumber(text, option);
  if (!(value > 0 && value < 1))
  {
    Fail(option + " must lie in (0, 1)");
  }
  return value;
}

long long ParseInteger(
  const std::string& text, const std::string& option, long long minimum, long long maximum)
{
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || value < minimum || value > maximum)
  {
    Fail("bad value '" + text + "' for " + option + " (expected an integer " +
      (maximum == LLONG_MAX ? ">= " + std::to_string(minimum)
                            : "from " + std::to_string(minimum) + " to " + std::to_string(maximum)) +
      ")");
  }
  return value;
}

double ParseByteSize(const std::string& text, const std::string& option)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  const std::string suffix = end ? std::string(end) : std::string();
  const std::string units = "KMGT";
  const std::size_t unit = suffix.size() == 1 ? units.find(std::toupper(suffix[0])) : std::string::npos;
  if (text.empty() || end == text.c_str() || !std::isfinite(value) || !(value > 0) ||
    (!suffix.empty() && unit == std::string::npos) ||
    text.find_first_of("xXpP") != std::string::npos) // decimal only, no hexadecimal
  {
    Fail("bad value '" + text + "' for " + option + " (expected bytes, e.g. 512M or 8G)");
  }
  const double bytes = value * std::pow(1024.0, suffix.empty() ? 0.0 : static_cast<double>(unit + 1));
  if (bytes > std::ldexp(1.0, 60) || bytes < 1024.0 * 1024.0)
  {
    Fail(option + " must lie between 1M and 2^60 bytes");
  }
  return bytes;
}

std::vector<std::string> Split(const std::string& text, char separator)
{
  // Every part, empty ones too ("16x16x" has three parts, the last empty).
  std::vector<std::string> parts(1);
  for (const char c : text)
  {
    if (c == separator)
    {
      parts.emplace_back();
    }
    else
    {
      parts.back() += c;
    }
  }
  return parts;
}

void ParseSize(
  const std::string& text, const std::string& option, int smallest, int largest, int size[2])
{
  const std::vector<std::string> parts = Split(text, 'x');
  if (parts.size() != 2)
  {
    Fail("bad " + option + " '" + text + "' (expected WxH, e.g. 512x512)");
  }
  for (int k = 0; k < 2; ++k)
  {
    const long long side = ParseInteger(parts[k], option, smallest);
    if (side > largest)
    {
      Fail(option + " is limited to " + std::to_string(largest) + " pixels per side");
    }
    size[k] = static_cast<int>(side);
  }
}

std::vector<double> ParseNumberList(
  const std::string& text, std::size_t count, const std::string& what)
{
  std::vector<std::string> parts;
  std::string part;
  for (char c : text + " ")
  {
    if (c == ',' || std::isspace(static_cast<unsigned char>(c)))
    {
      if (!part.empty())
      {
        parts.push_back(part);
      }
      part.clear();
    }
    else
    {
      part += c;
    }
  }
  if (parts.size() != count)
  {
    Fail("bad " + what + " '" + text + "' (expected " + std::to_string(count) +
      " numbers separated by commas or spaces)");
  }
  std::vector<double> numbers;
  for (const std::string& number : parts)
  {
    numbers.push_back(ParseNumber(number, what));
  }
  return numbers;
}

void ParseTriple(const std::string& text, double out[3], const std::string& what)
{
  const std::vector<std::string> parts = Split(text, ',');
  if (parts.size() != 3)
  {
    Fail("bad " + what + " '" + text + "' (expected x,y,z)");
  }
  for (int a = 0; a < 3; ++a)
  {
    out[a] = ParseNumber(parts[a], what);
  }
}

} // namespace mcxapp
