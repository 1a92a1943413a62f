#pragma once
#include <string>

namespace scenes {

// The shortest text that reads back to the same double (std::to_chars), for
// parameter defaults and CSV output alike.
std::string formatNumber(double value);

}  // namespace scenes
