#include "decimal_number.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace scenes {

namespace {

bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// Whether text is [+-] digits [. digits] [e [+-] digits] with a digit in the
// mantissa; nonZero tells whether a mantissa digit is not 0.
bool decimalForm(const std::string& text, bool& nonZero) {
  std::size_t k = 0, digits = 0;
  nonZero = false;
  if (k < text.size() && (text[k] == '+' || text[k] == '-')) ++k;
  const auto mantissa = [&] {
    for (; k < text.size() && isDigit(text[k]); ++k, ++digits) nonZero |= text[k] != '0';
  };
  mantissa();
  if (k < text.size() && text[k] == '.') {
    ++k;
    mantissa();
  }
  if (digits == 0) return false;
  if (k < text.size() && (text[k] == 'e' || text[k] == 'E')) {
    ++k;
    if (k < text.size() && (text[k] == '+' || text[k] == '-')) ++k;
    const std::size_t start = k;
    while (k < text.size() && isDigit(text[k])) ++k;
    if (k == start) return false;
  }
  return k == text.size();
}

bool namedValue(const std::string& text) {
  std::string word = text.substr(!text.empty() && (text[0] == '+' || text[0] == '-') ? 1 : 0);
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return word == "nan" || word == "inf" || word == "infinity";
}

}  // namespace

double readDecimalNumber(const std::string& text) {
  bool nonZero = false;
  const bool decimal = decimalForm(text, nonZero);
  if (!decimal && !namedValue(text)) throw std::invalid_argument("expected a decimal number, got '" + text + "'");
  errno = 0;
  const double value = std::strtod(text.c_str(), nullptr);
  if (decimal && std::isinf(value))
    throw std::invalid_argument("'" + text + "' is too large for a double (above 1.8e+308)");
  if (decimal && nonZero && value == 0.0)
    throw std::invalid_argument("'" + text + "' is too small for a double: it would read as 0");
  return value;
}

}  // namespace scenes
