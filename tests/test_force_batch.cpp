// The force batches (flat arrays, one loop per force type) give each spring's
// force as the same bits as its force object, and the plain loop over force
// objects' sums to rounding (the springs' terms are added in runs, in another
// order), for every built-in scene; a torn spring drops out of forces,
// potential and Jacobians.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>

#include "particles/constraints/rod.h"
#include "forces/force_batch.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "forces/spring_batch.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "thread_balance.h"
#include "particles/threads.h"
#include "scene.h"
#include "system_internals.h"

namespace {

using particles::ParticleSystem;

// Bit equality of two vectors (EXPECT_EQ on doubles is exact).
void expectSameBits(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (Eigen::Index k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << what << " entry " << k;
}

// Two sums of the same m terms t_k in different orders differ by at most
// (m − 1) ε Σ|t_k| (each is within (m − 1) u Σ|t_k| of the exact sum, u = ε/2).
// The terms of entry e are the force objects' contributions to it, each
// object applied alone; scale multiplies both sums (a = w f).
void expectEqualToRounding(const ParticleSystem& system, const Eigen::VectorXd& batched, const Eigen::VectorXd& scale,
                           const std::string& what) {
  const Eigen::Index size = system.positions().size();
  Eigen::VectorXd plain = Eigen::VectorXd::Zero(size), magnitude = Eigen::VectorXd::Zero(size);
  Eigen::VectorXd terms = Eigen::VectorXd::Zero(size);
  for (const auto& force : system.forceObjects()) {
    Eigen::VectorXd one = Eigen::VectorXd::Zero(size);
    force->apply(system.phase(), one);
    plain += one;
    magnitude += one.cwiseAbs();
    terms += (one.array() != 0.0).cast<double>().matrix();
  }
  const double eps = std::numeric_limits<double>::epsilon();
  int differing = 0;
  for (Eigen::Index e = 0; e < size; ++e) {
    const double bound = std::max(terms[e] - 1.0, 0.0) * eps * magnitude[e] * std::abs(scale[e]);
    ASSERT_LE(std::abs(batched[e] - plain[e] * scale[e]), bound)
        << what << " entry " << e << ": " << terms[e] << " terms of magnitude " << magnitude[e];
    differing += batched[e] != plain[e] * scale[e];
  }
  std::printf("%s: %d of %lld entries differ from the plain loop's, within (m - 1) eps sum|t|\n", what.c_str(),
              differing, static_cast<long long>(size));
}

TEST(ForceBatch, EveryBuiltInSceneGivesThePlainLoopsForcesAndAccelerationsToRounding) {
  for (const scenes::SceneInfo& info : scenes::sceneTable()) {
    scenes::Scene scene = scenes::buildScene(info.name);
    ParticleSystem& system = *scene.system;
    auto integrator = particles::makeIntegrator("rk4");
    for (int k = 0; k < 5; ++k) system.step(*integrator, scene.dt);  // moving, stretched springs
    particles::ForceBatches batches;
    batches.update(system.forceObjects(), system.structureStamp());
    Eigen::VectorXd f;
    batches.apply(system.phase(), f);
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(f.size());
    expectEqualToRounding(system, f, ones, info.name);
    if (std::string(info.name) == "cloth") {
      EXPECT_GT(batches.springCount(), 100) << "cloth springs batched";
      ASSERT_EQ(batches.springBatches().size(), 1u);
      EXPECT_EQ(batches.springBatches()[0].springsInRuns(), batches.springCount()) << "every cloth spring in a run";
    }
    if (system.constraints().empty()) {
      Eigen::VectorXd a;
      system.acceleration(system.positions(), system.velocities(), a);
      Eigen::VectorXd w(f.size());
      for (int i = 0; i < system.size(); ++i) w.segment<2>(2 * i).setConstant(system.inverseMasses()[i]);
      expectEqualToRounding(system, a, w, std::string(info.name) + " a");
      expectEqualToRounding(system, system.forces(), ones, std::string(info.name) + " f");
    }
  }
}

// Springs (p, p + n/2) for p < n/2: one run whose particles each have one
// spring, so f holds each spring's force itself, with no sum to round. Random
// lengths (one of them 0: no force) and velocities; parameters equal on the
// first half of the run (its uniform loop) and varying on the second.
TEST(ForceBatch, EverySpringsForceInARunIsItsForceObjectsBitForBit) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (bool uniform : {true, false}) {
    const int half = 40;
    ParticleSystem system;
    for (int p = 0; p < 2 * half; ++p)
      system.addParticle({coordinate(random), coordinate(random)}, 1.0, {coordinate(random), coordinate(random)});
    system.setPosition(half + 3, system.position(3));
    for (int p = 0; p < half; ++p) {
      const double k = uniform ? 1.0 : 1.0 + p;
      system.addForce(std::make_unique<particles::SpringForce>(p, p + half, 0.5 * k, 30.0 * k, 0.2 * k));
    }
    particles::ForceBatches batches;
    batches.update(system.forceObjects(), system.structureStamp());
    ASSERT_EQ(batches.springBatches()[0].runs(), 1);
    Eigen::VectorXd f;
    batches.apply(system.phase(), f);
    for (int p = 0; p < half; ++p) {
      const Eigen::Vector2d expected =
          particles::springForce(system.position(p) - system.position(p + half),
                                 system.velocity(p) - system.velocity(p + half), 0.5 * (uniform ? 1.0 : 1.0 + p),
                                 30.0 * (uniform ? 1.0 : 1.0 + p), 0.2 * (uniform ? 1.0 : 1.0 + p));
      ASSERT_EQ(f[2 * p], expected.x()) << "spring " << p << (uniform ? " uniform" : " varying");
      ASSERT_EQ(f[2 * p + 1], expected.y()) << "spring " << p;
      ASSERT_EQ(f[2 * (p + half)], -expected.x()) << "spring " << p;
      ASSERT_EQ(f[2 * (p + half) + 1], -expected.y()) << "spring " << p;
    }
    EXPECT_EQ(f.segment<2>(2 * 3).norm(), 0.0) << "a spring of length 0 has no force";
    EXPECT_GT(f.norm(), 1.0);
  }
}

// The runs are found in any order of the force list: a shuffled 8-way cloth
// gives the same runs, so the same bits.
TEST(ForceBatch, TheSpringsOrderInTheListDoesNotChangeTheBatchedForce) {
  scenes::Scene scene = scenes::buildScene("cloth");
  ParticleSystem& system = *scene.system;
  auto integrator = particles::makeIntegrator("rk4");
  for (int k = 0; k < 5; ++k) system.step(*integrator, scene.dt);
  ParticleSystem shuffled;
  std::vector<Eigen::Vector2d> x;
  for (int i = 0; i < system.size(); ++i) x.push_back(system.position(i));
  shuffled.addParticles(x, std::vector<double>(x.size(), system.masses()[0]));
  shuffled.setVelocities(system.velocities());
  std::vector<const particles::SpringForce*> springs;
  for (const auto& force : system.forceObjects())
    if (const auto* s = dynamic_cast<const particles::SpringForce*>(force.get())) springs.push_back(s);
  std::shuffle(springs.begin(), springs.end(), std::mt19937(3));
  for (const particles::SpringForce* s : springs)
    shuffled.addForce(std::make_unique<particles::SpringForce>(s->first(), s->second(), s->restLength(),
                                                               s->stiffness(), s->damping()));
  particles::ForceBatches inOrder, outOfOrder;
  inOrder.update(system.forceObjects(), system.structureStamp());
  outOfOrder.update(shuffled.forceObjects(), shuffled.structureStamp());
  Eigen::VectorXd a, b;
  outOfOrder.apply(shuffled.phase(), b);
  // The scene's list also holds gravity and drag after its springs: compare
  // the springs' segment alone.
  inOrder.springBatches()[0].apply(system.phase(), a, true);
  expectSameBits(a, b, "shuffled cloth");
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
// kParallelParticles particles): 80 × 80 particles, 8-way springs; with
// colliders, 96 × 96 at rest with its grid's sides as collision edges, its
// bottom row 0.2 mm above a box it meets within ten 1 ms steps (and a disc
// below), for the contact broad phase's parallel blocks (kParallelEntries
// particles and edges). With ties, 400 springs more join scattered pairs of
// particles: too few of one stride to make runs, they take the gathered path.
std::unique_ptr<ParticleSystem> bigCloth(bool colliders = false, bool ties = false) {
  auto s = std::make_unique<ParticleSystem>();
  const int w = colliders ? 96 : 80;
  std::vector<Eigen::Vector2d> x;
  for (int r = 0; r < w; ++r)
    for (int c = 0; c < w; ++c) x.emplace_back(0.05 * c + (colliders ? 0.0 : 0.001 * r * r), -0.05 * r);  // on colliders: at rest
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
  if (ties)
    for (int k = 0; k < 400; ++k) {
      const int i = (k * 7919) % (w * w), j = (k * 104729 + 13) % (w * w);
      if (i != j) s->addForce(std::make_unique<particles::SpringForce>(i, j, 0.1, 5.0, 0.1));
    }
  s->addForce(std::make_unique<particles::GravityForce>(Eigen::Vector2d(0.0, -9.81)));
  if (colliders) {
    s->addCollider(particles::Collider::box(Eigen::Vector2d(-1.0, -5.2), Eigen::Vector2d(6.0, -4.7502)));
    s->addCollider(particles::Collider::disc(Eigen::Vector2d(2.4, -5.6), 0.3));
    for (int r = 0; r < w; ++r)
      for (int c = 0; c < w; ++c) {
        if (c + 1 < w) s->addCollisionEdge(r * w + c, r * w + c + 1);
        if (r + 1 < w) s->addCollisionEdge(r * w + c, (r + 1) * w + c);
      }
  }
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

// The shares follow the threads' measured speeds: equal at first, then 2 : 1 when thread 0 does its
// items twice as fast, never below a quarter of an equal share, unchanged by a pass with nothing
// measured; the bounds cover [0, n) in order.
TEST(ThreadBalance, SharesFollowTheThreadsSpeeds) {
  particles::ThreadBalance balance;
  EXPECT_EQ(balance.bounds(1000, 2), (std::vector<int>{0, 500, 1000}));
  for (int pass = 0; pass < 100; ++pass) {
    const std::vector<int> b = balance.bounds(1000, 2);
    const double items0 = b[1] - b[0], items1 = b[2] - b[1];
    balance.update({items0, items1}, {items0 / 2.0, items1 / 1.0});  // thread 0: 2 items a second, thread 1: 1
  }
  const std::vector<double> cuts = balance.cuts(2);
  EXPECT_NEAR(cuts[1], 2.0 / 3.0, 1e-6);
  EXPECT_EQ(cuts.front(), 0.0);
  EXPECT_EQ(cuts.back(), 1.0);
  balance.update({0.0, 10.0}, {0.0, 1.0});  // nothing measured on thread 0: kept
  EXPECT_NEAR(balance.cuts(2)[1], 2.0 / 3.0, 1e-6);
  for (int pass = 0; pass < 100; ++pass) balance.update({1.0, 1.0}, {1.0, 1e9});  // thread 1 all but stopped
  // Thread 1 keeps about an eighth (a quarter of an equal share, before the shares are renormalised).
  EXPECT_GT(1.0 - balance.cuts(2)[1], 0.11);
  EXPECT_LT(1.0 - balance.cuts(2)[1], 0.13);
  const std::vector<int> three = balance.bounds(10, 3);  // another thread count starts equal again
  EXPECT_EQ(three.front(), 0);
  EXPECT_EQ(three.back(), 10);
  EXPECT_TRUE(std::is_sorted(three.begin(), three.end()));
  EXPECT_NEAR(balance.cuts(3)[1], 1.0 / 3.0, 1e-12);
}

namespace {
// n particles at random in [−10, 10]², moving at random in [−1, 1]² (seeded).
void scatter(int n, unsigned seed, Eigen::VectorXd& x, Eigen::VectorXd& v) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  x.resize(2 * n);
  v.resize(2 * n);
  for (int k = 0; k < 2 * n; ++k) {
    x[k] = 10.0 * unit(random);
    v[k] = unit(random);
  }
}
}  // namespace

// A thread evaluates only the runs that can reach its range of particles
// (found by the runs' first particles): runs of both orientations (second end
// before or after the first) with strides from 1 to past a whole thread's
// range, cut wherever the threads' shares fall, give on 2, 3 and 5 threads
// the one-thread force bit for bit, and that force is the force objects' sum
// to rounding.
TEST(ForceBatchThreads, RunsOfEveryStrideAndOrientationReachEveryThreadsRange) {
  const int n = 6000;
  Eigen::VectorXd x, v, mass = Eigen::VectorXd::Ones(n), inverse = Eigen::VectorXd::Ones(n);
  scatter(n, 11, x, v);
  const particles::Phase phase{x, v, mass, inverse};
  particles::SpringBatch batch;
  std::vector<std::unique_ptr<particles::SpringForce>> objects;
  for (const int stride : {1, -1, 3, -40, 129, -700, 2500, -3100})
    for (int i = 0; i < n - std::abs(stride); ++i) {
      if (i % 97 == 0 || i % 31 == 7) continue;  // gaps: runs of many lengths
      const int a = stride > 0 ? i : i - stride, b = a + stride;   // b after a (stride > 0) or before it
      const double rest = 0.5 + 0.001 * (i % 7);
      batch.add(a, b, rest, 30.0, 0.2);
      objects.push_back(std::make_unique<particles::SpringForce>(a, b, rest, 30.0, 0.2));
    }
  batch.build();
  ASSERT_GE(batch.size(), particles::kParallelSprings) << "the threaded path is taken";
  ASSERT_GT(batch.runs(), 8);
  particles::setThreadCount(1);
  Eigen::VectorXd one;
  batch.apply(phase, one, true);
  Eigen::VectorXd plain = Eigen::VectorXd::Zero(2 * n), magnitude = Eigen::VectorXd::Zero(2 * n);
  for (const auto& spring : objects) {
    Eigen::VectorXd term = Eigen::VectorXd::Zero(2 * n);
    spring->apply(phase, term);
    plain += term;
    magnitude += term.cwiseAbs();
  }
  for (int k = 0; k < 2 * n; ++k)
    ASSERT_LE(std::abs(one[k] - plain[k]), 16.0 * std::numeric_limits<double>::epsilon() * magnitude[k]) << k;
  for (const int threads : {2, 3, 5}) {
    particles::setThreadCount(threads);
    for (int pass = 0; pass < 4; ++pass) {  // the shares move as the passes are measured
      Eigen::VectorXd threaded;
      batch.apply(phase, threaded, true);
      expectSameBits(threaded, one, "threads " + std::to_string(threads) + " pass " + std::to_string(pass));
    }
  }
  particles::setThreadCount(1);
}

// A sequence of evaluations whose points are written by the evaluations
// before them, as RK4's stages: with buffers that alternate (evaluation k
// writes the buffer evaluation k − 1 read), and one thread held back at a
// different place in each evaluation (its finish spins for 0.3 ms), so that
// a thread that went on without the edges it needs, or wrote over a buffer
// another thread still reads, would change the bits. Springs of strides up
// to 700 (every range of 2, 3 and 5 threads is longer: the threads wait for
// their neighbours' edges only) and up to 3100 (longer than a range: the
// evaluations are separated by barriers); both give the one-thread result.
TEST(ForceBatchThreads, ASequenceOfEvaluationsGivesTheOneThreadResultWhileAThreadLags) {
  const int n = 6000, stages = 4;
  for (const int longest : {700, 3100}) {
    SCOPED_TRACE("longest stride " + std::to_string(longest));
    Eigen::VectorXd x0, v0, mass = Eigen::VectorXd::Ones(n), inverse = Eigen::VectorXd::Ones(n);
    scatter(n, 5, x0, v0);
    particles::SpringBatch batch;
    for (const int stride : {1, -1, 3, -40, 129, -longest})
      for (int i = 0; i < n - std::abs(stride); ++i) {
        if (i % 97 == 0) continue;
        const int a = stride > 0 ? i : i - stride;
        batch.add(a, a + stride, 0.5 + 0.001 * (i % 7), 30.0, 0.2);
      }
    batch.build();
    ASSERT_GE(batch.size(), particles::kParallelSprings);
    auto run = [&](int threads) {
      particles::setThreadCount(threads);
      Eigen::VectorXd x = x0, v = v0, xs(2 * n), vs(2 * n), xt(2 * n), vt(2 * n), f, sum = Eigen::VectorXd::Zero(2 * n);
      const Eigen::VectorXd* reads[stages][2] = {{&x, &v}, {&xs, &vs}, {&xt, &vt}, {&xs, &vs}};
      Eigen::VectorXd* writes[stages][2] = {{&xs, &vs}, {&xt, &vt}, {&xs, &vs}, {&x, &v}};
      std::vector<particles::Phase> phases;
      for (int k = 0; k < stages; ++k) phases.push_back({*reads[k][0], *reads[k][1], mass, inverse});
      batch.applySequence(phases, f, [&](int k, int begin, int end) {
        const int lagging = (k * 1777 + 900) % n;  // the particle whose thread is held back
        if (begin <= lagging && lagging < end) {
          const double until = omp_get_wtime() + 3e-4;
          while (omp_get_wtime() < until) {
          }
        }
        for (int e = 2 * begin; e < 2 * end; ++e) {
          sum[e] += f[e];
          (*writes[k][0])[e] = x0[e] + 0.01 * (*reads[k][1])[e];
          (*writes[k][1])[e] = v0[e] + 0.01 * f[e];
        }
      });
      Eigen::VectorXd state(6 * n);
      state << x, v, sum;
      return state;
    };
    const Eigen::VectorXd one = run(1);
    for (const int threads : {2, 3, 5})
      for (int pass = 0; pass < 3; ++pass)
        expectSameBits(run(threads), one, "threads " + std::to_string(threads) + " pass " + std::to_string(pass));
  }
  particles::setThreadCount(1);
}

// acceleration()'s then(begin, end) sees every particle once, with its entries of a already final:
// fused into the force pass (the big cloth, with and without gathered springs; 1 and 2 threads) and
// after the constraint solve (the cloth with a rod).
TEST(ForceBatchThreads, AccelerationsThenSeesEachParticleOnceWithItsFinalAcceleration) {
  for (const int threads : {1, 2})
    for (const int variant : {0, 1, 2}) {
      SCOPED_TRACE("threads " + std::to_string(threads) + " variant " + std::to_string(variant));
      particles::setThreadCount(threads);
      auto cloth = bigCloth(false, variant == 1);
      if (variant == 2) cloth->addConstraint(std::make_unique<particles::RodConstraint>(100, 101, 0.05));
      const int n = cloth->size();
      Eigen::VectorXd a, seen = Eigen::VectorXd::Constant(2 * n, std::numeric_limits<double>::quiet_NaN());
      std::vector<int> calls(static_cast<std::size_t>(n), 0);
      particles::SystemInternals::acceleration(*cloth, cloth->positions(), cloth->velocities(), a,
                                               [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
          ++calls[static_cast<std::size_t>(i)];
          seen.segment<2>(2 * i) = a.segment<2>(2 * i);
        }
      });
      EXPECT_EQ(std::count(calls.begin(), calls.end(), 1), n);
      Eigen::VectorXd plain;
      cloth->acceleration(cloth->positions(), cloth->velocities(), plain);
      expectSameBits(seen, plain, "then's view of a");
      expectSameBits(a, plain, "a");
    }
  particles::setThreadCount(1);
}

// accelerations() over three points: then(k, begin, end) sees every particle once in each
// evaluation k, in order, with a's entries the acceleration() at point k, and the tally counts three
// force evaluations; on the big cloth (the pipelined path), with gathered springs (barriers between
// the evaluations) and with a rod (one evaluation after another), on 1 and 2 threads.
TEST(ForceBatchThreads, AccelerationsSequenceSeesEachParticleOnceAnEvaluationWithItsAcceleration) {
  for (const int threads : {1, 2})
    for (const int variant : {0, 1, 2}) {
      SCOPED_TRACE("threads " + std::to_string(threads) + " variant " + std::to_string(variant));
      particles::setThreadCount(threads);
      auto cloth = bigCloth(false, variant == 1);
      if (variant == 2) cloth->addConstraint(std::make_unique<particles::RodConstraint>(100, 101, 0.05));
      const int n = cloth->size(), stages = 3;
      std::vector<Eigen::VectorXd> xs, vs;
      for (int k = 0; k < stages; ++k) {
        xs.push_back(cloth->positions() + (0.002 * k) * cloth->velocities());
        vs.push_back(cloth->velocities() * (1.0 + 0.5 * k) + Eigen::VectorXd::Constant(2 * n, 0.01 * k));
      }
      std::vector<Eigen::VectorXd> seen(stages, Eigen::VectorXd::Constant(2 * n, std::numeric_limits<double>::quiet_NaN()));
      std::vector<std::vector<int>> calls(stages, std::vector<int>(static_cast<std::size_t>(n), 0));
      std::vector<int> stageOrder;  // then may run on several threads: appended under a lock
      Eigen::VectorXd a;
      cloth->takeEvaluationStats();
      particles::SystemInternals::accelerations(*cloth, {{xs[0], vs[0]}, {xs[1], vs[1]}, {xs[2], vs[2]}}, a,
                                                [&](int k, int begin, int end) {
#pragma omp critical
        stageOrder.push_back(k);
        for (int i = begin; i < end; ++i) {
          ++calls[k][static_cast<std::size_t>(i)];
          seen[k].segment<2>(2 * i) = a.segment<2>(2 * i);
        }
      });
      EXPECT_EQ(cloth->takeEvaluationStats().forceEvaluations, stages);
      if (threads == 1) {
        EXPECT_TRUE(std::is_sorted(stageOrder.begin(), stageOrder.end()));
      }
      for (int k = 0; k < stages; ++k) {
        EXPECT_EQ(std::count(calls[k].begin(), calls[k].end(), 1), n) << "evaluation " << k;
        Eigen::VectorXd plain;
        cloth->acceleration(xs[k], vs[k], plain);
        expectSameBits(seen[k], plain, "evaluation " + std::to_string(k));
      }
    }
  particles::setThreadCount(1);
}

// Every integrator (and xpbd with hanging lines) on the big cloth (with and without gathered springs) and every
// built-in scene (that it accepts): 2 and 3 threads give the one-thread trajectory bit for bit.
TEST(ForceBatchThreads, ThreadedTrajectoriesEqualOneThreadBitForBit) {
  std::vector<std::string> integrators;
  for (const particles::IntegratorInfo& info : particles::integratorTable()) integrators.push_back(info.name);
  integrators.push_back("xpbd-lines");  // xpbd with XpbdSettings::lines
  auto run = [&](int threads, const std::string& scene, const std::string& integratorName) {
    particles::setThreadCount(threads);
    std::unique_ptr<ParticleSystem> system;
    double dt = 0.001;
    scenes::Scene built;
    if (scene.rfind("big-cloth", 0) == 0) {
      system = bigCloth(scene == "big-cloth-on-colliders", scene == "big-cloth-with-ties");
    } else {
      built = scenes::buildScene(scene);
      system = std::move(built.system);
      dt = built.dt;
    }
    system->threadUse().adaptive = false;  // every step on `threads` threads, however fast
    particles::IntegratorSettings settings;
    settings.xpbd.lines = integratorName == "xpbd-lines";
    auto integrator = particles::makeIntegrator(settings.xpbd.lines ? "xpbd" : integratorName, settings);
    int contacts = 0;
    for (int k = 0; k < 10; ++k) {
      system->step(*integrator, dt);
      contacts += system->contactsLastStep();
    }
    // The cloth on colliders does meet them within its ten steps.
    if (scene == "big-cloth-on-colliders") {
      EXPECT_GT(contacts, 0) << integratorName;
    }
    Eigen::VectorXd state(2 * system->positions().size());
    state << system->positions(), system->velocities();
    return state;
  };
  std::vector<std::string> sceneNames = {"big-cloth", "big-cloth-with-ties", "big-cloth-on-colliders"};
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
