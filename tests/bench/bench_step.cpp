// Time per step of two scenes:
//   chain80/<integrator>  an 80-particle rod chain (links 0.05, masses 1), first
//                         particle pinned, released horizontally under gravity,
//                         once per entry of integratorTable();
//   cloth32x32/rk4        a 32×32 8-way spring cloth (structural and shear
//                         springs, diagonal rest √2·spacing), top row pinned.
// Both at the solver's default settings (the direct solve: SimplicialLDLT of
// J W Jᵀ, refactorised each evaluation).
//
// Each scene runs in episodes of kEpisodeSteps steps from a state warmed up by
// kWarmupSteps steps; the reset between episodes is not timed. dt is 1 ms, not
// the scenes' 10 ms: released from horizontal, the chain's free end whips
// through the bottom at about 25 units/s near t = 0.9 s, five links per 10 ms
// step, and every explicit scheme diverges there; at 1 ms and 0.3 s episodes
// all four stay on the constraint manifold (relative rod error < 1%), and the
// cost of a step does not depend on dt. An episode that ends off the manifold
// is reported as an error rather than timed.
// Counters (from the StepStats each step returns): CG iterations per constraint
// solve, solves and force evaluations per step.
//
// chain80-dt10ms/{rk4,dopri5}: the chain at dt 10 ms, 40 whole episodes of 30
// steps (see chainStepAt10ms), dopri5 at its default tolerance 2e-5.
// Measured 2026-12-02 on the 2-core AMD EPYC (shared):
// instructions per timed step by callgrind (scripts/callgrind-step.sh,
// repeatable): rk4 257,728, dopri5 397,814, ratio 1.544. dopri5 takes 29
// accepted and 1 rejected internal step per 30 outputs (6.0 evaluations per
// step against RK4's 4); its evaluations cost 1.50 RK4 steps' evaluations and
// its own stage sums, error norm and dense output ~27,000 instructions a step
// (RK4's ~10,000). CPU time, by scripts/bench-ratio.sh (runs of 9
// interleaved repetitions, the two medians of a run in the same run): at load
// 0.4, 7 runs, rk4 13.7–14.4 µs, dopri5 21.4–22.5 µs, ratio median 1.563
// (1.525–1.592); at load 0.5–1.5 the ratio spread to 1.51–1.69 over 13 runs
// (median 1.59): per step dopri5 misses the first-level cache about four times
// as often as an RK4 step (callgrind --cache-sim=yes), so its CPU ratio sits
// above the instruction ratio and is the more load-sensitive. At the earlier
// default 1e-5 dopri5 took 33 internal steps per 30
// outputs: 436,837 instructions, 1.695 RK4 steps.
//
//   ./build/tests/bench_step --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "particles/forces/drag.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/particle_system.h"
#include "cloth_grid.h"
#include "rod_chain.h"

using namespace particles;
using Eigen::Vector2d;

namespace {

constexpr double kDt = 0.001;          // s
constexpr int kWarmupSteps = 5;
constexpr int kEpisodeSteps = 300;     // 0.3 simulated seconds
constexpr double kMaxRelativeRodError = 0.01;

ParticleSystem buildCloth(int width, int height, double spacing) { return bench::clothGrid(width, height, spacing); }

// Restarts an episode: restore and kWarmupSteps untimed steps. Out of line so
// that callgrind's call graph tells these steps from the timed ones (the timed
// ones are the calls of ParticleSystem::step made from runSteps).
[[gnu::noinline]] void warmUp(ParticleSystem& system, Integrator& integrator, const Snapshot& start, double dt) {
  system.restore(start);
  for (int k = 0; k < kWarmupSteps; ++k) system.step(integrator, dt);
}

void runSteps(benchmark::State& state, ParticleSystem& system, const std::string& integratorName,
              double dt = kDt, int episodeSteps = kEpisodeSteps) {
  auto integrator = makeIntegrator(integratorName);
  const Snapshot start = system.snapshot();
  auto episodeWentWrong = [&] {
    return !system.finite() || system.maxRelativeConstraintError() > kMaxRelativeRodError;
  };
  warmUp(system, *integrator, start, dt);
  StepStats work;
  work.internalSteps = 0;
  long steps = 0;
  for (auto _ : state) {
    work += system.step(*integrator, dt);
    if (++steps % episodeSteps == 0) {
      state.PauseTiming();
      if (episodeWentWrong()) {
        state.SkipWithError("the episode left the constraint manifold");
        state.ResumeTiming();
        break;
      }
      warmUp(system, *integrator, start, dt);
      state.ResumeTiming();
    }
  }
  if (episodeWentWrong()) state.SkipWithError("the episode left the constraint manifold");
  state.counters["cg_iters_per_solve"] = work.solves ? static_cast<double>(work.cgIterations) / work.solves : 0.0;
  state.counters["solves_per_step"] = steps ? static_cast<double>(work.solves) / steps : 0.0;
  state.counters["evaluations_per_step"] = steps ? static_cast<double>(work.forceEvaluations) / steps : 0.0;
  state.counters["particles"] = system.size();
}

void chainStep(benchmark::State& state, std::string integratorName) {
  ParticleSystem system = bench::horizontalRodChain(80, 0.05);
  runSteps(state, system, integratorName);
  state.counters["cg_tolerance"] = system.solver().settings.tolerance;
}

// The same chain at the scenes' dt of 10 ms, in episodes of 0.3 s (30 steps,
// before the free end whips through the bottom): the cost of an RK4 step
// against a dopri5 call covering the same interval with its own steps.
constexpr int kEpisodeSteps10ms = 30, kEpisodes10ms = 40;
void chainStepAt10ms(benchmark::State& state, std::string integratorName) {
  ParticleSystem system = bench::horizontalRodChain(80, 0.05);
  runSteps(state, system, integratorName, 0.01, kEpisodeSteps10ms);
}

void clothStep(benchmark::State& state, std::string integratorName) {
  ParticleSystem system = buildCloth(32, 32, 0.05);
  runSteps(state, system, integratorName);
}

}  // namespace

int main(int argc, char** argv) {
  for (const IntegratorInfo& info : integratorTable())
    benchmark::RegisterBenchmark((std::string("chain80/") + info.name).c_str(), chainStep,
                                 std::string(info.name))
        ->Unit(benchmark::kMicrosecond);
  // Whole episodes, the same steps for both schemes (and a repeatable count under callgrind).
  for (const char* name : {"rk4", "dopri5"})
    benchmark::RegisterBenchmark((std::string("chain80-dt10ms/") + name).c_str(), chainStepAt10ms, std::string(name))
        ->Unit(benchmark::kMicrosecond)
        ->Iterations(kEpisodeSteps10ms * kEpisodes10ms);
  benchmark::RegisterBenchmark("cloth32x32/rk4", clothStep, std::string("rk4"))
      ->Unit(benchmark::kMicrosecond);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
