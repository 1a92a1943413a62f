#include "format_number.h"

#include <charconv>

#include <fmt/format.h>

namespace scenes {

std::string formatNumber(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string formatGeneral(double value, int digits) { return fmt::format("{:.{}g}", value, digits); }

std::string formatFixed(double value, int digits) { return fmt::format("{:.{}f}", value, digits); }

}  // namespace scenes
