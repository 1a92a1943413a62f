#pragma once
#include <string>

#include "scene.h"

namespace scenes {

// A chain of rods hanging from a bead that rides on a circular wire, released
// horizontally at rest under gravity.
struct RodChainParams {
  int links = 6;
  double length = 0.12;
  double radius = 0.25;
  double mass = 1.0;
  std::string rod = "squared";
  double gravity = 0.05;

  double dt = 0.01;  // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("links", links, "number of rods");
    field("length", length, "rod length, world units");
    field("radius", radius, "radius of the wire the first particle rides on, world units");
    field("mass", mass, "mass of each particle");
    field("rod", rod, "rod constraint form: squared (|d|^2 - r^2) or root (|d| - r)");
    field("gravity", gravity, "downward acceleration, world units/s^2");
  }
  void validate() const;
  static RodChainParams seed();  // preset "seed": the seed report's values
};

Scene buildRodChain(const RodChainParams& p);

}  // namespace scenes
