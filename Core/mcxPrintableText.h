// Text from a file or a command line made safe to print in one line of
// error: a hostile header's bytes (control characters that move a
// terminal's cursor, a newline that would split the line, bytes that are no
// UTF-8 and that Python cannot decode into a str) become \xNN escapes, and
// a megabyte-long name is cut in its middle. Valid UTF-8 (a patient's name
// in a path) stays as it is.
#ifndef mcxPrintableText_h
#define mcxPrintableText_h

#include <cstddef>
#include <string>

namespace mcx
{

/// Length of the valid, printable UTF-8 sequence at text[at] (1 to 4), or 0
/// for a control character, a C1 control, or bytes that are no UTF-8.
inline std::size_t PrintableSequence(const std::string& text, std::size_t at)
{
  const unsigned char lead = static_cast<unsigned char>(text[at]);
  if (lead >= 0x20 && lead < 0x7f)
  {
    return 1;
  }
  const std::size_t length = lead >= 0xf0 && lead < 0xf5 ? 4
    : lead >= 0xe0 && lead < 0xf0                        ? 3
    : lead >= 0xc2 && lead < 0xe0                        ? 2
                                                         : 0;
  if (length == 0 || at + length > text.size())
  {
    return 0;
  }
  unsigned long code = lead & (0x3f >> (length - 1));
  for (std::size_t i = 1; i < length; ++i)
  {
    const unsigned char next = static_cast<unsigned char>(text[at + i]);
    if ((next & 0xc0) != 0x80)
    {
      return 0;
    }
    code = (code << 6) | (next & 0x3f);
  }
  const unsigned long shortest[5] = { 0, 0, 0x80, 0x800, 0x10000 };
  const bool valid = code >= shortest[length] && code <= 0x10ffff &&
    !(code >= 0xd800 && code <= 0xdfff) && !(code >= 0x80 && code < 0xa0);
  return valid ? length : 0;
}

/// text with every byte that is not printable UTF-8 as "\xNN", and, beyond
/// maxBytes, its middle replaced by " ... " (the start names the file, the
/// end says why).
inline std::string PrintableText(const std::string& text, std::size_t maxBytes = 2048)
{
  std::string out;
  out.reserve(text.size());
  for (std::size_t at = 0; at < text.size();)
  {
    const std::size_t length = PrintableSequence(text, at);
    if (length > 0)
    {
      out.append(text, at, length);
      at += length;
      continue;
    }
    static const char hex[] = "0123456789abcdef";
    const unsigned char byte = static_cast<unsigned char>(text[at++]);
    out += "\\x";
    out += hex[byte >> 4];
    out += hex[byte & 15];
  }
  if (out.size() > maxBytes && maxBytes >= 16)
  {
    // Cut between UTF-8 sequences: a continuation byte is never a start.
    std::size_t head = maxBytes * 2 / 3, tail = out.size() - (maxBytes - head - 5);
    while (head > 0 && (static_cast<unsigned char>(out[head]) & 0xc0) == 0x80)
    {
      --head;
    }
    while (tail < out.size() && (static_cast<unsigned char>(out[tail]) & 0xc0) == 0x80)
    {
      ++tail;
    }
    out = out.substr(0, head) + " ... " + out.substr(tail);
  }
  return out;
}

} // namespace mcx

#endif
