// The header check of VTK XML image data (.vti): the WholeExtent and the
// first piece's extent within 2^31 and inside it, the first point array's
// type and components, and raw appended data (its size word or compressed
// block table) against the bytes the file holds (mcxHeaderCheck.h).
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include "mcxByteSize.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace mcxio
{
using namespace check;

namespace
{
std::string Attribute(const std::string& tag, const std::string& name)
{
  const std::size_t at = tag.find(" " + name + "=\"");
  if (at == std::string::npos)
  {
    return std::string();
  }
  const std::size_t begin = at + name.size() + 3;
  const std::size_t end = tag.find('"', begin);
  return end == std::string::npos ? std::string() : tag.substr(begin, end - begin);
}

Bytes XMLElementBytes(const std::string& type)
{
  static const std::map<std::string, Bytes> sizes = { { "Int8", 1 }, { "UInt8", 1 }, { "Int16", 2 },
    { "UInt16", 2 }, { "Int32", 4 }, { "UInt32", 4 }, { "Int64", 8 }, { "UInt64", 8 },
    { "Float32", 4 }, { "Float64", 8 } };
  const auto found = sizes.find(type);
  return found == sizes.end() ? 0 : found->second;
}

// One header word of raw appended data (UInt32 or UInt64, in the file's
// byte order); false past the end of the file.
bool ReadWord(std::ifstream& in, Bytes at, int size, bool bigEndian, Bytes& word)
{
  unsigned char raw[8] = { 0 };
  in.clear();
  in.seekg(static_cast<std::streamoff>(at));
  in.read(reinterpret_cast<char*>(raw), size);
  if (in.gcount() != size)
  {
    return false;
  }
  word = 0;
  for (int b = 0; b < size; ++b)
  {
    word |= static_cast<Bytes>(raw[bigEndian ? size - 1 - b : b]) << (8 * b);
  }
  return true;
}

// The first array's raw appended data: its size word (uncompressed) or its
// block table (compressed: block count, block size, last block size, then
// each block's compressed size) must describe exactly the claimed bytes and
// fit in the file; a lying table sends VTK's reader into a loop over
// billions of blocks or past its buffers.
bool CheckAppendedData(const std::string& path, const std::string& head, const std::string& tag,
  Bytes claimed, std::string& error)
{
  const std::size_t appended = head.find("<AppendedData");
  std::vector<long long> offset;
  if (Attribute(tag, "format") != "appended" || appended == std::string::npos ||
    Attribute(head.substr(appended, head.find('>', appended) - appended), "encoding") != "raw" ||
    !ParseIntegers(Attribute(tag, "offset"), offset) || offset.size() != 1 || offset[0] < 0)
  {
    return true; // base64 or inline data: bounded by the ratio check alone
  }
  // As VTK reads it: after the tag, whitespace, then one marker character
  // (normally '_'), whatever it is.
  const std::size_t underscore = head.find_first_not_of(" \t\r\n", head.find('>', appended) + 1);
  if (underscore == std::string::npos)
  {
    error = "the image's appended data have no marker";
    return false;
  }
  const std::string file = head.substr(0, head.find('>'));
  const int word = Attribute(file, "header_type") == "UInt64" ? 8 : 4;
  const bool bigEndian = Attribute(file, "byte_order") == "BigEndian";
  const bool compressed = !Attribute(file, "compressor").empty();
  const Bytes size = FileSize(path);
  const Bytes start = underscore + 1 + static_cast<Bytes>(offset[0]);
  std::ifstream in(path, std::ios::binary);
  Bytes first = 0;
  if (!ReadWord(in, start, word, bigEndian, first))
  {
    error = "truncated: the image's appended data end before their header";
    return false;
  }
  if (!compressed)
  {
    if (first != claimed || size - std::min(size, start + word) < claimed)
    {
      error = "the image's appended data hold " + mcx::DescribeBytes(double(first)) +
        " (the file " + mcx::DescribeBytes(double(size - std::min(size, start + word))) +
        ") where its extent needs " + mcx::DescribeBytes(double(claimed));
      return false;
    }
    return true;
  }
  Bytes blockSize = 0, lastSize = 0;
  const Bytes blocks = first;
  if (!ReadWord(in, start + word, word, bigEndian, blockSize) ||
    !ReadWord(in, start + 2 * word, word, bigEndian, lastSize) || blocks > size / word)
  {
    error = "truncated: the image's compressed data end inside their block table";
    return false;
  }
  const double total = blocks == 0 ? 0.0
                                   : static_cast<double>(blocks - 1) * blockSize +
      static_cast<double>(lastSize ? lastSize : blockSize);
  if (total != static_cast<double>(claimed))
  {
    error = "the image's compressed blocks hold " + mcx::DescribeBytes(total) +
      " where its extent needs " + mcx::DescribeBytes(double(claimed));
    return false;
  }
  Bytes compressedTotal = 0;
  for (Bytes b = 0; b < blocks; ++b)
  {
    Bytes block = 0;
    if (!ReadWord(in, start + (3 + b) * word, word, bigEndian, block) || block > size)
    {
      error = "truncated: the image's compressed data end inside their block table";
      return false;
    }
    compressedTotal += block;
  }
  if (compressedTotal > size - std::min(size, start + (3 + blocks) * word))
  {
    error = "truncated: the image's compressed blocks need " +
      mcx::DescribeBytes(double(compressedTotal)) + ", the file holds " +
      mcx::DescribeBytes(double(size - std::min(size, start + (3 + blocks) * word)));
    return false;
  }
  return true;
}

// An extent attribute's six integers, each side from -2^31 to 2^31.
bool ParseExtent(const std::string& text, std::vector<long long>& extent)
{
  if (!ParseIntegers(text, extent) || extent.size() != 6)
  {
    return false;
  }
  for (long long e : extent)
  {
    if (e < -LargestSide || e > LargestSide)
    {
      return false;
    }
  }
  return true;
}

// The first piece's dimensions: its Extent must lie in the whole extent
// (whole, as wholeText says it); without a piece extent, the whole one's.
bool PieceDimensions(const std::string& pieceText, const std::vector<long long>& whole,
  const std::string& wholeText, std::vector<long long>& pieceDims, std::string& error)
{
  pieceDims.assign(3, 0);
  if (pieceText.empty())
  {
    for (int a = 0; a < 3; ++a)
    {
      pieceDims[a] = whole[2 * a + 1] - whole[2 * a] + 1;
    }
    return true;
  }
  std::vector<long long> piece;
  bool inside = ParseExtent(pieceText, piece);
  for (int a = 0; inside && a < 3; ++a)
  {
    pieceDims[a] = piece[2 * a + 1] - piece[2 * a] + 1;
    inside =
      piece[2 * a] >= whole[2 * a] && piece[2 * a + 1] <= whole[2 * a + 1] && pieceDims[a] >= 0;
  }
  if (!inside)
  {
    error =
      "the piece extent '" + pieceText + "' does not lie in the WholeExtent '" + wholeText + "'";
    return false;
  }
  return true;
}

// The tag of the first array of the point data after from ("" when there
// is none) and the bytes of one of its values (1 without an array).
bool FirstPointArray(
  const std::string& head, std::size_t from, std::string& tag, Bytes& value, std::string& error)
{
  const std::size_t pointData = head.find("<PointData", from);
  const std::size_t pointDataEnd =
    head.find("</PointData", pointData == std::string::npos ? 0 : pointData);
  std::size_t array =
    pointData == std::string::npos ? std::string::npos : head.find("<DataArray", pointData);
  if (array != std::string::npos && pointDataEnd != std::string::npos && array > pointDataEnd)
  {
    array = std::string::npos;
  }
  tag =
    array == std::string::npos ? std::string() : head.substr(array, head.find('>', array) - array);
  value = 1;
  if (tag.empty())
  {
    return true;
  }
  const Bytes element = XMLElementBytes(Attribute(tag, "type"));
  std::vector<long long> components;
  if (element == 0)
  {
    error = "the image's data type '" + Attribute(tag, "type") + "' is unknown";
    return false;
  }
  if (ParseIntegers(Attribute(tag, "NumberOfComponents"), components) &&
    (components.size() != 1 || components[0] < 1 || components[0] > 64))
  {
    error = "the image's NumberOfComponents is not 1 to 64";
    return false;
  }
  value = element * static_cast<Bytes>(components.empty() ? 1 : components[0]);
  return true;
}
}

bool CheckXMLImageHeader(const std::string& path, Bytes& claimed, std::string& error)
{
  if (!RegularFile(path, std::string(), error))
  {
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  std::string head(65536, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  auto tagAt = [&](std::size_t at)
  { return at == std::string::npos ? std::string() : head.substr(at, head.find('>', at) - at); };
  const std::size_t image = head.find("<ImageData");
  if (head.find("<VTKFile") == std::string::npos || image == std::string::npos)
  {
    error = "not a VTK XML image (no <VTKFile> with <ImageData>)";
    return false;
  }
  std::vector<long long> whole;
  const std::string wholeText = Attribute(tagAt(image), "WholeExtent");
  if (!ParseExtent(wholeText, whole))
  {
    error = "the image's WholeExtent '" + wholeText + "' is not six integers within 2^31";
    return false;
  }
  std::vector<long long> dims(3), pieceDims;
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = whole[2 * a + 1] - whole[2 * a] + 1;
  }
  // The first piece's extent lies in the whole extent; its point data's
  // first array is what the header checks size (field data may come first).
  const std::size_t pieceAt = head.find("<Piece", image);
  std::string tag;
  Bytes value = 1;
  if (!PieceDimensions(Attribute(tagAt(pieceAt), "Extent"), whole, wholeText, pieceDims, error) ||
    !FirstPointArray(head, pieceAt == std::string::npos ? image : pieceAt, tag, value, error) ||
    !Product(dims, value, claimed, error))
  {
    return false;
  }
  // Raw appended data must all be there; base64, text and compression make
  // the data larger or smaller: bound those by what deflate can hold.
  const std::string file = head.substr(0, head.find('>'));
  const bool raw = Attribute(file, "compressor").empty() &&
    head.find("encoding=\"raw\"") != std::string::npos &&
    head.find("format=\"ascii\"") == std::string::npos &&
    head.find("format=\"binary\"") == std::string::npos;
  Bytes pieceBytes = 0;
  const bool emptyPiece = pieceDims[0] < 1 || pieceDims[1] < 1 || pieceDims[2] < 1;
  return CheckAvailable(claimed, FileSize(path), !raw, dims, error) &&
    (tag.empty() || emptyPiece ||
      (Product(pieceDims, value, pieceBytes, error) &&
        CheckAppendedData(path, head, tag, pieceBytes, error)));
}

} // namespace mcxio
