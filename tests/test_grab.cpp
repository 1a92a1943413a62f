// The mouse joint's gains (particles/grab.h): what a grabbed particle pulls
// (its tied mass and attached stiffness), the rule that makes k and c from
// them and its stability bounds, and the follow gap of a 5 cm move on the
// cloth and the test chain under every integrator that steps them.
#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "particles/constants.h"
#include "particles/constraints/rod.h"
#include "particles/forces/mouse_spring.h"
#include "particles/forces/spring.h"
#include "particles/forces/wind.h"
#include "particles/grab.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "scene.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;
using test_support::expectRejected;

TEST(GrabReach, TiedMassCountsWhatSpringsAndConstraintsJoinButNotPinsOrWind) {
  // pin 0 —spring 10— 1 —spring 20— 2 —rod— 3;   4 —wind only— 5.
  ParticleSystem system;
  for (int i = 0; i < 6; ++i) system.addParticle(Vector2d(0.1 * i, 0.0), 1.0 + i);
  system.setPinned(0, true);
  system.addForce(std::make_unique<SpringForce>(0, 1, 0.1, 10.0, 0.0));
  system.addForce(std::make_unique<SpringForce>(1, 2, 0.1, 20.0, 0.0));
  system.addConstraint(std::make_unique<RodConstraint>(2, 3, 0.1, RodForm::Squared));
  WindSettings w;
  w.speed = 3.0;
  w.drag = 0.5;
  system.addForce(std::make_unique<WindForce>(std::vector<std::array<int, 2>>{{4, 5}}, w));

  const GrabReach one = grabReach(system, 1);
  EXPECT_EQ(one.mass, 2.0);
  EXPECT_EQ(one.tiedMass, 2.0 + 3.0 + 4.0);  // not the pin's
  EXPECT_NEAR(one.stiffness, 30.0, 1e-12);   // both springs along x, far ends held
  const GrabReach three = grabReach(system, 3);
  EXPECT_EQ(three.tiedMass, 9.0);
  EXPECT_EQ(three.stiffness, 0.0);  // a rod is a constraint, not a stiffness
  EXPECT_TRUE(three.constrained);
  EXPECT_FALSE(one.constrained);  // springs only; the rod holds 2 and 3
  const GrabReach four = grabReach(system, 4);
  EXPECT_EQ(four.tiedMass, 5.0);  // the wind pushes, it does not tie
  EXPECT_EQ(four.stiffness, 0.0);
  // The joint being replaced is left out.
  const Force& mouse = system.addForce(std::make_unique<MouseSpringForce>(1, Vector2d(0.1, 0.0), 500.0, 1.0));
  EXPECT_NEAR(grabReach(system, 1, &mouse).stiffness, 30.0, 1e-12);
  EXPECT_NEAR(grabReach(system, 1).stiffness, 530.0, 1e-12);
}

TEST(MouseSpringGains, TheLargerOfTheTiedBodysJointAndTheAttachedStiffnessWithinTheStep) {
  MouseJointSettings joint;  // 5 Hz, ζ = 0.7, ρ = 9
  const double omega = 2.0 * kPi * 5.0;
  // A heavy body on soft springs: Box2D's joint on the tied mass.
  GrabReach reach{0.1, 2.0, 10.0};
  MouseSpringGains g = mouseSpringGains(reach, joint, 0.0);
  EXPECT_NEAR(g.stiffness, 2.0 * omega * omega, 1e-9);
  EXPECT_NEAR(g.damping, 2.0 * 0.7 * 2.0 * omega, 1e-9);
  // A light particle held by stiff springs: nine times their stiffness.
  reach = {0.01, 0.5, 1000.0};
  g = mouseSpringGains(reach, joint, 0.0);
  EXPECT_NEAR(g.stiffness, 9000.0, 1e-9);
  EXPECT_NEAR(g.damping, 2.0 * 0.7 * std::sqrt(9000.0 * 0.5), 1e-9);
  // Applied explicitly over h = 2 ms: √(k/m) h ≤ 1 and c h/m ≤ 1/2.
  g = mouseSpringGains(reach, joint, 0.002);
  EXPECT_NEAR(g.stiffness, 0.01 / (0.002 * 0.002), 1e-9);
  EXPECT_NEAR(g.damping, 0.5 * 0.01 / 0.002, 1e-12);
  // ... and √(k/m) h ≤ 0.4 where a constraint holds the particle.
  GrabReach held = reach;
  held.constrained = true;
  EXPECT_NEAR(mouseSpringGains(held, joint, 0.002).stiffness, 0.16 * 0.01 / (0.002 * 0.002), 1e-9);
  // A ratio of 0 and a heavy particle: Box2D's joint, within the bounds.
  joint.stiffnessRatio = 0.0;
  g = mouseSpringGains(GrabReach{1.0, 1.0, 1e6}, joint, 0.002);
  EXPECT_NEAR(g.stiffness, omega * omega, 1e-9);
}

TEST(MouseSpringGains, OverflowAndBadSettingsAreRejectedNamingTheValue) {
  expectRejected([] { mouseSpringGains(GrabReach{7e306, 7e306, 0.0}, MouseJointSettings{}, 0.0); },
                 "overflows for mass 7e+306");
  expectRejected([] { mouseSpringGains(GrabReach{0.0, 1.0, 0.0}, MouseJointSettings{}, 0.0); }, "grabbed mass");
  MouseJointSettings bad;
  bad.frequency = std::nan("");
  expectRejected([&] { mouseSpringGains(GrabReach{1.0, 1.0, 0.0}, bad, 0.0); }, "mouse joint frequency");
  bad = MouseJointSettings{};
  bad.stiffnessRatio = -1.0;
  expectRejected([&] { mouseSpringGains(GrabReach{1.0, 1.0, 0.0}, bad, 0.0); }, "mouse joint stiffness ratio");
}

TEST(Integrators, ImplicitEulerAndXpbdTakeTheJointImplicitlyTheOthersOverTheirStep) {
  for (const IntegratorInfo& info : integratorTable()) {
    const double h = explicitForceStep(info.name, 0.01);
    if (std::string(info.name) == "implicit-euler" || std::string(info.name) == "xpbd")
      EXPECT_EQ(h, 0.0) << info.name;
    else
      EXPECT_EQ(h, 0.01) << info.name;
  }
}

namespace {

// Runs `scene` for 0.5 s, grabs its lowest movable particle (the rightmost of
// equals) with the joint's gains under `integrator`, holds 2 s, moves the
// target 5 cm to the right over 0.1 s and holds 2 s more. Returns the follow
// gap |Δx̄ − Δt| / 5 cm, x̄ the particle's mean position over the last second
// of each hold; a negative value when the run fails or leaves the scene.
double followGap(const std::string& scene, const std::string& integrator) {
  scenes::Scene built = scenes::buildScene(scene);
  ParticleSystem& s = *built.system;
  const auto stepper = makeIntegrator(integrator, built.integratorSettings);
  const double dt = built.dt;
  bool failed = false;
  const auto run = [&](double seconds, auto&& each) {
    const int steps = static_cast<int>(std::lround(seconds / dt));
    for (int k = 0; k < steps && !failed; ++k) {
      each(k, steps);
      failed = s.step(*stepper, dt).failure != StepFailure::None || !s.finite() ||
               s.positions().cwiseAbs().maxCoeff() > 100.0;
    }
  };
  run(0.5, [](int, int) {});
  int pick = -1;
  for (int i = 0; i < s.size(); ++i)
    if (!s.pinned(i) && (pick < 0 || s.position(i).y() < s.position(pick).y() ||
                         (s.position(i).y() == s.position(pick).y() && s.position(i).x() > s.position(pick).x())))
      pick = i;
  const Vector2d start = s.position(pick);
  const MouseSpringGains gains =
      mouseSpringGains(grabReach(s, pick), MouseJointSettings{}, explicitForceStep(stepper->name(), dt));
  auto& mouse = static_cast<MouseSpringForce&>(
      s.addForce(std::make_unique<MouseSpringForce>(pick, start, gains.stiffness, gains.damping)));
  Vector2d before = Vector2d::Zero(), after = Vector2d::Zero();
  const int lastSecond = static_cast<int>(std::lround(1.0 / dt));
  run(2.0, [&](int k, int steps) {
    if (k >= steps - lastSecond) before += s.position(pick) / lastSecond;
  });
  run(0.1, [&](int k, int steps) { mouse.setTarget(start + Vector2d(0.05 * (k + 1) / steps, 0.0)); });
  run(2.0, [&](int k, int steps) {
    if (k >= steps - lastSecond) after += s.position(pick) / lastSecond;
  });
  if (failed) return -1.0;
  return ((after - before) - Vector2d(0.05, 0.0)).norm() / 0.05;
}

bool stepsWithoutAGrab(const std::string& scene, const std::string& integrator) {
  scenes::Scene built = scenes::buildScene(scene);
  const auto stepper = makeIntegrator(integrator, built.integratorSettings);
  const int steps = static_cast<int>(std::lround(4.6 / built.dt));
  for (int k = 0; k < steps; ++k)
    if (built.system->step(*stepper, built.dt).failure != StepFailure::None || !built.system->finite() ||
        built.system->positions().cwiseAbs().maxCoeff() > 100.0)
      return false;
  return true;
}

}  // namespace

// A cloth particle is held by its springs (the joint is nine times their
// stiffness, within the step's bound), a chain's by its rods (the joint is
// Box2D's on the chain's whole mass). Every integrator that steps the scene
// steps it with the grab, and the particle follows the move to within 10%.
TEST(Grab, FollowsAFiveCentimetreMoveWithinTenPercentUnderEveryIntegrator) {
  for (const char* scene : {"cloth", "test-chain"})
    for (const IntegratorInfo& info : integratorTable()) {
      SCOPED_TRACE(std::string(scene) + " under " + info.name);
      if (!stepsWithoutAGrab(scene, info.name)) continue;  // explicit Euler on both, Verlet on the chain
      const double gap = followGap(scene, info.name);
      std::printf("%s under %s: steady gap %.2f%% of the move\n", scene, info.name, 100.0 * gap);
      EXPECT_GE(gap, 0.0) << "the grab made the run fail";
      EXPECT_LE(gap, 0.10);
    }
}
