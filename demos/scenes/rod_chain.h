#pragma once
#include <string>

#include "scene.h"
#include "scenes/world.h"

namespace scenes {

// A chain of rods hanging from a bead that rides on a circular wire, released
// horizontally at rest under gravity.
struct RodChainParams {
  int links = 6;
  double length = 0.12;            // m
  double radius = 0.25;            // m
  double mass = 0.1;               // kg
  std::string rod = "squared";
  double gravity = kEarthGravity;  // m/s²
  double dt = 0.002;               // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("links", links, "number of rods");
    field("length", length, "rod length, m");
    field("radius", radius, "radius of the wire the first particle rides on, m");
    field("mass", mass, "mass of each particle, kg");
    field("rod", rod, "rod constraint form: squared (|d|^2 - r^2) or root (|d| - r)");
    field("gravity", gravity, "downward acceleration, m/s^2");
  }
  void validate() const;
  static RodChainParams seed();  // preset "seed": the seed report's values
};

Scene buildRodChain(const RodChainParams& p);

}  // namespace scenes
