#include "simulation.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "particles/check.h"

namespace demo {

particles::DivergenceLimits demoDivergenceLimits(const scenes::Scene& scene) {
  const double diagonal = (scene.viewMax - scene.viewMin).norm();
  particles::DivergenceLimits limits;
  limits.maxRelativeConstraintError = 1.0;
  limits.maxConstraintError = 1.0 * diagonal;
  limits.maxCoordinate = 1000.0 * diagonal;
  return limits;
}

Simulation::Simulation(scenes::Scene scene, int integratorIndex, double dt)
    : scene_(std::move(scene)), integratorIndex_(-1), dt_(0.0), limits_(demoDivergenceLimits(scene_)) {
  setIntegrator(integratorIndex);
  setDt(dt);
  history_.record(system());
}

void Simulation::setIntegrator(int index) {
  const auto& table = particles::integratorTable();
  if (index < 0 || index >= static_cast<int>(table.size()))
    throw std::invalid_argument("integrator index out of range");
  integrator_ = table[index].make();
  integrator_->configure(integratorSettings_);
  integratorIndex_ = index;
  refusal_.reset();
}

void Simulation::setIntegratorSettings(const particles::IntegratorSettings& settings) {
  settings.validate();
  integratorSettings_ = settings;
  integrator_->configure(settings);
}

const char* Simulation::integratorName() const {
  return particles::integratorTable()[integratorIndex_].name;
}

void Simulation::setDt(double dt) {
  particles::requirePositive("dt", dt);
  dt_ = dt;
}

void Simulation::advanceFrame(double frameTime, StepMode mode) {
  lastFrame_ = {};
  if (stopped()) return;
  const auto start = std::chrono::steady_clock::now();
  if (mode == StepMode::Lockstep) {
    stepAndWatch();
  } else {
    // Fixed simulated time per frame: the frame rate changes how often this
    // runs, never what it computes. Time short of a whole dt carries over.
    owedTime_ += frameTime;
    if (owedTime_ > maxSubstepsPerFrame * dt_) {
      owedTime_ = maxSubstepsPerFrame * dt_;
      lastFrame_.capped = true;
    }
    while (owedTime_ >= dt_ * (1.0 - 1e-9) && !stopped()) {
      stepAndWatch();
      owedTime_ -= dt_;
    }
  }
  lastFrame_.simulationMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (!stopped()) trace_.add(system().totalEnergy(), system().maxConstraintError());
}

void Simulation::stepOnce() {
  if (stopped()) return;
  lastFrame_ = {};
  stepAndWatch();
  if (!stopped()) trace_.add(system().totalEnergy(), system().maxConstraintError());
}

void Simulation::stepAndWatch() {
  particles::StepStats stats;
  try {
    stats = system().step(*integrator_, dt_);
  } catch (const std::exception& e) {
    // Raised before the step changes anything (an integrator's or the
    // solver's precondition): stop here and say why, never crash the window.
    refusal_ = e.what();
    owedTime_ = 0.0;
    return;
  }
  ++steps_;
  ++lastFrame_.substeps;
  // The energy test is off (energyScale infinite), so E₀ is not needed.
  divergence_ = particles::checkDivergence(system(), limits_, 0.0, stats);
  if (divergence_) {
    divergedAt_ = system().time();
    owedTime_ = 0.0;
    return;
  }
  history_.record(system());
}

std::optional<double> Simulation::rewindTo(double time) {
  const particles::Snapshot* snapshot = history_.rewindTo(time);
  if (!snapshot) return std::nullopt;
  system().restore(*snapshot);
  divergedAt_.reset();
  divergence_ = {};
  owedTime_ = 0.0;
  return snapshot->time;
}

void Simulation::copyStateFrom(const Simulation& other) {
  system().restore(other.system().snapshot());
  for (int i = 0; i < system().size(); ++i)
    if (system().pinned(i) != other.system().pinned(i)) system().setPinned(i, other.system().pinned(i));
  system().restore(other.system().snapshot());  // pinning zeroes velocities; take them back
  history_.clear();
  history_.record(system());
  trace_.clear();
}

std::optional<int> Simulation::particleNear(const Eigen::Vector2d& world, double radius,
                                            bool movableOnly) const {
  std::optional<int> best;
  double bestDistance = radius;
  for (int i = 0; i < system().size(); ++i) {
    if (movableOnly && system().pinned(i)) continue;
    const double d = (system().position(i) - world).norm();
    if (d <= bestDistance) {
      bestDistance = d;
      best = i;
    }
  }
  return best;
}

void Simulation::grab(int particle, const Eigen::Vector2d& target, double stiffness,
                      double damping) {
  release();
  auto spring = std::make_unique<particles::MouseSpringForce>(particle, target, stiffness, damping);
  spring_ = spring.get();
  system().addForce(std::move(spring));
}

void Simulation::moveGrab(const Eigen::Vector2d& target) {
  if (spring_) spring_->setTarget(target);
}

void Simulation::release() {
  if (!spring_) return;
  system().removeForce(spring_);
  spring_ = nullptr;
}

void Simulation::setPinned(int particle, bool pinned) {
  if (spring_ && spring_->particle() == particle && pinned) release();
  system().setPinned(particle, pinned);
}

void Simulation::placePinned(int particle, const Eigen::Vector2d& position) {
  if (!system().pinned(particle)) return;
  system().positions().segment<2>(2 * particle) = position;
  system().velocities().segment<2>(2 * particle).setZero();
}

}  // namespace demo
