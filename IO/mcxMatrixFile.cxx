#include "mcxMatrixFile.h"

#include "mcxPrintableText.h"

#include "vtk_jsoncpp.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <sys/stat.h>

namespace mcxio
{

namespace
{
const std::size_t MaximumBytes = std::size_t(64) << 20;
const std::size_t MaximumNumberLength = 64;

std::string Quoted(const std::string& path)
{
  return "'" + mcx::PrintableText(path) + "'";
}

bool ParseNumber(const std::string& text, double& value)
{
  if (text.empty() || text.size() > MaximumNumberLength)
  {
    return false;
  }
  errno = 0;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno == 0 && std::isfinite(value);
}

std::string ReadText(const std::string& path, const std::string& text, std::size_t limit,
  std::vector<MatrixPose>& poses)
{
  std::vector<double> numbers;
  std::string token;
  std::size_t line = 1;
  bool comment = false;
  for (std::size_t at = 0; at <= text.size(); ++at)
  {
    const char c = at < text.size() ? text[at] : '\n';
    if (comment && c != '\n')
    {
      continue;
    }
    if (c == '#' || c == '\n' || c == ' ' || c == '\t' || c == '\r' || c == ',')
    {
      if (!token.empty())
      {
        double value;
        if (!ParseNumber(token, value))
        {
          return "cannot read " + Quoted(path) + ": line " + std::to_string(line) + ": '" +
            mcx::PrintableText(token.substr(0, MaximumNumberLength)) + "' is not a finite number";
        }
        numbers.push_back(value);
        if (numbers.size() > 12 * limit)
        {
          return "cannot read " + Quoted(path) + ": more than " + std::to_string(limit) + " poses";
        }
      }
      token.clear();
      comment = c == '#';
      line += c == '\n' && at < text.size() ? 1 : 0;
      continue;
    }
    if (token.size() > MaximumNumberLength)
    {
      return "cannot read " + Quoted(path) + ": line " + std::to_string(line) +
        ": a number longer than " + std::to_string(MaximumNumberLength) + " characters";
    }
    token += c;
  }
  if (numbers.empty() || numbers.size() % 12 != 0)
  {
    return "cannot read " + Quoted(path) + ": " + std::to_string(numbers.size()) +
      " numbers, not a multiple of 12 (a 3x4 matrix per pose)";
  }
  for (std::size_t k = 0; k < numbers.size(); k += 12)
  {
    MatrixPose pose;
    std::copy(numbers.begin() + k, numbers.begin() + k + 12, pose.Matrix);
    poses.push_back(pose);
  }
  return std::string();
}

std::string ReadJSON(const std::string& path, const std::string& text, std::size_t limit,
  std::vector<MatrixPose>& poses)
{
  Json::CharReaderBuilder builder;
  builder["collectComments"] = false;
  builder["stackLimit"] = 64;
  Json::Value root;
  std::string errors;
  std::istringstream stream(text);
  if (!Json::parseFromStream(builder, stream, &root, &errors))
  {
    std::string first = errors.substr(0, errors.find('\n'));
    return "cannot read " + Quoted(path) + ": not valid JSON (" + mcx::PrintableText(first) + ")";
  }
  const std::string what = "cannot read " + Quoted(path) + ": ";
  if (!root.isObject() || !root["poses"].isArray() || root["poses"].empty())
  {
    return what + "no \"poses\" array (the JSON of mcxray render --output-geometry)";
  }
  const Json::Value& list = root["poses"];
  if (list.size() > limit)
  {
    return what + "more than " + std::to_string(limit) + " poses";
  }
  for (Json::ArrayIndex k = 0; k < list.size(); ++k)
  {
    const Json::Value& entry = list[k];
    const std::string pose = "pose " + std::to_string(k) + ": ";
    const Json::Value& P = entry["P"];
    if (!entry.isObject() || !P.isArray() || P.size() != 3)
    {
      return what + pose + "\"P\" must be 3 rows of 4 numbers";
    }
    MatrixPose out;
    for (Json::ArrayIndex r = 0; r < 3; ++r)
    {
      if (!P[r].isArray() || P[r].size() != 4)
      {
        return what + pose + "\"P\" must be 3 rows of 4 numbers";
      }
      for (Json::ArrayIndex c = 0; c < 4; ++c)
      {
        if (!P[r][c].isNumeric() || !std::isfinite(P[r][c].asDouble()))
        {
          return what + pose + "\"P\" holds a value that is not a finite number";
        }
        out.Matrix[4 * r + c] = P[r][c].asDouble();
      }
    }
    const Json::Value& size = entry["size"];
    if (!size.isNull())
    {
      if (!size.isArray() || size.size() != 2 || !size[0].isInt() || !size[1].isInt() ||
        size[0].asInt() < 1 || size[1].asInt() < 1 || size[0].asInt() > 65536 ||
        size[1].asInt() > 65536)
      {
        return what + pose + "\"size\" must be two whole numbers of pixels from 1 to 65536";
      }
      out.HasSize = true;
      out.Size[0] = size[0].asInt();
      out.Size[1] = size[1].asInt();
    }
    poses.push_back(out);
  }
  return std::string();
}
}

std::string ReadProjectionMatrices(
  const std::string& path, std::size_t limit, std::vector<MatrixPose>& poses)
{
  poses.clear();
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
  {
    return "cannot read " + Quoted(path) + ": " + std::strerror(errno);
  }
  if (!S_ISREG(info.st_mode))
  {
    return "cannot read " + Quoted(path) + ": not a regular file";
  }
  if (static_cast<std::size_t>(info.st_size) > MaximumBytes)
  {
    return "cannot read " + Quoted(path) + ": " + std::to_string(info.st_size) +
      " bytes, more than a file of matrices may have (64 MiB)";
  }
  std::ifstream file(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (!file && !file.eof())
  {
    return "cannot read " + Quoted(path);
  }
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  const std::string problem = first != std::string::npos && text[first] == '{'
    ? ReadJSON(path, text, limit, poses)
    : ReadText(path, text, limit, poses);
  if (!problem.empty())
  {
    poses.clear();
  }
  return problem;
}

} // namespace mcxio
