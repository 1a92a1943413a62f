// The cancel flag (particles/cancel.h): every long loop of a step and of a
// scene load watches it. Each test raises the flag from inside the work (a
// force's or a constraint's n-th evaluation) and counts what was done after:
// a loop that watches the flag stops within the iteration it was raised in,
// one that does not runs to its end (no clocks, so no timing assertion).
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <string>

#include "particles/cancel.h"
#include "particles/constraints/line.h"
#include "particles/forces/gravity.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "scene_file/scene_file.h"
#include "starting_overlap.h"

namespace {

// Watches a flag of its own for the test's length, and unwatches it after.
class WatchedFlag {
 public:
  WatchedFlag() { particles::setCancelFlag(&flag_); }
  ~WatchedFlag() { particles::setCancelFlag(nullptr); }
  void raise() { flag_ = true; }

 private:
  std::atomic<bool> flag_{false};
};

// A force of no strength that raises the flag at its raiseAt-th evaluation.
class FlagRaisingForce : public particles::Force {
 public:
  FlagRaisingForce(WatchedFlag& flag, int raiseAt) : flag_(flag), raiseAt_(raiseAt) {}
  const char* type() const override { return "flag-raising"; }
  void apply(const particles::Phase&, Eigen::VectorXd&) const override {
    if (++evaluations == raiseAt_) flag_.raise();
  }
  bool hasJacobians() const override { return true; }
  void addJacobians(const particles::Phase&, particles::Triplets&, particles::Triplets&) const override {}
  mutable int evaluations = 0;

 private:
  WatchedFlag& flag_;
  int raiseAt_;
};

// A line constraint that raises the flag at its raiseAt-th evaluation.
class FlagRaisingLine : public particles::LineConstraint {
 public:
  FlagRaisingLine(WatchedFlag& flag, int raiseAt) : LineConstraint(0, Eigen::Vector2d::Zero(), 0.0), flag_(flag), raiseAt_(raiseAt) {}
  void evaluate(const particles::Phase& s, particles::ConstraintRow& row) const override {
    if (++evaluations == raiseAt_) flag_.raise();
    LineConstraint::evaluate(s, row);
  }
  mutable int evaluations = 0;

 private:
  WatchedFlag& flag_;
  int raiseAt_;
};

// One particle falling under gravity.
void addFallingParticle(particles::ParticleSystem& system, double height) {
  system.addParticle(Eigen::Vector2d(0.0, height), 1.0);
  system.addForce(std::make_unique<particles::GravityForce>(Eigen::Vector2d(0.0, -9.81)));
}

particles::IntegratorSettings xpbdSettings(int substeps, int iterations) {
  particles::IntegratorSettings settings;
  settings.xpbd.substeps = substeps;
  settings.xpbd.iterations = iterations;
  return settings;
}

}  // namespace

// xpbd applies a force without a position form once per substep: with the
// flag raised in substep 3 of 1000, the step ends there.
TEST(Cancel, XpbdStopsInTheSubstepTheFlagIsRaisedIn) {
  WatchedFlag flag;
  particles::ParticleSystem system;
  system.addParticle(Eigen::Vector2d(0.0, 1.0), 1.0);
  auto& force = static_cast<FlagRaisingForce&>(system.addForce(std::make_unique<FlagRaisingForce>(flag, 3)));
  const auto xpbd = particles::makeIntegrator("xpbd", xpbdSettings(1000, 1));
  system.step(*xpbd, 0.01);
  EXPECT_EQ(force.evaluations, 3);
}

// Each of xpbd's passes projects every hard constraint once: with the flag
// raised in pass 5 of 10,000 (one substep), the step ends after that pass.
TEST(Cancel, XpbdStopsAfterThePassTheFlagIsRaisedIn) {
  WatchedFlag flag;
  particles::ParticleSystem system;
  addFallingParticle(system, 0.5);
  auto& line = static_cast<FlagRaisingLine&>(system.addConstraint(std::make_unique<FlagRaisingLine>(flag, 5)));
  const auto xpbd = particles::makeIntegrator("xpbd", xpbdSettings(1, 10000));
  system.step(*xpbd, 0.01);
  EXPECT_GE(line.evaluations, 5);
  EXPECT_LE(line.evaluations, 6);  // the pass it was raised in, and at most one evaluation outside the passes
}

// dopri5's attempts (seven evaluations each, up to 100,000 a call): with the
// flag raised in the first attempt, no second one starts.
TEST(Cancel, Dopri5StopsAfterTheAttemptTheFlagIsRaisedIn) {
  WatchedFlag flag;
  particles::ParticleSystem system;
  addFallingParticle(system, 1.0);
  auto& force = static_cast<FlagRaisingForce&>(system.addForce(std::make_unique<FlagRaisingForce>(flag, 2)));
  particles::IntegratorSettings settings;
  settings.dopri5.tolerance = 1e-13;
  const auto dopri5 = particles::makeIntegrator("dopri5", settings);
  system.step(*dopri5, 100.0);  // thousands of attempts at this tolerance
  EXPECT_GE(force.evaluations, 2);
  EXPECT_LE(force.evaluations, 2 + 7);
}

// The reader stops with particles::Cancelled, whatever part of the file it
// is in, and reads the same text once the flag is down.
TEST(Cancel, ReadingASceneFileStopsWithCancelled) {
  std::string text = R"({"particles": [)";
  for (int k = 0; k < 20000; ++k) text += std::string(k ? "," : "") + R"({"position": [)" + std::to_string(k) + ", 0], \"mass\": 1}";
  text += R"(], "colliders": [{"type": "disc", "centre": [0.5, 5], "radius": 0.1}]})";
  {
    WatchedFlag flag;
    flag.raise();
    EXPECT_THROW(scenes::readScene(text, "big"), particles::Cancelled);
  }
  EXPECT_EQ(scenes::readScene(text, "big").system->size(), 20000);
}

// The check of particles starting inside colliders, on its own.
TEST(Cancel, TheStartingOverlapCheckStopsWithCancelledWhenAsked) {
  particles::ParticleSystem system;
  for (int k = 0; k < 10000; ++k) system.addParticle(Eigen::Vector2d(0.01 * k, 0.0), 1.0);
  system.addCollider(particles::Collider::disc(Eigen::Vector2d(0.0, 5.0), 1.0));
  WatchedFlag flag;
  flag.raise();
  EXPECT_THROW(scenes::firstStartingOverlap(system, true), particles::Cancelled);
  EXPECT_FALSE(scenes::firstStartingOverlap(system, false));  // a built-in scene's check is never cut short
}

// A CancelPoll reads the flag on every period-th call, then stays up.
TEST(Cancel, APollReadsTheFlagOncePerPeriodAndRemembersIt) {
  WatchedFlag flag;
  particles::CancelPoll poll(4);
  for (int k = 0; k < 8; ++k) EXPECT_FALSE(poll.poll());
  flag.raise();
  EXPECT_FALSE(poll.poll());
  EXPECT_FALSE(poll.poll());
  EXPECT_FALSE(poll.poll());
  EXPECT_TRUE(poll.poll());  // the 12th call reads it
  particles::setCancelFlag(nullptr);
  EXPECT_TRUE(poll.poll());
}

// The contact solve's sweeps watch the flag: a pile of 400 overlapping discs
// stepped with the flag already up makes no sweep (without it, hundreds).
TEST(Cancel, TheContactSolveMakesNoSweepWithTheFlagUp) {
  for (const bool raised : {false, true}) {
    WatchedFlag flag;
    if (raised) flag.raise();
    particles::ParticleSystem system;
    for (int k = 0; k < 400; ++k) {
      system.addParticle(Eigen::Vector2d(0.015 * (k % 20), 0.015 * (k / 20)), 1.0);
      system.setCollidable(k, 0.01);
    }
    system.addForce(std::make_unique<particles::GravityForce>(Eigen::Vector2d(0.0, -9.81)));
    system.step(*particles::makeIntegrator("symplectic-euler"), 0.01);
    if (raised)
      EXPECT_EQ(system.lastStepStats().contactIterations, 0);
    else
      EXPECT_GT(system.lastStepStats().contactIterations, 0);
  }
}
