// The helpers the per-format header checks share (mcxHeaderCheckPrivate.h):
// sizes and their messages, numbered data files, and the data runs a reader
// consumes, checked against their files.
#include "mcxHeaderCheckPrivate.h"

#include "mcxHeaderCheck.h"

#include "mcxByteSize.h"

#include "vtk_zlib.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <locale>
#include <sstream>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace mcxio
{
namespace check
{

std::string Lower(std::string text)
{
  std::transform(
    text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
  return text;
}

std::string Trim(const std::string& text)
{
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  const std::size_t last = text.find_last_not_of(" \t\r\n");
  return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
}

bool EndsWith(const std::string& text, const std::string& suffix)
{
  const std::string lower = Lower(text);
  return lower.size() >= suffix.size() &&
    lower.compare(lower.size() - suffix.size(), suffix.size(), suffix) == 0;
}

Bytes FileSize(const std::string& path)
{
  return static_cast<Bytes>(vtksys::SystemTools::FileLength(path));
}

bool RegularFile(const std::string& path, const std::string& what, std::string& error)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
  {
    error = (what.empty() ? std::string("it") : what) + " cannot be opened";
    return false;
  }
  if (!S_ISREG(info.st_mode))
  {
    error = (what.empty() ? std::string("it") : what) +
      " is not a regular file (a pipe, device or socket cannot be read as a volume)";
    return false;
  }
  return true;
}

std::string Dimensions(const std::vector<long long>& dims)
{
  std::string text;
  for (std::size_t a = 0; a < dims.size(); ++a)
  {
    text += (a ? "x" : "") + std::to_string(dims[a]);
  }
  return text;
}

// dims' product times elementBytes, without overflow; false (error set)
// for a side below 1 or above LargestSide, or a product beyond 2^63.
bool Product(
  const std::vector<long long>& dims, Bytes elementBytes, Bytes& bytes, std::string& error)
{
  if (dims.empty())
  {
    error = "the header gives no dimensions";
    return false;
  }
  double product = static_cast<double>(elementBytes);
  bytes = elementBytes;
  for (long long side : dims)
  {
    if (side < 1 || side > LargestSide)
    {
      error = "the header's dimensions " + Dimensions(dims) + " are not all between 1 and 2^31";
      return false;
    }
    product *= static_cast<double>(side);
    bytes *= static_cast<Bytes>(side);
  }
  if (elementBytes == 0 || product >= 9.2e18)
  {
    error = "the header's dimensions " + Dimensions(dims) + " overflow";
    return false;
  }
  return true;
}

// Raw data must be all there; compressed data within deflate's ratio.
bool CheckAvailable(Bytes claimed, Bytes available, bool compressed,
  const std::vector<long long>& dims, std::string& error)
{
  if (!compressed && available < claimed)
  {
    error = "truncated: the header claims " + Dimensions(dims) + " voxels (" +
      mcx::DescribeBytes(static_cast<double>(claimed)) + "), the file holds " +
      mcx::DescribeBytes(static_cast<double>(available)) + " of data";
    return false;
  }
  if (compressed && static_cast<double>(claimed) > LargestCompressionRatio * (available + 64.0))
  {
    error = "the header claims " + Dimensions(dims) + " voxels (" +
      mcx::DescribeBytes(static_cast<double>(claimed)) + ") from " +
      mcx::DescribeBytes(static_cast<double>(available)) +
      " of compressed data, more than deflate can hold";
    return false;
  }
  return true;
}

// A base64 digit's value; -1 for any other character.
static int Base64Value(char c)
{
  static const std::string digits =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const std::size_t at = c ? digits.find(c) : std::string::npos;
  return at == std::string::npos ? -1 : static_cast<int>(at);
}

bool DecodeBase64(const std::string& text, std::string& decoded)
{
  decoded.clear();
  for (std::size_t g = 0; g + 4 <= text.size(); g += 4)
  {
    unsigned int bits = 0;
    int valid = 0;
    for (int k = 0; k < 4; ++k)
    {
      const int v = Base64Value(text[g + k]);
      if (v < 0 && text[g + k] != '=')
      {
        return false;
      }
      valid += v >= 0 && valid == k ? 1 : 0;
      bits = (bits << 6) | static_cast<unsigned int>(v < 0 ? 0 : v);
    }
    for (int b = 0; b < valid - 1; ++b)
    {
      decoded += static_cast<char>((bits >> (16 - 8 * b)) & 0xff);
    }
  }
  return true;
}

bool ParseIntegers(const std::string& text, std::vector<long long>& values)
{
  std::istringstream in(text);
  long long v = 0;
  values.clear();
  while (in >> v)
  {
    values.push_back(v);
  }
  return in.eof() && !values.empty();
}

bool ParseFiniteNumbers(const std::string& text, std::vector<double>& values)
{
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  double v = 0;
  values.clear();
  while (in >> v)
  {
    if (!std::isfinite(v))
    {
      return false;
    }
    values.push_back(v);
  }
  return in.eof() && !values.empty();
}

bool FiniteNumbersOrNone(
  const std::string& name, const std::string& text, std::size_t count, std::string& error)
{
  std::vector<double> values;
  if (text.empty() || (ParseFiniteNumbers(text, values) && values.size() == count))
  {
    return true;
  }
  error =
    "the image's " + name + " '" + text + "' is not " + std::to_string(count) + " finite numbers";
  return false;
}

bool ReadHead(const std::string& path, std::string& text, std::string& error)
{
  if (!RegularFile(path, std::string(), error))
  {
    return false;
  }
  // At most LargestHeader + 1 bytes, whatever the lines (one huge line included).
  std::ifstream file(path, std::ios::binary);
  text.assign(static_cast<std::size_t>(std::min<Bytes>(FileSize(path), LargestHeader + 1)), '\0');
  file.read(&text[0], static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(std::max<std::streamsize>(file.gcount(), 0)));
  if (!file && !file.eof())
  {
    error = "it cannot be read";
    return false;
  }
  return true;
}

// A data file named relative to its header's folder.
std::string Beside(const std::string& header, const std::string& name)
{
  return vtksys::SystemTools::CollapseFullPath(
    name, vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::CollapseFullPath(header)));
}

// A printf pattern with exactly one integer conversion: %d, %Nd or %0Nd
// (N at most two digits) and no other '%'.
bool IsNumberPattern(const std::string& pattern)
{
  const std::size_t at = pattern.find('%');
  if (at == std::string::npos || pattern.find('%', at + 1) != std::string::npos)
  {
    return false;
  }
  std::size_t i = at + 1;
  if (i < pattern.size() && pattern[i] == '0')
  {
    ++i;
  }
  const std::size_t digits = i;
  while (
    i < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[i])) && i - digits < 2)
  {
    ++i;
  }
  return i < pattern.size() && pattern[i] == 'd';
}

bool ExistingDataFile(
  const std::string& header, const std::string& name, std::string& file, std::string& error)
{
  file = Beside(header, name);
  struct stat info;
  if (::stat(file.c_str(), &info) != 0)
  {
    const int reason = errno;
    error = "the data file '" + file + "' " +
      (reason == ENOENT ? std::string("is missing")
                        : "cannot be opened (" + std::string(std::strerror(reason)) + ")");
    return false;
  }
  if (!RegularFile(file, "the data file '" + file + "'", error))
  {
    return false;
  }
  if (::access(file.c_str(), R_OK) != 0)
  {
    error = "the data file '" + file + "' cannot be read (" + std::strerror(errno) + ")";
    return false;
  }
  return true;
}

bool NumberedFiles(const std::string& header, const std::string& pattern, long long first,
  long long last, long long step, std::vector<std::string>& files, std::string& error)
{
  // Numbers within int (what %d prints), so that the count cannot overflow.
  const bool small = first >= INT_MIN && first <= INT_MAX && last >= INT_MIN && last <= INT_MAX &&
    step >= 1 && step <= INT_MAX;
  const long long count = small && last >= first ? (last - first) / step + 1 : 0;
  if (count < 1 || count > LargestPatternFiles || !IsNumberPattern(pattern))
  {
    error = "the file-name pattern '" + pattern + "' from " + std::to_string(first) + " to " +
      std::to_string(last) + " by " + std::to_string(step) +
      " is not a bounded list of numbered files";
    return false;
  }
  for (long long i = 0; i < count; ++i)
  {
    char name[4096];
    std::snprintf(name, sizeof(name), pattern.c_str(), static_cast<int>(first + i * step));
    std::string file;
    if (!ExistingDataFile(header, name, file, error))
    {
      return false;
    }
    files.push_back(file);
  }
  return true;
}

namespace
{
std::string Quoted(const std::string& file)
{
  return "the data in '" + file + "'";
}

// Inflates run's source as a stream and counts what comes out, stopping at
// run.Needed: zlib's own buffers (about 44 KiB) and two of 64 KiB, whatever
// the volume.
bool CheckInflated(const DataRun& run, std::ifstream& in, std::string& error)
{
  z_stream stream{};
  if (inflateInit2(&stream, run.Encoding == DataRun::Gzip ? 15 + 16 : 15 + 32) != Z_OK)
  {
    error = "zlib cannot start inflating";
    return false;
  }
  std::vector<unsigned char> input(1 << 16), output(1 << 16);
  Bytes left = run.Source ? run.Source : ~0ULL, produced = 0, members = 0;
  int status = Z_OK;
  bool nextMember = false; // after a gzip member: what follows may be none
  while (produced < run.Needed && status == Z_OK)
  {
    if (stream.avail_in == 0)
    {
      in.read(reinterpret_cast<char*>(input.data()),
        static_cast<std::streamsize>(std::min<Bytes>(left, input.size())));
      stream.avail_in = static_cast<uInt>(in.gcount());
      stream.next_in = input.data();
      left -= stream.avail_in;
      if (stream.avail_in == 0)
      {
        break; // the source ends
      }
    }
    stream.next_out = output.data();
    stream.avail_out = static_cast<uInt>(std::min<Bytes>(output.size(), run.Needed - produced));
    status = inflate(&stream, Z_NO_FLUSH);
    produced = members + stream.total_out;
    if (status == Z_BUF_ERROR)
    {
      status = Z_OK; // no progress possible until more input comes
    }
    if (status == Z_DATA_ERROR && nextMember && stream.total_out == 0)
    {
      status = Z_STREAM_END; // no next member: the data end (gzread's reading)
    }
    else if (status == Z_STREAM_END && run.Encoding == DataRun::Gzip && produced < run.Needed)
    {
      // gzread goes on to a next gzip member.
      members = produced;
      nextMember = true;
      status = inflateReset(&stream);
    }
  }
  const std::string message = stream.msg ? stream.msg : "";
  inflateEnd(&stream);
  if (status != Z_OK && status != Z_STREAM_END)
  {
    error = Quoted(run.File) + " do not inflate (" +
      (message.empty() ? std::string("zlib error ") + std::to_string(status) : message) + ")";
    return false;
  }
  if (produced < run.Needed)
  {
    error = "truncated: " + Quoted(run.File) + " inflate to " +
      mcx::DescribeBytes(static_cast<double>(produced)) + ", the header claims " +
      mcx::DescribeBytes(static_cast<double>(run.Needed));
    return false;
  }
  return true;
}

// A number as a text reader (operator>> into a number) takes it whole: signs,
// digits, a point and an exponent; no "nan" or "inf", which it refuses.
bool IsNumber(const std::string& token)
{
  if (token.find_first_not_of("0123456789+-.eE") != std::string::npos)
  {
    return false;
  }
  char* end = nullptr;
  std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size();
}

// Counts the whitespace-separated numbers from in's position, up to
// run.Needed; a token longer than any number (64 characters) or not a
// number is an error.
bool CheckText(const DataRun& run, std::ifstream& in, std::string& error)
{
  const std::size_t longest = 64;
  Bytes values = 0;
  std::string token;
  std::streambuf* buffer = in.rdbuf();
  while (values < run.Needed)
  {
    const int c = buffer->sbumpc();
    const bool end = c == std::char_traits<char>::eof();
    if (end || std::isspace(c))
    {
      if (!token.empty())
      {
        if (!IsNumber(token))
        {
          error = Quoted(run.File) + " hold '" + token + "' after " + std::to_string(values) +
            " values, not a number";
          return false;
        }
        ++values;
        token.clear();
      }
      if (end)
      {
        break;
      }
      continue;
    }
    if (token.size() == longest)
    {
      error = Quoted(run.File) + " hold a token of more than " + std::to_string(longest) +
        " characters after " + std::to_string(values) + " values, not a number";
      return false;
    }
    token += static_cast<char>(c);
  }
  if (values < run.Needed)
  {
    error = "truncated: " + Quoted(run.File) + " hold " + std::to_string(values) +
      " values as text, the header claims " + std::to_string(run.Needed);
    return false;
  }
  return true;
}
}

bool CheckDataRun(const DataRun& run, std::string& error)
{
  if (!RegularFile(run.File, "the data file '" + run.File + "'", error))
  {
    return false;
  }
  const Bytes size = FileSize(run.File);
  if (run.Encoding == DataRun::Raw && !run.Dims.empty())
  {
    return CheckAvailable(
      run.Needed, size > run.Offset ? size - run.Offset : 0, false, run.Dims, error);
  }
  if (run.Encoding == DataRun::Raw)
  {
    if (size < run.Offset || size - run.Offset < run.Needed)
    {
      error = "truncated: the header claims " +
        mcx::DescribeBytes(static_cast<double>(run.Needed)) + " of voxels in '" + run.File +
        "', which holds " +
        mcx::DescribeBytes(static_cast<double>(size > run.Offset ? size - run.Offset : 0)) +
        " of data";
      return false;
    }
    return true;
  }
  if (run.Encoding != DataRun::Ascii &&
    static_cast<double>(run.Needed) > LargestCompressionRatio *
        (static_cast<double>(size > run.Offset ? size - run.Offset : 0) + 64.0))
  {
    error = "the header claims " + mcx::DescribeBytes(static_cast<double>(run.Needed)) +
      " of voxels from the " +
      mcx::DescribeBytes(static_cast<double>(size > run.Offset ? size - run.Offset : 0)) +
      " of compressed data in '" + run.File + "', more than deflate can hold";
    return false;
  }
  std::ifstream in(run.File, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(run.Offset));
  if (!in || run.Offset > size)
  {
    error = Quoted(run.File) + " cannot be read from byte " + std::to_string(run.Offset);
    return false;
  }
  return run.Encoding == DataRun::Ascii ? CheckText(run, in, error) : CheckInflated(run, in, error);
}

} // namespace check
} // namespace mcxio
