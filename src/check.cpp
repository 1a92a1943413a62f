#include "particles/check.h"

#include <cstdio>

namespace particles {

std::string formatValue(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace particles
