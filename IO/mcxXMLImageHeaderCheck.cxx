// The header check of VTK XML image data (.vti): the whole XML header (up
// to <AppendedData>, read in chunks, at most LargestXMLHeader of markup and
// comments), every piece's extent inside the WholeExtent, and every array
// of every piece (point, cell and field data) against the data it names:
// raw or base64 appended data, inline base64 ("binary") or ascii, each
// uncompressed (its size word) or compressed (its block table). The claimed
// bytes are what vtkXMLImageDataReader allocates: every array of the first
// piece over the whole extent, and the field data (mcxHeaderCheck.h).
#include "mcxHeaderCheck.h"
#include "mcxHeaderCheckPrivate.h"

#include "mcxByteSize.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace mcxio
{
using namespace check;

namespace
{
// Markup, comments and text outside inline data; VTK's parser (expat)
// holds a comment or an attribute whole in memory.
const Bytes LargestXMLHeader = 16ULL << 20;

// One element of the header: its start tag, its parent's name and, for an
// array with inline data, where its text lies in the file.
struct Element
{
  std::string Name;
  std::string Tag;
  std::string Parent;
  int Piece = -1; // the <Piece> it lies in (-1: none)
  Bytes ContentBegin = 0;
  Bytes ContentEnd = 0;
};

struct Header
{
  std::vector<Element> Elements;
  bool Appended = false;
  Bytes AppendedStart = 0; // the first byte after the marker character
};

std::string Attribute(const std::string& tag, const std::string& name)
{
  // After whitespace: "offset" must not match inside "RangeOffset".
  for (std::size_t at = tag.find(name + "=\""); at != std::string::npos;
       at = tag.find(name + "=\"", at + 1))
  {
    if (at > 0 &&
      (tag[at - 1] == ' ' || tag[at - 1] == '\t' || tag[at - 1] == '\n' || tag[at - 1] == '\r'))
    {
      const std::size_t begin = at + name.size() + 2;
      const std::size_t end = tag.find('"', begin);
      return end == std::string::npos ? std::string() : tag.substr(begin, end - begin);
    }
  }
  return std::string();
}

// Bytes one value takes in memory; a string array holds std::strings.
Bytes XMLElementBytes(const std::string& type)
{
  static const std::map<std::string, Bytes> sizes = { { "Int8", 1 }, { "UInt8", 1 }, { "Int16", 2 },
    { "UInt16", 2 }, { "Int32", 4 }, { "UInt32", 4 }, { "Int64", 8 }, { "UInt64", 8 },
    { "Float32", 4 }, { "Float64", 8 }, { "Char", 1 }, { "String", 32 }, { "Bit", 1 } };
  const auto found = sizes.find(type);
  return found == sizes.end() ? 0 : found->second;
}

// DataArray, or Array (string arrays).
bool IsArray(const std::string& name)
{
  return name == "DataArray" || name == "Array";
}

// The file's elements up to <AppendedData>, scanned in chunks: a comment or
// markup beyond LargestXMLHeader is refused before it is held.
bool ReadHeader(const std::string& path, Header& header, std::string& error)
{
  std::ifstream in(path, std::ios::binary);
  std::vector<char> chunk(1 << 16);
  enum State
  {
    Text,
    Markup,
    Comment,
    Marker
  } state = Text;
  std::string markup;
  char quote = 0;
  Bytes markupStart = 0, held = 0, pos = 0;
  std::vector<std::size_t> open; // indices of the open elements
  int pieces = 0;
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0)
  {
    const std::size_t n = static_cast<std::size_t>(in.gcount());
    for (std::size_t i = 0; i < n; ++i, ++pos)
    {
      const char c = chunk[i];
      const bool inArray = !open.empty() && IsArray(header.Elements[open.back()].Name);
      if (state == Marker)
      {
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n')
        {
          continue;
        }
        header.AppendedStart = pos + 1; // the marker ('_') skipped, whatever it is
        return true;
      }
      if (state == Text)
      {
        if (c == '<')
        {
          state = Markup;
          markup = "<";
          quote = 0;
          markupStart = pos;
        }
        else if (!inArray && ++held > LargestXMLHeader)
        {
          break;
        }
        continue;
      }
      if (++held > LargestXMLHeader)
      {
        break;
      }
      if (state == Comment)
      {
        markup = markup.substr(markup.size() > 2 ? markup.size() - 2 : 0) + c;
        if (markup == "-->")
        {
          state = Text;
        }
        continue;
      }
      markup += c;
      if (markup == "<!--")
      {
        state = Comment;
        markup.clear();
        continue;
      }
      if (quote)
      {
        quote = c == quote ? 0 : quote;
        continue;
      }
      if ((c == '"' || c == '\'') && markup[1] != '!' && markup[1] != '?')
      {
        quote = c;
        continue;
      }
      if (c != '>')
      {
        continue;
      }
      state = Text;
      if (markup[1] == '!' || markup[1] == '?')
      {
        continue; // a declaration or processing instruction
      }
      // An array's inline data end at its first child (InformationKey) or its end tag.
      if (!open.empty() && IsArray(header.Elements[open.back()].Name) &&
        header.Elements[open.back()].ContentEnd == 0)
      {
        header.Elements[open.back()].ContentEnd = markupStart;
      }
      if (markup[1] == '/')
      {
        if (!open.empty())
        {
          open.pop_back();
        }
        continue;
      }
      Element element;
      const std::size_t nameEnd = markup.find_first_of(" \t\r\n/>", 1);
      element.Name = markup.substr(1, nameEnd - 1);
      element.Tag = markup;
      element.Parent = open.empty() ? std::string() : header.Elements[open.back()].Name;
      element.Piece = element.Name == "Piece" ? pieces++ : pieces - 1;
      element.ContentBegin = pos + 1;
      header.Elements.push_back(element);
      if (element.Name == "AppendedData")
      {
        header.Appended = true;
        state = Marker;
        continue;
      }
      if (markup[markup.size() - 2] != '/')
      {
        open.push_back(header.Elements.size() - 1);
      }
    }
    if (held > LargestXMLHeader)
    {
      error = "the image's XML header (markup and comments) is longer than 16 MiB";
      return false;
    }
  }
  if (header.Appended)
  {
    error = "the image's appended data have no marker";
    return false;
  }
  return true;
}

// Reads the decoded bytes [at, at + count) of an array's data: raw bytes
// of the file from start, or the base64 text there decoded (VTK's base64
// streams start on a four-character group).
class DataReader
{
public:
  DataReader(std::ifstream& in, Bytes start, Bytes end, bool base64)
    : In(in)
    , Start(start)
    , End(end)
    , Base64(base64)
  {
  }

  // Decoded bytes from start to end (base64: what the text could hold).
  Bytes Available() const
  {
    const Bytes chars = this->End > this->Start ? this->End - this->Start : 0;
    return this->Base64 ? chars / 4 * 3 : chars;
  }

  bool Read(Bytes at, Bytes count, std::string& out)
  {
    out.clear();
    if (!this->Base64)
    {
      return this->Raw(this->Start + at, count, out);
    }
    const Bytes first = at / 3, last = (at + count + 2) / 3;
    std::string text;
    if (!this->Raw(this->Start + first * 4, (last - first) * 4, text))
    {
      return false;
    }
    std::string decoded;
    if (!DecodeBase64(text, decoded))
    {
      return false;
    }
    const std::size_t skip = static_cast<std::size_t>(at - first * 3);
    if (decoded.size() < skip + count)
    {
      return false;
    }
    out = decoded.substr(skip, static_cast<std::size_t>(count));
    return true;
  }

private:
  bool Raw(Bytes at, Bytes count, std::string& out)
  {
    if (at + count > this->End)
    {
      return false;
    }
    out.assign(static_cast<std::size_t>(count), '\0');
    this->In.clear();
    this->In.seekg(static_cast<std::streamoff>(at));
    this->In.read(&out[0], static_cast<std::streamsize>(count));
    return this->In.gcount() == static_cast<std::streamsize>(count);
  }

  std::ifstream& In;
  Bytes Start, End;
  bool Base64;
};

// The file's header words and byte order (VTKFile's attributes).
struct Layout
{
  int Word = 4;
  bool BigEndian = false;
  bool Compressed = false;
};

Bytes Word(const std::string& bytes, std::size_t at, const Layout& layout)
{
  Bytes word = 0;
  for (int b = 0; b < layout.Word; ++b)
  {
    const unsigned char byte = static_cast<unsigned char>(bytes[at + b]);
    word |= static_cast<Bytes>(byte) << (8 * (layout.BigEndian ? layout.Word - 1 - b : b));
  }
  return word;
}

// One array's binary data (raw or base64): its size word (uncompressed)
// or block table (compressed: block count, block size, last block size,
// each block's compressed size) must describe exactly the bytes the array
// needs (any for a string array, needed 0) and lie in the data.
bool CheckBinaryData(
  DataReader& data, const Layout& layout, Bytes needed, const std::string& name, std::string& error)
{
  const Bytes w = static_cast<Bytes>(layout.Word);
  std::string bytes;
  const std::string what = "the image's array '" + name + "'";
  if (!layout.Compressed)
  {
    if (!data.Read(0, w, bytes))
    {
      error = "truncated: " + what + " ends before its size word";
      return false;
    }
    const Bytes size = Word(bytes, 0, layout);
    const Bytes holds = data.Available() - std::min(data.Available(), w);
    if ((needed && size != needed) || size > holds)
    {
      error = what + " holds " + mcx::DescribeBytes(double(size)) + " (the file " +
        mcx::DescribeBytes(double(holds)) + ") where its extent needs " +
        mcx::DescribeBytes(double(needed));
      return false;
    }
    return true;
  }
  if (!data.Read(0, 3 * w, bytes))
  {
    error = "truncated: the compressed data of " + what + " end inside their block table";
    return false;
  }
  const Bytes blocks = Word(bytes, 0, layout), blockSize = Word(bytes, w, layout),
              lastSize = Word(bytes, 2 * w, layout);
  if (blocks > data.Available() / w)
  {
    error = "truncated: the compressed data of " + what + " end inside their block table";
    return false;
  }
  const double total = blocks == 0 ? 0.0
                                   : static_cast<double>(blocks - 1) * blockSize +
      static_cast<double>(lastSize ? lastSize : blockSize);
  if ((needed && total != static_cast<double>(needed)) || (lastSize > blockSize))
  {
    error = "the compressed blocks of " + what + " hold " + mcx::DescribeBytes(total) +
      " where its extent needs " + mcx::DescribeBytes(double(needed));
    return false;
  }
  // The block sizes, a chunk at a time: a table as long as the file is read,
  // never held whole.
  Bytes compressedTotal = 0;
  const Bytes perChunk = 8192;
  for (Bytes b = 0; b < blocks; b += perChunk)
  {
    const Bytes count = std::min(perChunk, blocks - b);
    if (!data.Read((3 + b) * w, count * w, bytes))
    {
      error = "truncated: the compressed data of " + what + " end inside their block table";
      return false;
    }
    for (Bytes k = 0; k < count; ++k)
    {
      compressedTotal += std::min(Word(bytes, static_cast<std::size_t>(k * w), layout), 1ULL << 62);
    }
  }
  // A base64 table is a stream of its own: the blocks start on the next group.
  const Bytes table = (3 + blocks) * w;
  const Bytes after = data.Available() - std::min(data.Available(), table);
  if (compressedTotal > after)
  {
    error = "truncated: the compressed blocks of " + what + " need " +
      mcx::DescribeBytes(double(compressedTotal)) + ", the file holds " +
      mcx::DescribeBytes(double(after));
    return false;
  }
  if (total > LargestCompressionRatio * (double(compressedTotal) + 64.0))
  {
    error = "the compressed blocks of " + what + " claim " + mcx::DescribeBytes(total) + " from " +
      mcx::DescribeBytes(double(compressedTotal)) + ", more than deflate can hold";
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

// A piece's point dimensions: its Extent must lie in the whole extent
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

// Cells of an image of these point dimensions (a flat axis has one layer).
std::vector<long long> CellDimensions(const std::vector<long long>& points)
{
  std::vector<long long> cells(3);
  for (int a = 0; a < 3; ++a)
  {
    cells[a] = points[a] < 1 ? 0 : std::max(points[a] - 1, 1LL);
  }
  return cells;
}

bool Empty(const std::vector<long long>& dims)
{
  return dims[0] < 1 || dims[1] < 1 || dims[2] < 1;
}

// An array: its value's size, and its values' bytes as its piece holds
// them (values, by dims: tuples x components) and as the reader allocates
// them (allocated: over the whole extent).
bool ArrayBytes(const Element& array, const std::vector<long long>& pieceDims,
  const std::vector<long long>& wholeDims, Bytes& value, Bytes& needed, Bytes& allocated,
  std::string& error)
{
  const std::string name = Attribute(array.Tag, "Name");
  const std::string type = Attribute(array.Tag, "type");
  const Bytes element = XMLElementBytes(type);
  if (element == 0)
  {
    error = "the image's data type '" + type + "' is unknown";
    return false;
  }
  std::vector<long long> components;
  const bool field = array.Parent != "PointData" && array.Parent != "CellData";
  const long long most = field ? LargestSide : 64;
  if (ParseIntegers(Attribute(array.Tag, "NumberOfComponents"), components) &&
    (components.size() != 1 || components[0] < 1 || components[0] > most))
  {
    error = "the image's NumberOfComponents of '" + name + "' is not 1 to " +
      (field ? std::string("2^31") : std::string("64"));
    return false;
  }
  value = element * static_cast<Bytes>(components.empty() ? 1 : components[0]);
  needed = allocated = 0;
  if (field)
  {
    std::vector<long long> tuples;
    if (!ParseIntegers(Attribute(array.Tag, "NumberOfTuples"), tuples))
    {
      return true; // none allocated
    }
    if (tuples.size() != 1 || tuples[0] < 0 || tuples[0] > LargestSide)
    {
      error = "the image's NumberOfTuples of '" + name + "' is not 0 to 2^31";
      return false;
    }
    needed = allocated = value * static_cast<Bytes>(tuples[0]);
    return true;
  }
  const bool cells = array.Parent == "CellData";
  const std::vector<long long> piece = cells ? CellDimensions(pieceDims) : pieceDims;
  const std::vector<long long> whole = cells ? CellDimensions(wholeDims) : wholeDims;
  return (Empty(piece) || Product(piece, value, needed, error)) &&
    (Empty(whole) || Product(whole, value, allocated, error));
}

// One array's data against what it needs; binary marks raw binary data.
bool CheckArrayData(std::ifstream& in, const Header& header, const Element& array,
  const Layout& layout, const std::string& encoding, Bytes fileSize, Bytes value, Bytes needed,
  bool& binary, std::string& error)
{
  const std::string format = Attribute(array.Tag, "format");
  const std::string name = Attribute(array.Tag, "Name");
  const bool strings = Attribute(array.Tag, "type") == "String";
  binary = false;
  if (format == "appended")
  {
    std::vector<long long> offset;
    if (!header.Appended || !ParseIntegers(Attribute(array.Tag, "offset"), offset) ||
      offset.size() != 1 || offset[0] < 0)
    {
      error = "the image's array '" + name + "' names appended data the file does not have";
      return false;
    }
    binary = encoding != "base64";
    DataReader data(in, header.AppendedStart + static_cast<Bytes>(offset[0]), fileSize, !binary);
    return CheckBinaryData(data, layout, strings ? 0 : needed, name, error);
  }
  // Inline data: the text between the tags, whitespace before it skipped.
  Bytes begin = array.ContentBegin;
  const Bytes end = std::max(array.ContentEnd, begin);
  if (format == "binary")
  {
    std::string lead;
    DataReader text(in, begin, end, false);
    while (begin < end && text.Read(begin - array.ContentBegin, 1, lead) &&
      (lead[0] == ' ' || lead[0] == '\t' || lead[0] == '\r' || lead[0] == '\n'))
    {
      ++begin;
    }
    DataReader data(in, begin, end, true);
    return CheckBinaryData(data, layout, strings ? 0 : needed, name, error);
  }
  // ascii: each value takes a character and a separator.
  const Bytes values =
    value ? needed / value * (value / XMLElementBytes(Attribute(array.Tag, "type"))) : 0;
  if (!strings && values > 0 && 2 * values - 1 > end - begin)
  {
    error = "truncated: the image's ascii array '" + name + "' needs " + std::to_string(values) +
      " values, its text holds at most " + std::to_string((end - begin + 1) / 2);
    return false;
  }
  return true;
}
}

bool CheckXMLImageHeader(const std::string& path, Bytes& claimed, std::string& error)
{
  if (!RegularFile(path, std::string(), error))
  {
    return false;
  }
  Header header;
  if (!ReadHeader(path, header, error))
  {
    return false;
  }
  const Element* file = nullptr;
  const Element* image = nullptr;
  for (const Element& e : header.Elements)
  {
    file = !file && e.Name == "VTKFile" ? &e : file;
    image = !image && e.Name == "ImageData" ? &e : image;
  }
  if (!file || !image)
  {
    error = "not a VTK XML image (no <VTKFile> with <ImageData>)";
    return false;
  }
  // The placement: the reader takes one it cannot parse as its default.
  const std::string& tag = image->Tag;
  if (!FiniteNumbersOrNone("Origin", Attribute(tag, "Origin"), 3, error) ||
    !FiniteNumbersOrNone("Spacing", Attribute(tag, "Spacing"), 3, error) ||
    !FiniteNumbersOrNone("Direction", Attribute(tag, "Direction"), 9, error))
  {
    return false;
  }
  Layout layout;
  layout.Word = Attribute(file->Tag, "header_type") == "UInt64" ? 8 : 4;
  layout.BigEndian = Attribute(file->Tag, "byte_order") == "BigEndian";
  layout.Compressed = !Attribute(file->Tag, "compressor").empty();
  std::string encoding = "raw";
  for (const Element& e : header.Elements)
  {
    encoding = e.Name == "AppendedData" ? Attribute(e.Tag, "encoding") : encoding;
  }
  std::vector<long long> whole;
  const std::string wholeText = Attribute(image->Tag, "WholeExtent");
  if (!ParseExtent(wholeText, whole))
  {
    error = "the image's WholeExtent '" + wholeText + "' is not six integers within 2^31";
    return false;
  }
  std::vector<long long> dims(3);
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = whole[2 * a + 1] - whole[2 * a] + 1;
  }
  Bytes wholePoints = 0;
  if (!Product(dims, 1, wholePoints, error))
  {
    return false;
  }
  // Each piece's extent; each array against its data. The reader allocates
  // the first piece's arrays over the whole extent, and the field data.
  std::vector<std::vector<long long>> pieceDims;
  for (const Element& e : header.Elements)
  {
    if (e.Name == "Piece")
    {
      pieceDims.emplace_back();
      if (!PieceDimensions(Attribute(e.Tag, "Extent"), whole, wholeText, pieceDims.back(), error))
      {
        return false;
      }
    }
  }
  const Bytes fileSize = FileSize(path);
  // First what the reader allocates, against what the file can hold; then
  // each array's data (the cheap refusal first).
  std::vector<const Element*> arrays;
  std::set<std::string> names; // two of one name: the reader frees one while it reads it
  for (const Element& e : header.Elements)
  {
    const bool field = e.Parent == "FieldData";
    const std::string name = Attribute(e.Tag, "Name");
    if (IsArray(e.Name) && (field || e.Parent == "PointData" || e.Parent == "CellData") &&
      (field || (e.Piece >= 0 && e.Piece < static_cast<int>(pieceDims.size()))))
    {
      if (!name.empty() && !names.insert(std::to_string(e.Piece) + e.Parent + "/" + name).second)
      {
        error = "the image's " + e.Parent + " holds two arrays named '" + name + "'";
        return false;
      }
      arrays.push_back(&e); // outside any piece: the reader reads none of it
    }
  }
  claimed = 0;
  double total = 0.0;
  bool allBinary = !layout.Compressed;
  std::vector<Bytes> values, needs;
  for (const Element* e : arrays)
  {
    const bool field = e->Parent == "FieldData";
    Bytes value = 1, needed = 0, allocated = 0;
    if (!ArrayBytes(*e, field ? dims : pieceDims[e->Piece], dims, value, needed, allocated, error))
    {
      return false;
    }
    values.push_back(value);
    needs.push_back(needed);
    allBinary = allBinary &&
      (needed == 0 ||
        (Attribute(e->Tag, "format") == "appended" && header.Appended && encoding != "base64"));
    if (field || e->Piece == 0)
    {
      claimed += allocated;
      total += static_cast<double>(allocated);
    }
  }
  if (total >= 9.2e18)
  {
    error = "the image's arrays overflow";
    return false;
  }
  // Raw data must all be there; base64, text and compression make the data
  // larger or smaller: bound those by what deflate can hold.
  if (!CheckAvailable(claimed, fileSize, !allBinary, dims, error))
  {
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  for (std::size_t a = 0; a < arrays.size(); ++a)
  {
    bool binary = false;
    if (needs[a] > 0 &&
      !CheckArrayData(
        in, header, *arrays[a], layout, encoding, fileSize, values[a], needs[a], binary, error))
    {
      return false;
    }
  }
  return true;
}

} // namespace mcxio
