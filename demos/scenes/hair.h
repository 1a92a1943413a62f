#pragma once
#include "scene.h"

namespace scenes {

// The report's hair: several curls, each a chain of particles with springs
// between neighbours and angular springs on consecutive triples, the root of
// each curl sliding on one horizontal line, the curls colliding with each
// other as discs. Departing from the report, a small gravity makes the curls
// hang down (the report's future work: its curls flipped without it).
//
// The angular damping k_d = 3 acts on levers of length rest, a rate of order
// k_d / (m rest²) that explicit schemes must resolve; the mass (10) keeps that
// rate within reach of dt = 0.002, and the gravity (0.005, a tenth of the
// world's) keeps the curl's weight m g small against the bending stiffness k_s = 1.
//
// The angle spring is signed (θ counter-clockwise from arm x₁−x₂ to arm
// x₃−x₂), so a curl with every rest angle +π/2 would close into a square after
// four links and fold onto itself; the rest angles alternate ±θ₀ instead, and
// a curl at rest is a crimped zigzag whose axis points down.
struct HairParams {
  int curls = 6;
  int particles = 25;
  double rest = 0.08;
  double mass = 10.0;
  double stiffness = 300.0;
  double damping = 1.0;
  double bendAngle = 90.0;
  double bendStiffness = 1.0;
  double bendDamping = 3.0;
  double radius = 0.025;
  double gravity = 0.005;

  double dt = 0.002;  // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("curls", curls, "number of curls");
    field("particles", particles, "particles per curl");
    field("rest", rest, "spring rest length between neighbours, world units");
    field("mass", mass, "mass of each particle");
    field("stiffness", stiffness, "neighbour spring k_s, force/length (holds the curl's weight)");
    field("damping", damping, "neighbour spring k_d, force/speed");
    field("bend-angle", bendAngle, "rest angle theta_0 of each triple, degrees (report: 90)");
    field("bend-stiffness", bendStiffness, "angular spring k_s, energy/rad^2 (report: 1)");
    field("bend-damping", bendDamping, "angular spring k_d, energy*s/rad^2 (report: 3)");
    field("radius", radius, "collision radius of each particle, world units");
    field("gravity", gravity, "downward acceleration, world units/s^2");
  }
  void validate() const;
  static HairParams seed();  // preset "seed": the seed report's values
};

Scene buildHair(const HairParams& p);

}  // namespace scenes
