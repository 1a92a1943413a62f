#pragma once
#include "scene.h"

namespace scenes {

// A bead on a circular wire of radius L under gravity, released at rest at a
// large angle from the bottom: a pendulum without small-angle approximation.
struct PendulumParams {
  double length = 0.5;
  double angle = 60.0;
  double mass = 1.0;
  double gravity = 0.05;

  double dt = 0.01;  // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("length", length, "wire radius L, world units");
    field("angle", angle, "release angle theta_0 from the bottom, degrees");
    field("mass", mass, "mass of the bead");
    field("gravity", gravity, "downward acceleration g, world units/s^2");
  }
  void validate() const;
  static PendulumParams seed();  // preset "seed": the seed report's values
};

Scene buildPendulum(const PendulumParams& p);

// Large-angle period T = 4 √(L/g) K(sin(θ₀/2)), K the complete elliptic
// integral of the first kind with modulus k (std::comp_ellint_1).
double pendulumPeriod(const PendulumParams& p);

}  // namespace scenes
