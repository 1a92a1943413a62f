#pragma once
#include <string>

#include "scene.h"
#include "scenes/world.h"

namespace scenes {

// The integrator test scene of the report (its Fig. 4): cl particles joined by
// rods, the first pinned, released at rest from a horizontal line under
// gravity only. The experiments sweep cl, dt and the rod form on it.
struct TestChainParams {
  int cl = 12;
  double length = 0.1;             // m
  double mass = 0.1;               // kg
  std::string rod = "squared";
  double gravity = kEarthGravity;  // m/s²
  double tipMassRatio = 1.0;
  double dt = 0.002;               // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("cl", cl, "chain length: number of particles, the first pinned");
    field("length", length, "rod length, m");
    field("mass", mass, "mass of each particle, kg");
    field("rod", rod, "rod constraint form: squared (|d|^2 - r^2) or root (|d| - r)");
    field("gravity", gravity, "downward acceleration, m/s^2");
    field("tip-mass-ratio", tipMassRatio, "mass of the last particle over the others' (heavy tip on a light chain)");
  }
  void validate() const;
  static TestChainParams seed();  // preset "seed": the seed report's values
};

Scene buildTestChain(const TestChainParams& p);

}  // namespace scenes
