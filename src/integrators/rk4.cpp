#include "particles/integrators/rk4.h"

#include "parallel_for.h"
#include "particles/particle_system.h"
#include "particles/threads.h"

namespace particles {

namespace {

// The combinations of one stage as one pass over entries [begin, end) of
// y = (x, v), each entry's operations as Eigen's whole-vector expressions do
// them (the same bits), on threadCount() threads for long vectors.
struct Stage {
  double *x0, *v0;  // the system's x and v: y0, overwritten by the last pass
  const double* a;
  double *xs, *vs, *dx, *dv;

  // After k1 = (v0, a): dx = v0, dv = a, and the next point y0 + c k1.
  void first(int begin, int end, double c) const {
#pragma omp simd
    for (int k = begin; k < end; ++k) {
      dx[k] = v0[k];
      dv[k] = a[k];
      xs[k] = x0[k] + c * v0[k];
      vs[k] = v0[k] + c * a[k];
    }
  }
  // After k2 or k3 = (vs, a): d += 2 k, and the next point y0 + c k.
  void middle(int begin, int end, double c) const {
#pragma omp simd
    for (int k = begin; k < end; ++k) {
      dx[k] += 2.0 * vs[k];
      dv[k] += 2.0 * a[k];
      xs[k] = x0[k] + c * vs[k];
      vs[k] = v0[k] + c * a[k];
    }
  }
  // After k4 = (vs, a): d += k4, and y = y0 + (h/6) d written over y0.
  void last(int begin, int end, double h6) const {
#pragma omp simd
    for (int k = begin; k < end; ++k) {
      dx[k] += vs[k];
      dv[k] += a[k];
      x0[k] = x0[k] + h6 * dx[k];
      v0[k] = v0[k] + h6 * dv[k];
    }
  }
};

}  // namespace

// For y = (x, v) and y' = (v, a(x, v)), the four stages are evaluated at
// y, y + (h/2) k1, y + (h/2) k2, y + h k3; dx_, dv_ accumulate the weighted
// sum. The start y0 is the system's own state, read until the last pass
// writes y0 + (h/6) d over it.
StepStats Rk4Integrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = positionsOf(system);
  Eigen::VectorXd& v = velocitiesOf(system);
  const int m = static_cast<int>(x.size()), threads = threadCount();
  for (Eigen::VectorXd* w : {&xs_, &vs_, &dx_, &dv_}) w->resize(m);
  auto each = [&](auto pass) { parallelRanges(m, threads, kParallelEntries, pass); };

  system.acceleration(x, v, a_);  // k1 = (v0, a)
  const Stage k{x.data(), v.data(), a_.data(), xs_.data(), vs_.data(), dx_.data(), dv_.data()};
  each([&](int b, int e) { k.first(b, e, 0.5 * dt); });
  system.acceleration(xs_, vs_, a_);  // k2 = (vs, a)
  each([&](int b, int e) { k.middle(b, e, 0.5 * dt); });
  system.acceleration(xs_, vs_, a_);  // k3
  each([&](int b, int e) { k.middle(b, e, dt); });
  system.acceleration(xs_, vs_, a_);  // k4
  each([&](int b, int e) { k.last(b, e, dt / 6.0); });
  lastStep_ = dt;
  return system.takeEvaluationStats();
}

}  // namespace particles
