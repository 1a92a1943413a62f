#pragma once
// The plain references' RK4 step (bench_cloth_reference, bench_chain_reference):
// flat arrays, plain loops, the classical four stages
//   k1 = f(x0, v0), k2 = f(x0 + h/2 v1, …), k3 = f(x0 + h/2 v2, …), k4 = f(x0 + h v3, …),
//   x = x0 + h/6 (v0 + 2 v1 + 2 v2 + v3),  v = v0 + h/6 (a0 + 2 a1 + 2 a2 + a3).
#include <algorithm>
#include <cmath>
#include <vector>

#include "integrators/rk4.h"
#include "particles/particle_system.h"

namespace bench {

struct PlainRk4 {
  // The state (2 entries a particle) and the stage scratch.
  std::vector<double> x, v, x0, v0, xs, vs, dx, dv;

  void resize(int particles) {
    for (auto* vec : {&x0, &v0, &xs, &vs, &dx, &dv}) vec->assign(2 * static_cast<std::size_t>(particles), 0.0);
  }

  // accel(x, v) fills acc with the accelerations at (x, v).
  template <class Accel>
  void step(double h, const Accel& accel, const std::vector<double>& acc) {
    const int m = static_cast<int>(x.size());
    x0 = x;
    v0 = v;
    accel(x0, v0);
    for (int k = 0; k < m; ++k) {
      dx[k] = v0[k];
      dv[k] = acc[k];
      xs[k] = x0[k] + (0.5 * h) * v0[k];
      vs[k] = v0[k] + (0.5 * h) * acc[k];
    }
    for (double c : {0.5, 1.0}) {
      accel(xs, vs);
      for (int k = 0; k < m; ++k) {
        dx[k] += 2.0 * vs[k];
        dv[k] += 2.0 * acc[k];
        xs[k] = x0[k] + (c * h) * vs[k];
        vs[k] = v0[k] + (c * h) * acc[k];
      }
    }
    accel(xs, vs);
    for (int k = 0; k < m; ++k) {
      dx[k] += vs[k];
      dv[k] += acc[k];
      x[k] = x0[k] + (h / 6.0) * dx[k];
      v[k] = v0[k] + (h / 6.0) * dv[k];
    }
  }
};

// The engine (Rk4Integrator on s) and a plain reference (plain.step(dt),
// its PlainRk4 in plain.state) stepped `steps` times from the same state: the
// largest |engine − reference| of any coordinate then.
template <class Plain>
double largestDifferenceAfter(int steps, double dt, particles::ParticleSystem& s, Plain& plain) {
  particles::Rk4Integrator rk4;
  for (int k = 0; k < steps; ++k) {
    s.step(rk4, dt);
    plain.step(dt);
  }
  double worst = 0.0;
  for (int k = 0; k < 2 * s.size(); ++k)
    worst = std::max({worst, std::abs(s.positions()[k] - plain.state.x[k]),
                      std::abs(s.velocities()[k] - plain.state.v[k])});
  return worst;
}

}  // namespace bench
