#pragma once
#include "scene.h"
#include "scenes/world.h"

namespace scenes {

// Soft bodies: each a closed ring of `particles` particles joined by damped
// springs around a gas at pressure p₀ (particles/forces/pressure.h: Boyle's
// p A = p₀ A₀), dropped onto a floor with a ramp. The ring's particles are
// discs, so two bodies bump into each other; its sides are collision edges,
// so it cannot wrap a corner between two particles. The second body holds
// its gas at a quarter of the first's pressure: it squashes more.
//
// At rest without gravity a ring of N springs (k_s, rest r) settles as a
// regular polygon whose circumradius R balances the gas against the springs'
// tension T = k_s (l − r), l = 2 R sin(π/N): Laplace's law for the polygon,
// p = T / (R cos(π/N)), with p = p₀ A₀ / A (the tests check it).
// Defaults: R₀ = 0.12 m, 24 particles of 10 g, k_s = 400 N/m, p₀ = 40 N/m:
// under its weight (2.4 N) the first flattens its bottom by some 10% of its
// height; the fastest spring mode √(4 k_s/m) = 400 rad/s keeps RK4 stable at
// dt = 2 ms (ω dt = 0.8).
struct SoftBodyParams {
  int bodies = 2;
  int particles = 24;              // per ring
  double radius = 0.12;            // R₀ at rest, m
  double mass = 0.01;              // per particle, kg
  double stiffness = 400.0;        // spring k_s, N/m
  double damping = 0.2;            // spring k_d, N s/m
  double pressure = 40.0;          // p₀ of the first body at its rest area, N/m
  double gravity = kEarthGravity;  // m/s²
  double drag = 0.002;             // air drag on every particle, N s/m
  double dt = 0.002;               // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("bodies", bodies, "soft bodies dropped (1 or 2; the second at a quarter of the pressure)");
    field("particles", particles, "particles around each ring (at least 3)");
    field("radius", radius, "ring radius at rest, m");
    field("mass", mass, "mass of each particle, kg");
    field("stiffness", stiffness, "spring k_s around the ring, N/m");
    field("damping", damping, "spring k_d, N s/m");
    field("pressure", pressure, "gas pressure p0 of the first body at its rest area, N/m (p A stays p0 A0)");
    field("gravity", gravity, "downward acceleration g, m/s^2");
    field("drag", drag, "air drag k_d on every particle, N s/m (0: none)");
  }
  void validate() const;
  static SoftBodyParams seed();  // preset "seed": the defaults under the seed's gravity
};

Scene buildSoftBody(const SoftBodyParams& p);

}  // namespace scenes
