#pragma once
#include "scene.h"
#include "scenes/world.h"

namespace scenes {

// A rope over a pulley that does not turn: a chain of light particles joined
// by rods, draped over a disc of radius R with Coulomb friction μ (wrapped
// half way round, θ = π), a load m at its left end and a heavier one
// ratio × m at its right. The capstan law (Euler–Eytelwein): friction
// along the wrap can hold the heavier side while
//   T_heavy / T_light ≤ e^(μ θ),
// so the rope holds while the mass ratio stays below e^(μθ) (2.57 at the
// defaults μ = 0.3) and slips above it. The scene's caption states both.
// The rope's particles and its links meet the pulley (collision edges), so it
// slides on the disc's surface, not through it.
struct CapstanParams {
  double ratio = 2.0;              // heavy over light load
  double friction = 0.3;           // μ of the rope on the pulley
  double load = 0.2;               // the light load m, kg
  double radius = 0.1;             // R of the pulley, m
  int links = 40;                  // rods along the rope
  double drop = 0.3;               // each side's length below the pulley's centre, m
  double ropeMass = 0.002;         // per particle of the rope, kg
  double push = 0.5;               // the rope's speed toward the heavy side at release, m/s
  double gravity = kEarthGravity;  // m/s²
  double dt = 0.001;               // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("ratio", ratio, "mass of the heavy load over the light one (>= 1)");
    field("friction", friction, "Coulomb friction mu of the rope on the pulley");
    field("load", load, "mass of the light load, kg");
    field("radius", radius, "pulley radius R, m");
    field("links", links, "rods along the rope");
    field("drop", drop, "each side's rope below the pulley's centre, m");
    field("rope-mass", ropeMass, "mass of each rope particle, kg");
    field("push", push, "the rope's speed toward the heavy load at release, m/s (friction stops it if it can hold)");
    field("gravity", gravity, "downward acceleration g, m/s^2");
  }
  void validate() const;
  static CapstanParams seed();  // preset "seed": the defaults under the seed's gravity
};

Scene buildCapstan(const CapstanParams& p);

// e^(μ θ) of the wrap, θ = π.
double capstanLimit(const CapstanParams& p);

}  // namespace scenes
