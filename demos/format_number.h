#pragma once
#include <string>

namespace scenes {

// The shortest text that reads back to the same double (std::to_chars), for
// parameter defaults and CSV output alike.
std::string formatNumber(double value);

// A count with its noun, the noun plural unless the count is 1 ("1 particle",
// "24 particles", "0 starts"): every generated label and caption says it so.
// `pluralNoun` for a noun that does not take an s (empty: noun + "s").
std::string plural(long long count, const std::string& noun, const std::string& pluralNoun = "");

}  // namespace scenes
