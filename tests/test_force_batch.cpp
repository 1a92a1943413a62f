// The force batches (flat arrays, one loop per force type) give the same bits
// as the plain loop over force objects, for every built-in scene, and a torn
// spring drops out of forces, potential and Jacobians.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <stdexcept>

#include "particles/forces/force_batch.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "particles/threads.h"
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
    if (std::string(info.name) == "cloth") {
      EXPECT_GT(batches.springs().size(), 100) << "cloth springs batched";
    }
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

namespace {

int threadsOfThisProcess() {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) n += entry.is_directory();
  return n;
}

// A cloth big enough for the parallel paths (kParallelSprings springs,
// kParallelParticles particles): 80 × 80 particles, 8-way springs.
std::unique_ptr<ParticleSystem> bigCloth() {
  auto s = std::make_unique<ParticleSystem>();
  const int w = 80;
  std::vector<Eigen::Vector2d> x;
  for (int r = 0; r < w; ++r)
    for (int c = 0; c < w; ++c) x.emplace_back(0.05 * c + 0.001 * r * r, -0.05 * r);
  s->addParticles(x, std::vector<double>(x.size(), 0.2));
  for (int c = 0; c < w; ++c) s->setPinned(c, true);
  for (int r = 0; r < w; ++r)
    for (int c = 0; c < w; ++c) {
      auto spring = [&](int r2, int c2, double rest) {
        s->addForce(std::make_unique<particles::SpringForce>(r * w + c, r2 * w + c2, rest, 50.0, 0.5));
      };
      if (c + 1 < w) spring(r, c + 1, 0.05);
      if (r + 1 < w) spring(r + 1, c, 0.05);
      if (r + 1 < w && c + 1 < w) spring(r + 1, c + 1, 0.0707);
      if (r + 1 < w && c > 0) spring(r + 1, c - 1, 0.0707);
    }
  s->addForce(std::make_unique<particles::GravityForce>(Eigen::Vector2d(0.0, -9.81)));
  return s;
}

}  // namespace

// With one thread no parallel region is entered: the process keeps its one thread.
TEST(ForceBatchThreads, OneThreadNeverStartsAThread) {
  ASSERT_EQ(threadsOfThisProcess(), 1) << "the test process starts with one thread";
  particles::setThreadCount(1);
  auto cloth = bigCloth();
  auto integrator = particles::makeIntegrator("rk4");
  for (int k = 0; k < 3; ++k) cloth->step(*integrator, 0.001);
  EXPECT_EQ(threadsOfThisProcess(), 1);
  EXPECT_THROW(particles::setThreadCount(0), std::invalid_argument);
}

// Every integrator on the big cloth and every built-in scene (that it accepts): 2 and 3
// threads give the one-thread trajectory bit for bit.
TEST(ForceBatchThreads, ThreadedTrajectoriesEqualOneThreadBitForBit) {
  std::vector<std::string> integrators;
  for (const particles::IntegratorInfo& info : particles::integratorTable()) integrators.push_back(info.name);
  auto run = [&](int threads, const std::string& scene, const std::string& integratorName) {
    particles::setThreadCount(threads);
    std::unique_ptr<ParticleSystem> system;
    double dt = 0.001;
    scenes::Scene built;
    if (scene == "big-cloth") {
      system = bigCloth();
    } else {
      built = scenes::buildScene(scene);
      system = std::move(built.system);
      dt = built.dt;
    }
    auto integrator = particles::makeIntegrator(integratorName);
    for (int k = 0; k < 10; ++k) system->step(*integrator, dt);
    Eigen::VectorXd state(2 * system->positions().size());
    state << system->positions(), system->velocities();
    return state;
  };
  std::vector<std::string> sceneNames = {"big-cloth"};
  for (const scenes::SceneInfo& info : scenes::sceneTable()) sceneNames.push_back(info.name);
  for (const std::string& scene : sceneNames)
    for (const std::string& integrator : integrators) {
      Eigen::VectorXd one;
      try {
        one = run(1, scene, integrator);
      } catch (const std::invalid_argument&) {
        continue;  // an integrator that refuses the scene (at setup) refuses it on any thread count
      }
      for (int threads : {2, 3}) expectSameBits(run(threads, scene, integrator), one, scene + " " + integrator + " threads " + std::to_string(threads));
    }
  particles::setThreadCount(1);
}
