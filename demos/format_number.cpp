#include "format_number.h"

#include <charconv>

namespace scenes {

std::string formatNumber(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string plural(long long count, const std::string& noun, const std::string& pluralNoun) {
  return std::to_string(count) + " " + (count == 1 ? noun : pluralNoun.empty() ? noun + "s" : pluralNoun);
}

}  // namespace scenes
