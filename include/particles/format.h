#pragma once
// How numbers become text, in one place for the engine and the tools: error
// messages, CSV files, tables and the values the report quotes.
#include <string>

namespace particles {

// The shortest text that reads back to the same double (std::to_chars'
// shortest form: 0.1, 1e-05, 1e+10): parameter defaults, the runner's CSVs,
// anything a program reads back.
std::string formatNumber(double value);

// `digits` significant digits, as printf's %.*g: tables, quoted values, the
// laboratory's CSVs (10 digits).
std::string formatGeneral(double value, int digits);

// `digits` digits after the point, as printf's %.*f.
std::string formatFixed(double value, int digits);

// A value in an error message: 6 significant digits ("got 1e+308", "got nan").
inline std::string formatValue(double value) { return formatGeneral(value, 6); }

}  // namespace particles
