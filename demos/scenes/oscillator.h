#pragma once
#include "scene.h"

namespace scenes {

// A mass on a damped spring to a pinned anchor, no gravity: the anchor at the
// origin, the mass on the x axis stretched from rest and released at rest.
// The motion stays on the axis, so the displacement u = |x| − rest obeys
//   m ü + k_d u̇ + k_s u = 0,   u(0) = stretch, u̇(0) = 0.
// Defaults: ω₀ = √(k_s/m) = 2π/(0.99 s), the swing decaying as e^(−t/5 s).
struct OscillatorParams {
  double mass = 1.0;        // kg
  double stiffness = 40.0;  // N/m
  double damping = 0.4;     // N·s/m
  double rest = 0.5;        // m
  double stretch = 0.3;     // m
  double dt = 0.005;        // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("mass", mass, "mass of the moving particle, kg");
    field("stiffness", stiffness, "spring k_s, N/m");
    field("damping", damping, "spring k_d, N s/m");
    field("rest", rest, "spring rest length, m");
    field("stretch", stretch, "initial displacement from rest, m (|stretch| < rest)");
  }
  void validate() const;
  static OscillatorParams seed();  // preset "seed": the seed report's values
};

Scene buildOscillator(const OscillatorParams& p);

// The closed-form displacement u(t) from rest, with γ = k_d/(2m), ω₀² = k_s/m:
//   under-damped  u = s e^(−γt) (cos ω_d t + (γ/ω_d) sin ω_d t),  ω_d = √(ω₀² − γ²)
//   critical      u = s e^(−γt) (1 + γ t)
//   over-damped   u = s (r₁ e^(r₂t) − r₂ e^(r₁t)) / (r₁ − r₂),      r₁,₂ = −γ ± √(γ² − ω₀²)
double oscillatorDisplacement(const OscillatorParams& p, double t);

}  // namespace scenes
