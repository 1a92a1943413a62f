// Constraint solves compared on the test chain (cl = 80 and 500) and a cloth
// curtain: matrix-free CG (plain, cold start: the first solver;
// Jacobi + warm start), incomplete-Cholesky CG and the sparse direct LDLᵀ.
// Each benchmark times one RK4 step (four solves) at CG tolerance 1e-8 and
// reports CG iterations per solve beside the time. The implicit-Euler and
// large-cloth benchmarks are here too.
//
//   build/tests/bench_solvers --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Medians of 5 (chain, curtain) or 3 (cloth) repetitions, CPU time, on the
// shared 2-core Debian 12 machine (load average 6-9 from other builds, so wall
// time ran up to 3× CPU time), 2026-11-23:
//   RK4 step, test chain cl = 80:  plain cold CG 193 µs (79 it/solve), Jacobi warm
//     CG 212 µs (79), IC-CG 43.3 µs (1), direct LDLᵀ 15.0 µs   → direct default
//   RK4 step, test chain cl = 500: 7831 µs (499), 8586 µs (499), 262 µs (1), 95.5 µs
//   RK4 step, 32×32 curtain (top row on a line: J W Jᵀ diagonal): 111 µs for all (1 it)
//   RK4 step, 8-way cloth 32² / 64² / 128² / 256²: 0.105 / 0.451 / 1.92 / 9.13 ms
//     (log-log slope in particle count 32² → 256²: 1.07)
//   implicit Euler step at 1/60, k_s = 50:  Jacobi CG 0.67 / 3.05 / 12.6 ms (5-8 it),
//                                            direct   2.38 / 17.6 / 175 ms
//   implicit Euler step at 1/60, k_s = 4e5: Jacobi CG 3.39 / 22.7 / 122 ms (155-352 it),
//                                            direct   2.50 / 18.4 / 178 ms
//   implicit Euler step at 0.2, test chain cl = 200 (KKT direct): 47 µs
#include <benchmark/benchmark.h>

#include <memory>

#include "particles/constraints/line.h"
#include "particles/constraints/rod.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "integrators/implicit_euler.h"
#include "integrators/rk4.h"
#include "particles/particle_system.h"

using namespace particles;
using Eigen::Vector2d;

namespace {

// The report's test chain: cl particles joined by squared rods of 0.1, the
// first pinned, released horizontally under g = 0.05.
std::unique_ptr<ParticleSystem> testChain(int cl) {
  auto s = std::make_unique<ParticleSystem>();
  for (int i = 0; i < cl; ++i) s->addParticle(Vector2d(0.1 * i, 0.0), 1.0);
  s->setPinned(0, true);
  for (int i = 0; i + 1 < cl; ++i) s->addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1));
  s->addForce(std::make_unique<GravityForce>(Vector2d(0.0, -0.05)));
  return s;
}

struct ClothParams {
  int width = 32, height = 32;  // particles
  double rest = 0.05;           // spacing, world units
  double stiffness = 50.0;      // k_s of every spring, force / length
  double damping = 0.5;         // k_d, force / speed
  double mass = 0.2;            // per particle
  bool curtain = true;          // top row on a horizontal line (constraints); else corners pinned
};

// 8-way cloth: structural springs to the right and below, shear springs along
// both diagonals.
std::unique_ptr<ParticleSystem> cloth(const ClothParams& p) {
  auto s = std::make_unique<ParticleSystem>();
  std::vector<Vector2d> positions;
  for (int r = 0; r < p.height; ++r)
    for (int c = 0; c < p.width; ++c) positions.emplace_back(p.rest * c, -p.rest * r);
  s->addParticles(positions, std::vector<double>(positions.size(), p.mass));
  auto id = [&](int r, int c) { return r * p.width + c; };
  const double diagonal = p.rest * std::sqrt(2.0);
  for (int r = 0; r < p.height; ++r)
    for (int c = 0; c < p.width; ++c) {
      auto spring = [&](int i, int j, double rest) {
        s->addForce(std::make_unique<SpringForce>(i, j, rest, p.stiffness, p.damping));
      };
      if (c + 1 < p.width) spring(id(r, c), id(r, c + 1), p.rest);
      if (r + 1 < p.height) spring(id(r, c), id(r + 1, c), p.rest);
      if (c + 1 < p.width && r + 1 < p.height) spring(id(r, c), id(r + 1, c + 1), diagonal);
      if (c > 0 && r + 1 < p.height) spring(id(r, c), id(r + 1, c - 1), diagonal);
    }
  if (p.curtain) {
    for (int c = 0; c < p.width; ++c)
      s->addConstraint(std::make_unique<LineConstraint>(id(0, c), Vector2d::Zero(), 0.0));
  } else {
    s->setPinned(id(0, 0), true);
    s->setPinned(id(0, p.width - 1), true);
  }
  s->addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
  return s;
}

enum Variant { PlainCold, JacobiWarm, IncompleteCholeskyCg, Direct };

void configure(SolverSettings& settings, Variant variant) {
  settings.tolerance = 1e-8;
  settings.method = variant == Direct ? SolveMethod::Direct : SolveMethod::ConjugateGradient;
  settings.warmStart = variant != PlainCold;
  settings.preconditioner = variant == PlainCold              ? Preconditioner::None
                            : variant == IncompleteCholeskyCg ? Preconditioner::IncompleteCholesky
                                                              : Preconditioner::Jacobi;
}

void timeRk4(benchmark::State& state, ParticleSystem& system, double dt) {
  Rk4Integrator rk4;
  for (int k = 0; k < 10; ++k) system.step(rk4, dt);  // past the first, special steps
  StepStats work;
  for (auto _ : state) work += system.step(rk4, dt);
  state.counters["cg_iters_per_solve"] = work.solves ? double(work.cgIterations) / double(work.solves) : 0.0;
  state.counters["residual"] = work.maxResidual;
  if (!system.finite()) state.SkipWithError("the system blew up");
}

void BM_ChainRk4(benchmark::State& state) {
  auto system = testChain(static_cast<int>(state.range(0)));
  configure(system->solver().settings, static_cast<Variant>(state.range(1)));
  timeRk4(state, *system, 0.01);
}

void BM_CurtainRk4(benchmark::State& state) {
  ClothParams p;
  p.width = p.height = static_cast<int>(state.range(0));
  auto system = cloth(p);
  configure(system->solver().settings, static_cast<Variant>(state.range(1)));
  timeRk4(state, *system, 1e-3);
}

void solverArgs(benchmark::internal::Benchmark* b, std::initializer_list<int> sizes) {
  b->ArgNames({"n", "solver"});  // solver: 0 plain cold CG, 1 Jacobi warm CG, 2 IC-CG, 3 direct
  for (int n : sizes)
    for (int v : {PlainCold, JacobiWarm, IncompleteCholeskyCg, Direct}) b->Args({n, v});
  b->Unit(benchmark::kMicrosecond);
}

BENCHMARK(BM_ChainRk4)->Apply([](auto* b) { solverArgs(b, {80, 500}); });
BENCHMARK(BM_CurtainRk4)->Apply([](auto* b) { solverArgs(b, {32}); });

// --- large scenes -----------------------------------------------------------

void BM_ClothRk4(benchmark::State& state) {
  ClothParams p;
  p.width = p.height = static_cast<int>(state.range(0));
  p.curtain = false;
  auto system = cloth(p);
  timeRk4(state, *system, 1e-3);
}
BENCHMARK(BM_ClothRk4)->Arg(32)->Arg(64)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond);

// One implicit-Euler step at dt = 1/60 of an 8-way cloth hanging from two
// corners. stiff = 1 raises k_s to 4·10⁵ (mass 0.2): RK4 then blows up at
// dt = 1/1000 and needs 1/2000 — the stiff cloth of the small-steps experiment.
void BM_ClothImplicitEuler(benchmark::State& state) {
  ClothParams p;
  p.width = p.height = static_cast<int>(state.range(0));
  p.curtain = false;
  if (state.range(2)) p.stiffness = 4e5;
  auto system = cloth(p);
  ImplicitEulerIntegrator implicit;
  IntegratorSettings settings;
  settings.implicitEuler.solver =
      state.range(1) ? ImplicitLinearSolver::ConjugateGradient : ImplicitLinearSolver::Direct;
  implicit.configure(settings);
  for (int k = 0; k < 3; ++k) system->step(implicit, 1.0 / 60.0);
  long iterations = 0, steps = 0;
  for (auto _ : state) {
    iterations += system->step(implicit, 1.0 / 60.0).cgIterations;
    ++steps;
  }
  state.counters["cg_iters"] = double(iterations) / double(steps);
  if (!system->finite()) state.SkipWithError("the system blew up");
}
BENCHMARK(BM_ClothImplicitEuler)
    ->ArgNames({"n", "cg", "stiff"})
    ->ArgsProduct({{32, 64, 128}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

void BM_ChainImplicitEuler(benchmark::State& state) {
  auto system = testChain(static_cast<int>(state.range(0)));
  ImplicitEulerIntegrator implicit;
  for (int k = 0; k < 10; ++k) system->step(implicit, 0.2);
  for (auto _ : state) system->step(implicit, 0.2);
  state.counters["passes"] = implicit.lastPasses();
  if (!system->finite()) state.SkipWithError("the system blew up");
}
BENCHMARK(BM_ChainImplicitEuler)->Arg(200)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
