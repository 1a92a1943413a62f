#pragma once
#include <string>

#include "particles/format.h"

namespace scenes {

// Numbers are written by particles/format.h (one formatter for the engine and the tools).
using particles::formatNumber;

// A count with its noun, the noun plural unless the count is 1 ("1 particle",
// "24 particles", "0 starts"): every generated label and caption says it so.
// `pluralNoun` for a noun that does not take an s (empty: noun + "s").
std::string plural(long long count, const std::string& noun, const std::string& pluralNoun = "");

}  // namespace scenes
