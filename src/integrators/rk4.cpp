#include "integrators/rk4.h"

#include "particles/particle_system.h"
#include "system_internals.h"
#include "vector_kernels.h"

namespace particles {

namespace {

// The combinations of one stage over entries [begin, end) of y = (x, v), each
// entry's operations as Eigen's whole-vector expressions do them (the same
// bits). A stage reads the point its forces were evaluated at (xs, vs) and
// writes the next one elsewhere (xn, vn): it runs in the force pass, while
// other ranges of particles may still be reading xs and vs.
struct Stage {
  double *x0, *v0;  // the system's x and v: y0, overwritten by the last pass
  const double* a;
  double *dx, *dv;
  const double *xs, *vs;  // the point a was evaluated at
  double *xn, *vn;        // the next point
};

// After k1 = (v0, a): dx = v0, dv = a, and the next point y0 + c k1.
PARTICLES_VECTOR_CLONES
void firstStage(const Stage& s, int begin, int end, double c) {
#pragma omp simd
  for (int k = begin; k < end; ++k) {
    s.dx[k] = s.v0[k];
    s.dv[k] = s.a[k];
    s.xn[k] = s.x0[k] + c * s.v0[k];
    s.vn[k] = s.v0[k] + c * s.a[k];
  }
}

// After k2 or k3 = (vs, a): d += 2 k, and the next point y0 + c k.
PARTICLES_VECTOR_CLONES
void middleStage(const Stage& s, int begin, int end, double c) {
#pragma omp simd
  for (int k = begin; k < end; ++k) {
    s.dx[k] += 2.0 * s.vs[k];
    s.dv[k] += 2.0 * s.a[k];
    s.xn[k] = s.x0[k] + c * s.vs[k];
    s.vn[k] = s.v0[k] + c * s.a[k];
  }
}

// After k4 = (vs, a): d += k4, and y = y0 + (h/6) d written over y0.
PARTICLES_VECTOR_CLONES
void lastStage(const Stage& s, int begin, int end, double h6) {
#pragma omp simd
  for (int k = begin; k < end; ++k) {
    s.dx[k] += s.vs[k];
    s.dv[k] += s.a[k];
    s.x0[k] = s.x0[k] + h6 * s.dx[k];
    s.v0[k] = s.v0[k] + h6 * s.dv[k];
  }
}

}  // namespace

// For y = (x, v) and y' = (v, a(x, v)), the four stages are evaluated at
// y, y + (h/2) k1, y + (h/2) k2, y + h k3; dx_, dv_ accumulate the weighted
// sum. Each stage's combination runs in its force pass, particle range by
// particle range (SystemInternals::accelerations's then), so a step is four
// passes over the particles, evaluated as one sequence (one parallel region
// when the forces allow); the stage points alternate between (xs_, vs_) and
// (xt_, vt_). The start y0 is the system's own state, read until the last
// pass writes y0 + (h/6) d over it.
StepStats Rk4Integrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = positionsOf(system);
  Eigen::VectorXd& v = velocitiesOf(system);
  for (Eigen::VectorXd* w : {&xs_, &vs_, &xt_, &vt_, &dx_, &dv_, &a_}) w->resize(x.size());
  auto stage = [&](const Eigen::VectorXd& xs, const Eigen::VectorXd& vs, Eigen::VectorXd& xn, Eigen::VectorXd& vn) {
    return Stage{x.data(), v.data(), a_.data(), dx_.data(), dv_.data(), xs.data(), vs.data(), xn.data(), vn.data()};
  };
  // Stage k: the point its forces are evaluated at, its combination, the step it takes.
  struct Rule {
    Stage stage;
    void (*combine)(const Stage&, int, int, double);
    double c;
  };
  const Rule rules[] = {{stage(x, v, xs_, vs_), firstStage, 0.5 * dt},       // k1
                        {stage(xs_, vs_, xt_, vt_), middleStage, 0.5 * dt},  // k2
                        {stage(xt_, vt_, xs_, vs_), middleStage, dt},        // k3
                        {stage(xs_, vs_, xs_, vs_), lastStage, dt / 6.0}};   // k4
  SystemInternals::accelerations(system, {{x, v}, {xs_, vs_}, {xt_, vt_}, {xs_, vs_}}, a_,
                                 [&](int k, int begin, int end) {
                                   rules[k].combine(rules[k].stage, 2 * begin, 2 * end, rules[k].c);
                                 });
  lastStep_ = dt;
  return system.takeEvaluationStats();
}

}  // namespace particles
