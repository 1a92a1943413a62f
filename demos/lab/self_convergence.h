#pragma once
// A reference for a scene with contacts. odeint integrates the smooth
// equations of motion only: once two discs touch, or a particle or edge meets
// a collider, its trajectory is wrong. The engine's fixed-step schemes end
// every step with the contact pass, so a converged run of one of them is a
// reference, and whether it converged is measured, not assumed:
//
//   run the scheme at dt_0 = T / round(T / h) and at dt_k = dt_0 / 2^k,
//   sampled every h; d_k = max over the samples of the largest particle
//   distance between the runs at dt_k and dt_{k−1}. The run at dt_k is the
//   reference once d_k ≤ threshold (E/10 for a budget E): with an order
//   p ≥ 1 its own error is then about d_k / (2^p − 1) ≤ E/10.
//
// Runs are compared at their common samples, every h. The reference is then
// sampled again, finer where the scene moves fast: a contact changes a
// velocity within an interval, where the interpolant between samples
// (Trajectory::positionsAt) is only as good as the distance moved in it.
//
// The observed order p_k = log2(d_{k−1} / d_k) says how fast the scheme
// converges with contacts (about 1 where the contact pass dominates: a
// contact's time is resolved to a step). A run that fails by the failure
// criterion has no distance; halving goes on past it. When no scheme reaches
// the threshold before dt falls below T / maxSteps there is no reference, and
// the reason says how far the last runs were apart.
#include <atomic>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "lab/failure.h"
#include "lab/reference.h"

namespace lab {

struct SelfConvergenceSettings {
  // Contact-aware fixed-step schemes, the next tried when no two runs of one
  // could be compared (they failed); RK4 first: between contacts it converges fastest.
  std::vector<std::string> schemes = {"rk4", "verlet"};
  double interval = 0.0;    // h: sample spacing and dt_0, simulated seconds
  double threshold = 0.0;   // successive runs must agree within this (world units)
  long maxSteps = 1000000;  // the finest run takes at most this many steps
  // The reference's samples are spread so that no particle moves more than
  // `threshold` between two of them (at a contact the interpolant between
  // samples is then off by at most about half that), unless the samples
  // would take more memory than this (referenceBytes).
  double maxBytes = kMaxReferenceBytes;
  FailureCriterion failure;
  const std::atomic<bool>* cancel = nullptr;
};

// One halving: the run at dt, and its distance from the run at 2 dt (infinite
// when either failed or for the first run).
struct Halving {
  double dt = 0.0;
  bool failed = false;
  double difference = std::numeric_limits<double>::infinity();
};

struct SelfConvergence {
  bool converged = false;
  std::string scheme;            // the scheme whose run is the reference
  double dt = 0.0;               // the reference's step
  double difference = 0.0;       // its distance from the run at 2 dt
  double sampleInterval = 0.0;   // of the reference's samples
  double order = std::numeric_limits<double>::quiet_NaN();  // observed at the last halving with two differences
  std::vector<Halving> halvings;  // of the scheme that converged (or of the last one tried)
  Trajectory trajectory;          // the reference, when converged
  // When not converged: why, and the longest T from 0 over which the last two
  // runs of the scheme tried last agreed within the threshold (0 if none did).
  std::string why;
  double agreesUntil = 0.0;
  // When not converged: how far a start moved by 1e-6 of the scene's size
  // (perturbStart) ends from the start as built at the last dt run, over T. Above the
  // threshold, the motion depends on its start at this error and step (chaos,
  // or contacts a tiny change sends to other steps); below it, the runs
  // converge too slowly in dt. NaN: not measured.
  double startSensitivity = std::numeric_limits<double>::quiet_NaN();
  // "rk4 at dt 3.9e-06 (7 halvings from 0.0005; the last two runs agree within 8.1e-05, observed order 1.02)".
  std::string description() const;
};

// Throws Cancelled when settings.cancel (or an interrupt) stops it, and
// std::invalid_argument for a non-positive interval or threshold.
SelfConvergence selfConvergedReference(const std::function<scenes::Scene()>& build, double horizon,
                                       const SelfConvergenceSettings& settings);

}  // namespace lab
