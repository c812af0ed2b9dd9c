// What the per-format header checks (mcx*HeaderCheck.cxx) share: bounds,
// sizes without overflow, the "truncated" and "more than deflate can hold"
// messages, numbered data files, and the data runs a reader will consume,
// each checked against its file (raw, compressed or text). Plain C++; stays
// inside IO/.
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

/// The bytes of text's complete groups of 4 base64 digits ('=' pads a
/// group's end); false for any other character.
bool DecodeBase64(const std::string& text, std::string& decoded);

/// Whitespace-separated integers, all of text; false for none.
bool ParseIntegers(const std::string& text, std::vector<long long>& values);
/// Whitespace-separated finite numbers, all of text; false for none, or
/// for any token that is not one ("nan", "inf", "1e999", "abc").
bool ParseFiniteNumbers(const std::string& text, std::vector<double>& values);
/// False (error set: "the image's NAME 'TEXT' is not COUNT finite
/// numbers") unless text is empty or COUNT finite numbers: a reader that
/// takes a value it cannot parse as its default would misplace the volume.
bool FiniteNumbersOrNone(
  const std::string& name, const std::string& text, std::size_t count, std::string& error);

/// A data file named relative to its header's folder.
std::string Beside(const std::string& header, const std::string& name);

/// A printf pattern with exactly one integer conversion (%d, %Nd, %0Nd).
bool IsNumberPattern(const std::string& pattern);

/// The files pattern names for first, first + step, ... up to last (step
/// at least 1, at most LargestPatternFiles of them), beside header; each
/// must exist and be a regular file (error set otherwise).
bool NumberedFiles(const std::string& header, const std::string& pattern, long long first,
  long long last, long long step, std::vector<std::string>& files, std::string& error);

/// One run of voxel data as a reader consumes it: from Offset in File,
/// Needed bytes (Raw), Needed bytes once inflated from at most Source bytes
/// (0: to the end; Zlib takes zlib or gzip, as MetaIO's inflateInit2(47);
/// Gzip gzip alone, as zlib's gzread), or Needed whitespace-separated numbers
/// (Ascii).
struct DataRun
{
  enum Kind
  {
    Raw,
    Zlib,
    Gzip,
    Ascii
  };
  std::string File;
  Kind Encoding = Raw;
  Bytes Offset = 0;
  Bytes Source = 0;
  Bytes Needed = 0;
  std::vector<long long> Dims; // the volume's, when one run holds it all (for the message)
};

/// False (error set) unless run's file holds what the reader will consume:
/// raw bytes by size; compressed data inflated as a stream (64 KiB buffers,
/// stopped once Needed bytes came out, so that time, not memory, grows with
/// the volume: the reader inflates them again, the check costs about as
/// much); text counted token by token, each a number of at most 64
/// characters, stopped at Needed.
bool CheckDataRun(const DataRun& run, std::string& error);

/// The data file named name beside header, which must exist and be a
/// regular file (error set otherwise).
bool ExistingDataFile(
  const std::string& header, const std::string& name, std::string& file, std::string& error);

/// The voxel data of a MetaImage (mcxMetaImageHeaderCheck.cxx) or NRRD
/// (mcxNrrdHeaderCheck.cxx) header as VTK's reader consumes them, parsed
/// the way that reader parses the header: runs in the order read, the
/// voxels' bytes claimed (claimed) and their dimensions. False (error set)
/// for a header the reader would misread or that the checks refuse.
bool MetaImageRuns(const std::string& path, std::vector<DataRun>& runs, Bytes& claimed,
  std::vector<long long>& dims, std::string& error);
bool NrrdRuns(const std::string& path, std::vector<DataRun>& runs, Bytes& claimed,
  std::vector<long long>& dims, std::string& error);

/// Reads at most LargestHeader + 1 bytes of path (a regular file); error
/// set and false when it is none or cannot be read.
bool ReadHead(const std::string& path, std::string& text, std::string& error);

} // namespace check
} // namespace mcxio

#endif
