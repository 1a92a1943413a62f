#pragma once
#include "scene.h"
#include "scenes/world.h"

namespace scenes {

// Newton's cradle: `balls` discs of radius r, each hanging on a rod of
// length L from a pinned pivot, the pivots 2r + gap apart so that the balls
// hang in a row a hair apart; the first is released at rest from `angle`
// out. With particle restitution e = 1 and equal masses every impact is an
// elastic collision of equals, which swaps the two velocities: the first
// ball stops dead and the last leaves with the first's speed at impact,
//   v = √(2 g L (1 − cos θ₀)),
// and swings out to θ₀ on the far side (the closed form the tests hold it
// to). The gap (a millimetre) makes the impacts one after another, as the
// idealised cradle's are; touching balls would take them all at once.
// Defaults: L = 0.3 m, θ₀ = 30°: v = 0.887 m/s, a swing of 0.55 s out and back.
struct NewtonsCradleParams {
  int balls = 5;
  double radius = 0.04;            // r, m
  double length = 0.3;             // L, rod from pivot to ball centre, m
  double mass = 0.1;               // kg
  double angle = 30.0;             // θ₀, the first ball's release angle, degrees
  double gap = 0.001;              // between neighbouring balls at rest, m
  double restitution = 1.0;        // e of the ball–ball impacts
  double gravity = kEarthGravity;  // m/s²
  double dt = 0.001;               // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("balls", balls, "balls in the row (at least 2)");
    field("radius", radius, "ball radius r, m");
    field("length", length, "rod length L from pivot to ball centre, m");
    field("mass", mass, "mass of each ball, kg");
    field("angle", angle, "release angle of the first ball, degrees");
    field("gap", gap, "gap between neighbouring balls at rest, m");
    field("restitution", restitution, "restitution e of the ball-ball impacts, in [0, 1]");
    field("gravity", gravity, "downward acceleration g, m/s^2");
  }
  void validate() const;
  static NewtonsCradleParams seed();  // preset "seed": the defaults under the seed's gravity
};

Scene buildNewtonsCradle(const NewtonsCradleParams& p);

// The first ball's speed at impact, √(2 g L (1 − cos θ₀)).
double cradleImpactSpeed(const NewtonsCradleParams& p);

}  // namespace scenes
