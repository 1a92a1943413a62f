#pragma once
// How numbers become text in the tools, in one place: CSV files, tables and
// the values the report quotes. (The engine's error messages use
// particles::formatValue, particles/check.h.)
#include <string>

namespace output {

// The shortest text that reads back to the same double (std::to_chars'
// shortest form: 0.1, 1e-05, 1e+10): parameter defaults, the runner's CSVs,
// anything a program reads back.
std::string formatNumber(double value);

// `digits` significant digits, as printf's %.*g: tables, quoted values, the
// laboratory's CSVs (10 digits).
std::string formatGeneral(double value, int digits);

// `digits` digits after the point, as printf's %.*f.
std::string formatFixed(double value, int digits);

// A count with its noun, the noun plural unless the count is 1 ("1 particle",
// "24 particles", "0 starts"): every generated label and caption says it so.
// `pluralNoun` for a noun that does not take an s (empty: noun + "s").
std::string plural(long long count, const std::string& noun, const std::string& pluralNoun = "");

}  // namespace output
