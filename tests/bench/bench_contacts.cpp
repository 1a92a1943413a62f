// The collision pass beside an RK4 step: a 64×64 4-way spring cloth (spacing
// 0.05, k_s 500, k_d 1, masses 0.01, top row free, dt 0.002) falling under
// gravity between two wall boxes onto a floor box, with every structural
// spring a collision edge. Its hem row starts 0.05 inside the floor box
// (y −2.15, the floor's top at −2.1) and is put out by the first steps; from
// step 50 on there are 64 contacts every step. 50 steps are taken
// before timing; every 200 timed steps the state is put back to step 50.
//   contacts64x64/rk4/with      the whole step: RK4 + the collision pass
//   contacts64x64/rk4/without   the same cloth and step with no colliders
//   .../cycle                   the same, exactly one 200-step cycle (for callgrind)
// The pass's share of a step is (with − without) / without, from medians:
//   ./build/tests/bench_contacts --benchmark_filter='rk4/with(out)?$' --benchmark_repetitions=9 \
//       --benchmark_report_aggregates_only=true --benchmark_enable_random_interleaving=true
// and as instructions, the collision pass (ContactPass::collideStep,
// inclusive) against the RK4 integration (Rk4Integrator::step, inclusive)
// over the 200 timed steps of one cycle:
//   valgrind --tool=callgrind --toggle-collect='particles::ParticleSystem::step(*' \
//       --dump-after='benchmark::State::StartKeepRunning*' --dump-before='benchmark::State::FinishKeepRunning*' \
//       ./build/tests/bench_contacts --benchmark_filter='rk4/with/cycle'
//   callgrind_annotate --inclusive=yes callgrind.out.<pid>.2
// Instructions per timed step (Release, g++ 12, the cycle above, 64 contacts
// a step): RK4 integration 3.572 M, the collision pass 0.702 M = 19.6 % of
// it; of the pass, edgeReach (the largest edge extent, over all 8064 edges)
// is 0.148 M and markNearColliders 0.118 M.
// Wall clock on a shared 2-core AMD EPYC (load 0.7–1.1; medians of 9 with
// --benchmark_enable_random_interleaving=true, with/without in the same run,
// ± the s.d.): with/without 0.392 ± 0.011 / 0.317 ± 0.006 ms (+24 %): the
// pass reads every position and edge once more, which the instruction count
// does not weigh.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/particle_system.h"

using namespace particles;
using Eigen::Vector2d;

namespace {

constexpr int kSide = 64;
constexpr double kSpacing = 0.05, kDt = 0.002;

std::unique_ptr<ParticleSystem> buildCloth(bool colliders) {
  auto s = std::make_unique<ParticleSystem>();
  std::vector<Vector2d> positions;
  for (int row = 0; row < kSide; ++row)
    for (int col = 0; col < kSide; ++col) positions.emplace_back(-1.6 + kSpacing * col, 1.0 - kSpacing * row);
  s->addParticles(positions, std::vector<double>(positions.size(), 0.01));
  auto id = [](int row, int col) { return row * kSide + col; };
  for (int row = 0; row < kSide; ++row)
    for (int col = 0; col < kSide; ++col) {
      for (const auto& [r, c] : {std::pair{row, col + 1}, std::pair{row + 1, col}}) {
        if (r >= kSide || c >= kSide) continue;
        s->addForce(std::make_unique<SpringForce>(id(row, col), id(r, c), kSpacing, 500.0, 1.0));
        if (colliders) s->addCollisionEdge(id(row, col), id(r, c));
      }
    }
  s->addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  if (colliders) {
    s->addCollider(Collider::box(Vector2d(-3, -2.5), Vector2d(3, -2.1)));   // floor, 0.1 below the hem
    s->addCollider(Collider::box(Vector2d(-3, -2.1), Vector2d(-1.7, 2)));   // left wall
    s->addCollider(Collider::box(Vector2d(1.7, -2.1), Vector2d(3, 2)));     // right wall
  }
  return s;
}

void clothStep(benchmark::State& state, bool colliders) {
  auto system = buildCloth(colliders);
  auto integrator = makeIntegrator("rk4");
  for (int k = 0; k < 50; ++k) system->step(*integrator, kDt);  // onto the floor
  const Snapshot warm = system->snapshot();
  int steps = 0;
  for (auto _ : state) {
    system->step(*integrator, kDt);
    if (++steps % 200 == 0) {
      state.PauseTiming();
      system->restore(warm);
      state.ResumeTiming();
    }
  }
  state.counters["contacts"] = system->contactsLastStep();
}

}  // namespace

BENCHMARK_CAPTURE(clothStep, contacts64x64/rk4/with, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(clothStep, contacts64x64/rk4/without, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(clothStep, contacts64x64/rk4/with/cycle, true)->Iterations(200)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(clothStep, contacts64x64/rk4/without/cycle, false)->Iterations(200)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
