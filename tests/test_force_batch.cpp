// The force batches (flat arrays, one loop per force type) give the same bits
// as the plain loop over force objects, for every built-in scene, and a torn
// spring drops out of forces, potential and Jacobians.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

#include "particles/forces/force_batch.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "scene.h"

namespace {

using particles::ParticleSystem;

// f = Σ force->apply, the evaluation before the batches.
Eigen::VectorXd plainForces(const ParticleSystem& system) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(system.positions().size());
  for (const auto& force : system.forceObjects()) force->apply(system.phase(), f);
  return f;
}

// Bit equality of two vectors (EXPECT_EQ on doubles is exact).
void expectSameBits(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (Eigen::Index k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << what << " entry " << k;
}

TEST(ForceBatch, EveryBuiltInSceneGivesThePlainLoopsForcesAndAccelerationsBitForBit) {
  for (const scenes::SceneInfo& info : scenes::sceneTable()) {
    scenes::Scene scene = scenes::buildScene(info.name);
    ParticleSystem& system = *scene.system;
    auto integrator = particles::makeIntegrator("rk4");
    for (int k = 0; k < 5; ++k) system.step(*integrator, scene.dt);  // moving, stretched springs
    particles::ForceBatches batches;
    batches.update(system.forceObjects(), system.structureStamp());
    Eigen::VectorXd f;
    batches.apply(system.phase(), f, false);
    expectSameBits(f, plainForces(system), info.name);
    if (std::string(info.name) == "cloth") EXPECT_GT(batches.springs().size(), 100) << "cloth springs batched";
    if (system.constraints().empty()) {
      Eigen::VectorXd a;
      system.acceleration(system.positions(), system.velocities(), a);
      Eigen::VectorXd plainA = plainForces(system);
      for (int i = 0; i < system.size(); ++i) plainA.segment<2>(2 * i) *= system.inverseMasses()[i];
      expectSameBits(a, plainA, std::string(info.name) + " a");
      expectSameBits(system.forces(), plainForces(system), std::string(info.name) + " f");
    }
  }
}

// Two particles on a spring, stretched: tearing it leaves gravity alone.
TEST(ForceBatch, ATornSpringAddsNoForcePotentialOrJacobianAndMendsBack) {
  ParticleSystem system;
  system.addParticle({0.0, 0.0}, 1.0);
  system.addParticle({2.0, 0.0}, 1.0);
  particles::Force& spring = system.addForce(std::make_unique<particles::SpringForce>(0, 1, 1.0, 10.0, 0.0));
  system.addForce(std::make_unique<particles::GravityForce>(Eigen::Vector2d(0.0, -9.81)));
  Eigen::VectorXd a;
  system.acceleration(system.positions(), system.velocities(), a);
  EXPECT_DOUBLE_EQ(a[0], 10.0);  // k (|l| − r) / m = 10 · 1 / 1, towards particle 1
  EXPECT_DOUBLE_EQ(system.potentialEnergy(), 5.0);
  system.setSpringEnabled(&spring, false);
  system.acceleration(system.positions(), system.velocities(), a);
  EXPECT_EQ(a[0], 0.0);
  EXPECT_EQ(a[2], 0.0);
  EXPECT_DOUBLE_EQ(a[1], -9.81);
  EXPECT_EQ(system.potentialEnergy(), 0.0);
  particles::Triplets dfdx, dfdv;
  spring.addJacobians(system.phase(), dfdx, dfdv);
  EXPECT_TRUE(dfdx.empty());
  system.setSpringEnabled(&spring, true);
  system.acceleration(system.positions(), system.velocities(), a);
  EXPECT_DOUBLE_EQ(a[0], 10.0);
  EXPECT_THROW(system.setSpringEnabled(system.forceObjects()[1].get(), false), std::invalid_argument);
  ParticleSystem other;
  EXPECT_THROW(other.setSpringEnabled(&spring, false), std::invalid_argument);
}

}  // namespace
