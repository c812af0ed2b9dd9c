// What the per-format header checks (mcx*HeaderCheck.cxx) share: bounds,
// sizes without overflow, the "truncated" and "more than deflate can hold"
// messages, and the text headers of MetaImage ("key = value") and NRRD
// ("key: value") with the data files they name. Plain C++; stays inside IO/.
#ifndef mcxHeaderCheckPrivate_h
#define mcxHeaderCheckPrivate_h

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace mcxio
{
namespace check
{
using Bytes = unsigned long long;

// Headers are text of bounded length: a line or header longer than these is
// not one of ours.
const std::size_t LargestHeader = 1 << 20;
const long long LargestSide = 1LL << 31;      // voxels along one axis
const long long LargestPatternFiles = 100000; // files a name pattern or list may name

std::string Lower(std::string text);
std::string Trim(const std::string& text);
bool EndsWith(const std::string& text, const std::string& suffix); // any case
Bytes FileSize(const std::string& path);

/// False (error set) unless path is a regular file: a FIFO, a device or a
/// socket would block a reader or feed it without end ("/dev/zero").
/// what names the file in the message ("the data file 'x'"); empty for
/// the file being checked itself.
bool RegularFile(const std::string& path, const std::string& what, std::string& error);
std::string Dimensions(const std::vector<long long>& dims); // "512x512x300"

/// dims' product times elementBytes, without overflow; false (error set)
/// for a side below 1 or above LargestSide, or a product beyond 2^63.
bool Product(
  const std::vector<long long>& dims, Bytes elementBytes, Bytes& bytes, std::string& error);

/// Raw data must be all there; compressed data within deflate's ratio.
bool CheckAvailable(Bytes claimed, Bytes available, bool compressed,
  const std::vector<long long>& dims, std::string& error);

/// Whitespace-separated integers, all of text; false for none.
bool ParseIntegers(const std::string& text, std::vector<long long>& values);

struct TextHeader
{
  std::map<std::string, std::string> Fields; // keys in lower case
  Bytes End = 0;                             // where the data of an attached header begin
};

/// MetaImage: lines up to and including ElementDataFile; NRRD: lines up to
/// the first blank line (comments '#' skipped, the magic line first).
bool ReadTextHeader(const std::string& path, bool nrrd, TextHeader& header, std::string& error);

/// A data file named relative to its header's folder.
std::string Beside(const std::string& header, const std::string& name);

/// The files of a printf pattern ("name%03d.raw first last step"), at most
/// LargestPatternFiles of them, each of which must exist.
bool PatternFiles(const std::string& header, const std::string& spec,
  std::vector<std::string>& files, std::string& error);

/// The data file field of a header's fields: NRRD spells it two ways.
std::string DataFileField(std::map<std::string, std::string>& fields, bool nrrd);

/// The bytes of voxel data a text header's data field gives: after the
/// header itself (data empty), in the files of a pattern, or in one data
/// file beside the header; a list is refused with listRefusal.
bool AvailableData(const std::string& path, const TextHeader& header, const std::string& data,
  const char* listRefusal, Bytes& available, std::string& error);

} // namespace check
} // namespace mcxio

#endif
