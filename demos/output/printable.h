#pragma once
// Text from a file or the command line made safe to print on one line of a
// terminal: control characters (newline, ESC, ...) become C-style escapes
// (\n, \t, \r, \xHH), and the Unicode characters that move or reorder text
// without being seen — C1 controls (U+0080–U+009F), the bidirectional marks,
// embeddings, overrides and isolates (U+061C, U+200E–U+200F, U+202A–U+202E,
// U+2066–U+2069) and the line and paragraph separators (U+2028, U+2029) —
// become \uXXXX, so a scene's name cannot break a one-line summary or
// message, disguise what it says, or send escape sequences to the terminal.
#include <cstdio>
#include <string>

namespace output {

namespace detail {
// The code point of the invisible formatting character whose UTF-8 encoding
// starts at text[at] (its length in `length`), or 0 for any other text.
inline unsigned invisibleCodePoint(const std::string& text, std::size_t at, std::size_t& length) {
  const auto byte = [&](std::size_t k) { return at + k < text.size() ? static_cast<unsigned char>(text[at + k]) : 0u; };
  unsigned point = 0;
  if (byte(0) == 0xc2 && byte(1) >= 0x80 && byte(1) <= 0x9f) {
    point = byte(1), length = 2;
  } else if (byte(0) == 0xd8 && byte(1) == 0x9c) {
    point = 0x061c, length = 2;
  } else if (byte(0) == 0xe2 && (byte(1) == 0x80 || byte(1) == 0x81) && (byte(2) & 0xc0) == 0x80) {
    point = 0x2000 + ((byte(1) & 0x3f) << 6) + (byte(2) & 0x3f), length = 3;
    const bool invisible = point == 0x200e || point == 0x200f || (point >= 0x2028 && point <= 0x202e) ||
                           (point >= 0x2066 && point <= 0x2069);
    if (!invisible) point = 0;
  }
  return point;
}
}  // namespace detail

inline std::string printable(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    const auto byte = static_cast<unsigned char>(c);
    std::size_t length = 0;
    if (const unsigned point = detail::invisibleCodePoint(text, k, length)) {
      char hex[7];
      std::snprintf(hex, sizeof hex, "\\u%04x", point);
      out += hex;
      k += length - 1;
    } else if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (c == '\r') out += "\\r";
    else if (byte < 0x20 || byte == 0x7f) {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", byte);
      out += hex;
    } else out += c;
  }
  return out;
}

}  // namespace output
