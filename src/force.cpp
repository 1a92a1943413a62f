#include "particles/force.h"

#include <stdexcept>
#include <string>

namespace particles {

void Force::addJacobians(const Phase&, Triplets&, Triplets&) const {
  throw std::logic_error(std::string("force '") + type() + "' provides no force Jacobians");
}

}  // namespace particles
