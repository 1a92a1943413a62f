#include "particles/integrator.h"

#include <stdexcept>

#include "particles/integrators/explicit_euler.h"
#include "particles/integrators/midpoint.h"
#include "particles/integrators/rk4.h"
#include "particles/integrators/symplectic_euler.h"

namespace particles {

namespace {
template <class T>
std::unique_ptr<Integrator> make() {
  return std::make_unique<T>();
}
}  // namespace

const std::vector<IntegratorInfo>& integratorTable() {
  static const std::vector<IntegratorInfo> table = {
      {"euler", "explicit Euler: x and v both from the old state", 1, make<ExplicitEulerIntegrator>},
      {"symplectic-euler", "symplectic Euler: v first, then x with the new v (the seed's \"Euler\")", 1,
       make<SymplecticEulerIntegrator>},
      {"midpoint", "explicit midpoint (RK2)", 2, make<MidpointIntegrator>},
      {"rk4", "classic fourth-order Runge-Kutta", 4, make<Rk4Integrator>},
  };
  return table;
}

std::unique_ptr<Integrator> makeIntegrator(const std::string& name) {
  std::string names;
  for (const IntegratorInfo& info : integratorTable()) {
    if (name == info.name) return info.make();
    names += names.empty() ? "" : ", ";
    names += info.name;
  }
  throw std::invalid_argument("unknown integrator '" + name + "' (valid: " + names + ")");
}

}  // namespace particles
