#include "output/format_number.h"

#include <charconv>

#include <fmt/format.h>

namespace output {

std::string formatNumber(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

// {fmt}'s g and f presentations with a precision write what printf's %.*g
// and %.*f write (and what an ostream with that precision writes).
std::string formatGeneral(double value, int digits) { return fmt::format("{:.{}g}", value, digits); }

std::string formatFixed(double value, int digits) { return fmt::format("{:.{}f}", value, digits); }

std::string plural(long long count, const std::string& noun, const std::string& pluralNoun) {
  return std::to_string(count) + " " + (count == 1 ? noun : pluralNoun.empty() ? noun + "s" : pluralNoun);
}

}  // namespace output
