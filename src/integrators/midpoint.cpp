#include "integrators/midpoint.h"

#include "particles/particle_system.h"
#include "system_internals.h"
#include "vector_kernels.h"

namespace particles {

namespace {

// y_mid = y + (h/2) (v, a) over entries [begin, end), each entry as Eigen's
// whole-vector expression rounds it.
PARTICLES_VECTOR_CLONES
void halfStep(const double* x, const double* v, const double* a, double* xMid, double* vMid, int begin, int end,
              double halfDt) {
#pragma omp simd
  for (int k = begin; k < end; ++k) {
    xMid[k] = x[k] + halfDt * v[k];
    vMid[k] = v[k] + halfDt * a[k];
  }
}

// y ← y + h (v_mid, a(y_mid)) over entries [begin, end).
PARTICLES_VECTOR_CLONES
void fullStep(double* x, double* v, const double* vMid, const double* a, int begin, int end, double dt) {
#pragma omp simd
  for (int k = begin; k < end; ++k) {
    x[k] = x[k] + dt * vMid[k];
    v[k] = v[k] + dt * a[k];
  }
}

}  // namespace

// The two evaluations are one sequence (SystemInternals::accelerations): the
// midpoint is written range by range in the first one's force pass, and the
// step over y in the second's, so that a step is two passes over the particles.
StepStats MidpointIntegrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = positionsOf(system);
  Eigen::VectorXd& v = velocitiesOf(system);
  for (Eigen::VectorXd* w : {&xMid_, &vMid_, &a_}) w->resize(x.size());
  SystemInternals::accelerations(system, {{x, v}, {xMid_, vMid_}}, a_, [&](int stage, int begin, int end) {
    if (stage == 0)
      halfStep(x.data(), v.data(), a_.data(), xMid_.data(), vMid_.data(), 2 * begin, 2 * end, 0.5 * dt);
    else
      fullStep(x.data(), v.data(), vMid_.data(), a_.data(), 2 * begin, 2 * end, dt);
  });
  lastStep_ = dt;
  return system.takeEvaluationStats();
}

}  // namespace particles
