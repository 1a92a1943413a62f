#include "particles/integrators/adaptive_rk4.h"

#include <algorithm>
#include <cmath>

#include "particles/particle_system.h"

namespace particles {

void AdaptiveRk4Integrator::configure(const IntegratorSettings& settings) {
  settings.validate();
  tolerance_ = settings.tolerance;
  minStepFraction_ = settings.minStepFraction;
  maxStepsPerCall_ = settings.maxStepsPerCall;
}

StepStats AdaptiveRk4Integrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = system.positions();
  Eigen::VectorXd& v = system.velocities();
  if (!(h_ > 0.0) || !std::isfinite(h_)) h_ = dt;
  // The floor: a step the controller would cut below it fails the call.
  const double floor = minStepFraction_ * dt;
  long attempts = 0;
  history_.clear();
  lastStep_ = 0.0;  // becomes the largest step accepted in this call
  double t = 0.0;
  StepStats stats;
  stats.internalSteps = 0;
  auto substep = [&](double h) {
    StepStats part = rk4_.step(system, h);
    part.internalSteps = 0;
    stats += part;
  };
  while (t < dt) {
    if (++attempts > maxStepsPerCall_) {
      stats.failure = StepFailure::WorkCapReached;
      break;
    }
    const bool last = h_ >= dt - t;
    const double h = last ? dt - t : h_;
    x0_ = x;
    v0_ = v;

    substep(h);
    xBig_.swap(x);
    vBig_.swap(v);
    x = x0_;
    v = v0_;
    substep(0.5 * h);
    substep(0.5 * h);

    // err = max_i |y_small − y_big|_i / (15 tol (1 + |y_i|)) over x and v.
    double err = 0.0;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      err = std::max(err, std::abs(x[i] - xBig_[i]) / (1.0 + std::abs(x[i])));
      err = std::max(err, std::abs(v[i] - vBig_[i]) / (1.0 + std::abs(v[i])));
    }
    err /= 15.0 * tolerance_;
    if (!std::isfinite(err)) err = 1e10;  // a blown-up trial is a rejection
    const double factor = std::clamp(0.9 * std::pow(std::max(err, 1e-10), -0.2), 0.2, 5.0);

    if (err <= 1.0) {
      x += (x - xBig_) / 15.0;
      v += (v - vBig_) / 15.0;
      t = last ? dt : t + h;
      history_.push_back(h);
      ++accepted_;
      ++stats.internalSteps;
      lastStep_ = std::max(lastStep_, h);
      // A last step shortened to land on dt says nothing about how far h_ can go.
      if (h == h_) h_ = h * factor;
    } else {
      x = x0_;
      v = v0_;
      ++rejected_;
      ++stats.rejectedSteps;
      h_ = h * factor;
      if (h_ < floor) {
        stats.failure = StepFailure::StepBelowFloor;
        break;
      }
    }
  }
  return stats;
}

}  // namespace particles
