#pragma once
#include <string>

#include "scene.h"
#include "scenes/world.h"

namespace scenes {

// The report's explosion case: a chain of rods pulled fully straight between
// two beads that ride on circular wires, each bead at the far side of its
// wire, under gravity. While the chain is straight every rod and both wire
// normals are parallel, so J W Jᵀ loses rank: a stress test for the solver.
struct TautChainParams {
  int links = 8;
  double separation = 1.2;         // m
  double radius = 0.2;             // m
  double mass = 0.1;               // kg
  std::string rod = "squared";
  double gravity = kEarthGravity;  // m/s²
  double dt = 0.002;               // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("links", links, "number of rods between the two beads");
    field("separation", separation, "distance between the two wire centres, m");
    field("radius", radius, "radius of both wires, m");
    field("mass", mass, "mass of each particle, kg");
    field("rod", rod, "rod constraint form: squared (|d|^2 - r^2) or root (|d| - r)");
    field("gravity", gravity, "downward acceleration, m/s^2");
  }
  void validate() const;
  static TautChainParams seed();  // preset "seed": the seed report's values
};

Scene buildTautChain(const TautChainParams& p);

}  // namespace scenes
