#pragma once
#include "scene.h"
#include "scenes/world.h"

namespace scenes {

// A bead on a circular wire of radius L under gravity, released at rest at a
// large angle from the bottom: a pendulum without small-angle approximation.
// Defaults: T = 1.522 s at 60° (4 √(L/g) K(sin 30°); 1.419 s for small swings).
struct PendulumParams {
  double length = 0.5;             // m
  double angle = 60.0;             // degrees
  double mass = 1.0;               // kg
  double gravity = kEarthGravity;  // m/s²
  double dt = 0.005;               // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("length", length, "wire radius L, m");
    field("angle", angle, "release angle theta_0 from the bottom, degrees");
    field("mass", mass, "mass of the bead, kg");
    field("gravity", gravity, "downward acceleration g, m/s^2");
  }
  void validate() const;
  static PendulumParams seed();  // preset "seed": the seed report's values
};

Scene buildPendulum(const PendulumParams& p);

// Large-angle period T = 4 √(L/g) K(sin(θ₀/2)), K the complete elliptic
// integral of the first kind with modulus k (ellipticK, scenes/elliptic.h).
double pendulumPeriod(const PendulumParams& p);

}  // namespace scenes
