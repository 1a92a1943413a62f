#include "simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "particles/check.h"
#include "particles/constants.h"
#include "particles/forces/polygon_area.h"
#include "particles/tearing.h"

namespace demo {

particles::DivergenceLimits demoDivergenceLimits(const scenes::Scene& scene) {
  const double diagonal = (scene.viewMax - scene.viewMin).norm();
  particles::DivergenceLimits limits;
  limits.maxRelativeConstraintError = 1.0;
  limits.maxConstraintError = 1.0 * diagonal;
  limits.maxCoordinate = 1000.0 * diagonal;
  limits.maxSolveResidual = 10.0;  // as the runner's (cli/step_output.h)
  return limits;
}

int integratorIndexByName(const std::string& name) {
  return static_cast<int>(&particles::requireIntegrator(name) - particles::integratorTable().data());
}

Simulation::Simulation(scenes::Scene scene, int integratorIndex, double dt)
    : scene_(std::move(scene)), integratorIndex_(-1), dt_(0.0), limits_(demoDivergenceLimits(scene_)) {
  setIntegrator(integratorIndex);
  setDt(dt);
  history_.record(frames_, system(), owedTime_, steps_);
  for (const auto& face : scene_.faces) restFaceAreas_.push_back(faceArea(system().phase(), face));
  intactFaces_.assign(scene_.faces.size(), 1);
  // A scene file's wind: its edges are where the wind can blow again once stopped.
  for (const auto& force : system().forceObjects())
    if (auto* wind = dynamic_cast<particles::WindForce*>(force.get())) {
      wind_ = wind;
      if (scene_.windEdges.empty()) scene_.windEdges = wind->edges();
    }
}

double faceArea(const particles::Phase& s, const std::array<int, 4>& f) {
  return particles::ringArea(s.x, f.data(), f.size());
}

void Simulation::setIntegrator(int index) {
  const auto& table = particles::integratorTable();
  if (index < 0 || index >= static_cast<int>(table.size()))
    throw std::invalid_argument("integrator index out of range");
  integrator_ = table[index].make();
  integrator_->configure(integratorSettings_);
  integratorIndex_ = index;
  refusal_.reset();
  retuneGrab();
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
  retuneGrab();
}

void Simulation::beginFrame(double frameTime, StepMode mode) {
  lastFrame_ = {};
  frameMode_ = mode;
  frameTime_ = frameTime;
  if (stopped()) return;
  // Fixed simulated time per frame: the frame rate changes how often this
  // runs, never what it computes. Time short of a whole dt carries over.
  if (mode == StepMode::Lockstep) lockstepOwed_ = true;
  else owedTime_ += frameTime;
}

double Simulation::drawnFraction(double frameTime) const {
  const bool between = frameTime > 0.0 && dt_ > frameTime && frameMode_ == StepMode::FixedTime && !stopped() &&
                       previousX_.size() == system().positions().size();
  return between ? std::clamp(owedTime_ / dt_, 0.0, 1.0) : 1.0;
}

bool Simulation::owesStep() const {
  if (stopped()) return false;
  return frameMode_ == StepMode::Lockstep ? lockstepOwed_ : owedTime_ >= dt_ * (1.0 - 1e-9);
}

double Simulation::takeStep() {
  const auto start = std::chrono::steady_clock::now();
  stepAndWatch();
  if (frameMode_ == StepMode::Lockstep) lockstepOwed_ = false;
  else if (!stopped()) owedTime_ -= dt_;
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  lastFrame_.simulationMs += ms;
  lastFrame_.longestStepMs = std::max(lastFrame_.longestStepMs, ms);
  return ms;
}

void Simulation::endFrame(bool budgetSpent) {
  if (stopped()) return;
  if (spring_) {
    grabTrail_.push_back(system().position(spring_->particle()));
    if (grabTrail_.size() > grabTrailFrames) grabTrail_.pop_front();
  }
  if (budgetSpent && owesStep()) {
    lastFrame_.capped = true;
    lastFrame_.waited = lastFrame_.substeps == 0;
    framesWaited_ += lastFrame_.waited;
    if (frameMode_ == StepMode::FixedTime) owedTime_ = 0.0;
  }
  ++frames_;
  history_.record(frames_, system(), owedTime_, steps_);
  trace_.add(sceneEnergy(), system().maxConstraintError());
}

void Simulation::stepOnce() {
  if (stopped()) return;
  lastFrame_ = {};
  stepAndWatch();
  if (!stopped()) trace_.add(sceneEnergy(), system().maxConstraintError());
}

double Simulation::mouseSpringEnergy() const {
  return spring_ ? spring_->potential(system().phase()) : 0.0;
}

void Simulation::stepAndWatch() {
  particles::StepStats stats;
  // Kept only while steps are longer than frames, the one case drawn between them.
  if (frameMode_ == StepMode::FixedTime && dt_ > frameTime_) previousX_ = system().positions();
  else previousX_.resize(0);
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
  if (stats.directFallbacks > 0 && !noticedFallback_) {
    noticedFallback_ = true;
    notice_ = particles::directFallbackMessage(static_cast<int>(system().constraints().size()),
                                               system().solver().settings);
  }
  // The energy test is off (energyScale infinite), so E₀ is not needed.
  divergence_ = particles::checkDivergence(system(), limits_, 0.0, stats);
  if (divergence_) {
    divergedAt_ = system().time();
    owedTime_ = 0.0;
    // The plots end where the HUD's numbers are: at the state that diverged.
    trace_.add(sceneEnergy(), system().maxConstraintError());
  }
}

bool Simulation::rewindTo(long long frame) {
  const RewindEntry* entry = history_.rewindTo(frame);
  if (!entry) return false;
  system().restore(entry->state);
  owedTime_ = entry->owedTime;
  steps_ = entry->steps;
  frames_ = entry->frame;
  divergedAt_.reset();
  divergence_ = {};
  trace_.clear();  // the plotted past belongs to the future just dropped
  lastFrame_ = {};
  return true;
}

void Simulation::copyStateFrom(const Simulation& other) {
  system().restore(other.system().snapshot());
  system().breakLinks(other.system().brokenLinks());
  system().tearing() = other.system().tearing();
  setWind(other.wind_ ? std::optional<particles::WindSettings>(other.wind_->settings()) : std::nullopt);
  for (int i = 0; i < system().size(); ++i)
    if (system().pinned(i) != other.system().pinned(i)) system().setPinned(i, other.system().pinned(i));
  system().restore(other.system().snapshot());  // pinning zeroes velocities; take them back
  owedTime_ = other.owedTime_;
  steps_ = other.steps_;
  frames_ = other.frames_;
  history_ = other.history_;
  trace_ = other.trace_;
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

particles::MouseSpringGains Simulation::grabGains(int particle, const particles::MouseJointSettings& joint) const {
  return particles::mouseSpringGains(particles::grabReach(system(), particle, spring_), joint,
                                     particles::explicitForceStep(integrator_->name(), dt_));
}

void Simulation::grab(int particle, const Eigen::Vector2d& target, const particles::MouseJointSettings& joint) {
  const particles::MouseSpringGains gains = grabGains(particle, joint);
  if (!spring_ || spring_->particle() != particle) grabTrail_.clear();
  // A copy first: retuning passes the held spring's own target, which
  // release() frees (a new dt or integrator while a particle was held read it after).
  const Eigen::Vector2d at = target;
  release();
  auto spring = std::make_unique<particles::MouseSpringForce>(particle, at, gains.stiffness, gains.damping);
  spring_ = spring.get();
  joint_ = joint;
  system().addForce(std::move(spring));
}

void Simulation::retuneGrab() {
  if (spring_) grab(spring_->particle(), spring_->target(), joint_);
}

void Simulation::moveGrab(const Eigen::Vector2d& target) {
  if (spring_) spring_->setTarget(target);
}

Eigen::Vector2d Simulation::grabbedMean() const {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& x : grabTrail_) sum += x;
  return grabTrail_.empty() ? sum : Eigen::Vector2d(sum / static_cast<double>(grabTrail_.size()));
}

void Simulation::release() {
  if (!spring_) return;
  system().removeForce(spring_);
  spring_ = nullptr;
}

void Simulation::setWind(const std::optional<particles::WindSettings>& settings) {
  if (!settings) {
    if (wind_) system().removeForce(wind_);
    wind_ = nullptr;
    return;
  }
  if (wind_) {
    wind_->setSettings(*settings);
    return;
  }
  if (!takesWind()) throw std::invalid_argument("wind blows on the cloth and the hair: this scene has no edges for it");
  const particles::LinkSet broken(system().brokenLinks());
  std::vector<std::array<int, 2>> edges;
  for (const auto& edge : scene_.windEdges)
    if (!broken.contains(edge[0], edge[1])) edges.push_back(edge);
  auto wind = std::make_unique<particles::WindForce>(std::move(edges), *settings);
  wind_ = wind.get();
  system().addForce(std::move(wind));
}

void Simulation::setTearStrain(double strain) {
  particles::TearSettings tearing;
  tearing.strain = strain;
  tearing.validate();
  system().tearing() = tearing;
}

const std::vector<char>& Simulation::intactFaces() const {
  const auto& broken = system().brokenLinks();
  if (facesCheckedAtBreaks_ != broken.size()) {
    const particles::LinkSet set(broken);
    for (std::size_t k = 0; k < scene_.faces.size(); ++k) {
      const auto& f = scene_.faces[k];
      bool intact = true;
      for (int c = 0; c < 4; ++c) intact = intact && !set.contains(f[c], f[(c + 1) % 4]);
      intactFaces_[k] = intact;
    }
    facesCheckedAtBreaks_ = broken.size();
  }
  return intactFaces_;
}

void Simulation::setPinned(int particle, bool pinned) {
  if (spring_ && spring_->particle() == particle && pinned) release();
  system().setPinned(particle, pinned);
}

void Simulation::placePinned(int particle, const Eigen::Vector2d& position) {
  if (!system().pinned(particle)) return;
  system().setPosition(particle, position);
  system().setVelocity(particle, Eigen::Vector2d::Zero());
}

}  // namespace demo
