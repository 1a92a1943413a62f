#pragma once
// Text from a file or the command line made safe to print on one line of a
// terminal: control characters (newline, ESC, ...) become C-style escapes
// (\n, \t, \r, \xHH), so a scene's name cannot break a one-line summary or
// message, or send escape sequences to the terminal.
#include <cstdio>
#include <string>

namespace scenes {

inline std::string printable(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') out += "\\n";
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

}  // namespace scenes
