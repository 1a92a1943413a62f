#pragma once
// The engine's own reach into a ParticleSystem beyond its public API (a
// friend of it, internal to src/): the evaluations that the explicit schemes
// fuse with their stages, and the controller that chooses a step's threads.
#include <vector>

#include <Eigen/Core>

#include "particle_range.h"
#include "particles/particle_system.h"
#include "thread_use.h"

namespace particles {

// One state at which accelerations() evaluates.
struct StatePoint {
  const Eigen::VectorXd& x;
  const Eigen::VectorXd& v;
};

struct SystemInternals {
  // ParticleSystem::acceleration at (x, v), then then(begin, end), when given,
  // over ranges of particles covering them all once a's entries of those
  // particles are final: fused into the force pass when nothing follows the
  // forces, on threadCount() threads. Other ranges may still be reading x and
  // v: then writes neither, and no entry of another range
  // (ForceBatches::applyAndDivide).
  static void acceleration(ParticleSystem& system, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                           Eigen::VectorXd& a, const ParticleRange& then);
  // acceleration() at points[0], points[1], … in turn, with then(k, begin,
  // end) as evaluation k's then. A particle's point k + 1 is read only after
  // then(k, ·) has run on every range whose particles its forces read, so
  // points[k + 1] may be what then(k, ·) writes (the stages of an explicit
  // Runge–Kutta method), and then(k, ·) may write what evaluation k − 1 read.
  // then reads and writes the entries of its own range only: other ranges may
  // meanwhile be in evaluation k − 1 or k + 1. a holds the last
  // evaluation's accelerations. Without constraints the whole sequence is one
  // pass of the force batches (one parallel region, ForceBatches::applyAndDivide);
  // tallied as points.size() force evaluations.
  static void accelerations(ParticleSystem& system, const std::vector<StatePoint>& points, Eigen::VectorXd& a,
                            const StageRange& then);
  // The controller behind system.threadUse() (its settings), with its clock
  // and hand-off timer.
  static ThreadUse& threadUse(ParticleSystem& system);
};

}  // namespace particles
