#pragma once
#include <string>

#include "scene.h"
#include "scenes/wind_and_tearing.h"
#include "scenes/world.h"

namespace scenes {

// Hair: several strands, each a chain of particles with springs between
// neighbours and angular springs on consecutive triples, the root of each
// strand sliding on one horizontal line (the scalp), the strands colliding
// with each other and themselves as discs, hanging under gravity.
//
// The angle spring is signed (θ counter-clockwise from arm x₁−x₂ to arm
// x₃−x₂), so the sign of the rest angles chooses the shape:
//   ringlet  every rest angle of a strand has one sign, ±θ₀ (the sign
//            alternating from strand to strand): unloaded, the strand
//            would close into a circle after 360°/(180° − θ₀) links; its
//            own discs keep the turns apart, so it winds into a spiral curl,
//            opened near the root by the weight it carries.
//   zigzag   the seed report's crimp: rest angles alternating ±θ₀, a
//            zigzag whose axis points down.
// A ringlet is released straight down and curls up within a fraction of a
// second; a zigzag starts at its rest shape. The roots are pinned, or slide
// on a horizontal rail as in the seed.
//
// Defaults: 0.29 m strands of 30 one-gram particles turning 40° per link
// (a curl of radius R = rest / (2 sin 20°) = 1.5 cm, 9 links a turn). The
// bending stiffness k_b = 0.007 N·m/rad is about 1.6 times the torque M g R
// of a whole strand's weight about its curl radius: the lower part, which
// carries little weight, winds into a spiral, while the upper part opens
// under the weight it carries (stiffer, k_b ≳ 0.01, and curls climb over
// their roots). The neighbour springs stretch by M g / k_s = 0.3 mm (3% of
// rest) at the root. The fastest modes, stretching at about 2 √(k_s/m) =
// 2000 rad/s and bending at about 4 √(k_b/(m rest²)) = 1060 rad/s, keep RK4
// (|ω dt| < 2.8) stable below dt ≈ 0.0014 s; dt = 0.0005 s leaves it a factor 2.8.
// The bending damping is as stiff: its rate, about 16 k_d/(m rest²), must stay
// below 2.8/dt, so k_d = 1e-5 is near the most RK4 takes at this dt (4e-5
// diverges). Air drag k_d/m = 1/s instead settles a bounce within a few seconds.
//
// Wind and tearing (wind_and_tearing.h) are off by default: the wind pushes
// on every link, and a link that tears takes the angle springs across it.
struct HairParams : WindTearParams {
  int curls = 6;
  int particles = 30;
  double rest = 0.01;                // m
  double mass = 0.001;               // kg
  double stiffness = 1000.0;         // N/m
  double damping = 0.3;              // N·s/m
  std::string shape = "ringlet";
  std::string root = "pinned";
  double bendAngle = 140.0;          // degrees
  double bendStiffness = 0.007;      // N·m/rad
  double bendDamping = 1e-5;         // N·m·s/rad
  double radius = 0.004;             // m
  double drag = 0.001;               // N·s/m
  double gravity = kEarthGravity;    // m/s²
  double dt = 0.0005;                // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("curls", curls, "number of strands");
    field("particles", particles, "particles per strand");
    field("rest", rest, "spring rest length between neighbours, m");
    field("mass", mass, "mass of each particle, kg");
    field("stiffness", stiffness, "neighbour spring k_s, N/m (holds the strand's weight)");
    field("damping", damping, "neighbour spring k_d, N s/m");
    field("shape", shape, "ringlet: rest angles of one sign per strand (curls); zigzag: alternating signs (the seed's crimp)");
    field("root", root, "pinned: each root fixed; rail: the roots slide on one horizontal line (the seed's)");
    field("bend-angle", bendAngle, "rest angle theta_0 of each triple, degrees (180: straight)");
    field("bend-stiffness", bendStiffness, "angular spring k_s, N m/rad (energy/rad^2)");
    field("bend-damping", bendDamping, "angular spring k_d, N m s/rad");
    field("radius", radius, "collision radius of each particle, m");
    field("gravity", gravity, "downward acceleration, m/s^2");
    field("drag", drag, "air drag k_d on every particle, N s/m (0: none)");
    visitWindTear(field);
  }
  void validate() const;
  static HairParams seed();  // preset "seed": the seed report's values
};

Scene buildHair(const HairParams& p);

// Rest angle of the triple centred on the k-th particle of strand `curl`
// (k = 1 … particles − 2): ±θ₀ by the shape's sign rule.
double hairRestAngle(const HairParams& p, int curl, int k);

}  // namespace scenes
