#pragma once
// How the tools write numbers: one place for every format ({fmt}).
#include <string>

namespace scenes {

// The shortest text that reads back to the same double (std::to_chars'
// shortest form: 0.1, 1e-05, 1e+10), for parameter defaults, the runner's
// CSVs and everything a program reads back.
std::string formatNumber(double value);

// `digits` significant digits, as printf's %.*g (tables, quoted values and
// the laboratory's CSVs: 10 digits).
std::string formatGeneral(double value, int digits);

// `digits` digits after the point, as printf's %.*f.
std::string formatFixed(double value, int digits);

}  // namespace scenes
