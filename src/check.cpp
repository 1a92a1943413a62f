#include "particles/check.h"

#include <sstream>

namespace particles {

std::string formatValue(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace particles
