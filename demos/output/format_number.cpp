#include "output/format_number.h"

#include <charconv>

#include <fmt/format.h>

namespace output {

// The shortest text that reads back as the same double: std::to_chars where
// the standard library has it for floating point (libstdc++), {fmt}'s
// shortest round trip where it has not (libc++ 14, the WebAssembly build).
std::string formatNumber(double value) {
#if defined(__cpp_lib_to_chars)
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
#else
  return fmt::format("{}", value);
#endif
}

// {fmt}'s g and f presentations with a precision write what printf's %.*g
// and %.*f write (and what an ostream with that precision writes).
std::string formatGeneral(double value, int digits) { return fmt::format("{:.{}g}", value, digits); }

std::string formatFixed(double value, int digits) { return fmt::format("{:.{}f}", value, digits); }

std::string plural(long long count, const std::string& noun, const std::string& pluralNoun) {
  return std::to_string(count) + " " + (count == 1 ? noun : pluralNoun.empty() ? noun + "s" : pluralNoun);
}

}  // namespace output
