// The engine's RK4 step of the 8-way spring cloth (cloth_grid.h) against a
// plain single-core structure-of-arrays RK4 step of the same springs, at 64²,
// 128² and 256² particles, dt 1 ms:
//   engine/<n>     ParticleSystem::step with Rk4Integrator;
//   reference/<n>  PlainCloth::step below: flat arrays, plain loops, no
//                  intrinsics, compiled at -O2 (this file's own flags).
// Both start from the same state warmed up by a few steps; before timing, one
// run of kCheckSteps steps of each from the same start is compared and the
// largest difference of any coordinate is printed (0: the same bits).
// Repetitions are interleaved (--benchmark_enable_random_interleaving) and
// at the end the ratio engine / reference of the medians of the CPU time per
// step is printed for each size, with the ratio's range over the repetitions.
// engine-2threads/<n>: the engine on at most 2 threads (wall time; it runs a
// step on one while two are not faster, and its `threads` counter gives the
// mean count its steps ran on); the speed-up 1 -> 2 threads printed is the
// ratio of the wall-time medians.
//
//   ./build/tests/bench_cloth_reference --benchmark_repetitions=7
//     --benchmark_enable_random_interleaving=true (one command line)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "cloth_grid.h"
#include "plain_rk4.h"
#include "repetition_reporter.h"
#include "integrators/rk4.h"
#include "particles/threads.h"

namespace {

constexpr double kDt = 0.001;  // s
constexpr int kWarmupSteps = 5, kCheckSteps = 20;
constexpr int kSizes[] = {64, 128, 256};
constexpr double kSpacing = 0.05;  // m

// The reference: the same physics written as simply as possible.
using bench::PlainRk4;
struct PlainCloth {
  int n = 0;
  std::vector<int> a, b;
  std::vector<double> rest, ks, kd;
  std::vector<double> mass, w;
  double gravity = 0.0, drag = 0.0;
  std::vector<double> acc, f;
  PlainRk4 state;  // x, v and the RK4 stages

  explicit PlainCloth(const particles::ParticleSystem& s) {
    n = s.size();
    for (const auto& force : s.forceObjects())
      if (const auto* sp = dynamic_cast<const particles::SpringForce*>(force.get())) {
        a.push_back(sp->first());
        b.push_back(sp->second());
        rest.push_back(sp->restLength());
        ks.push_back(sp->stiffness());
        kd.push_back(sp->damping());
      }
    gravity = bench::kClothGravity;
    drag = bench::kClothDrag;
    mass.assign(s.masses().data(), s.masses().data() + n);
    w.assign(s.inverseMasses().data(), s.inverseMasses().data() + n);
    state.x.assign(s.positions().data(), s.positions().data() + 2 * n);
    state.v.assign(s.velocities().data(), s.velocities().data() + 2 * n);
    state.resize(n);
    for (auto* vec : {&acc, &f}) vec->assign(2 * n, 0.0);
  }

  void accel(const std::vector<double>& px, const std::vector<double>& pv) {
    std::fill(f.begin(), f.end(), 0.0);
    const int m = static_cast<int>(a.size());
    for (int k = 0; k < m; ++k) {
      const int i = 2 * a[k], j = 2 * b[k];
      const double lx = px[i] - px[j], ly = px[i + 1] - px[j + 1];
      const double len = std::sqrt(lx * lx + ly * ly);
      if (len == 0.0) continue;
      const double ux = lx / len, uy = ly / len;
      const double s = -(ks[k] * (len - rest[k]) + kd[k] * ((pv[i] - pv[j]) * ux + (pv[i + 1] - pv[j + 1]) * uy));
      f[i] += s * ux;
      f[i + 1] += s * uy;
      f[j] -= s * ux;
      f[j + 1] -= s * uy;
    }
    for (int p = 0; p < n; ++p) {
      if (w[p] > 0.0) {
        f[2 * p + 1] += mass[p] * gravity;
        f[2 * p] += mass[p] * 0.0;
        f[2 * p] -= drag * pv[2 * p];
        f[2 * p + 1] -= drag * pv[2 * p + 1];
      }
      acc[2 * p] = w[p] * f[2 * p];
      acc[2 * p + 1] = w[p] * f[2 * p + 1];
    }
  }

  void step(double h) {
    state.step(h, [&](const std::vector<double>& px, const std::vector<double>& pv) { accel(px, pv); }, acc);
  }
};

particles::ParticleSystem warmCloth(int size) {
  particles::ParticleSystem s = bench::clothGrid(size, size, kSpacing);
  particles::Rk4Integrator rk4;
  for (int k = 0; k < kWarmupSteps; ++k) s.step(rk4, kDt);
  return s;
}

// Largest |engine − reference| over every coordinate after kCheckSteps steps.
double checkDifference(int size) {
  particles::ParticleSystem s = warmCloth(size);
  PlainCloth plain(s);
  return bench::largestDifferenceAfter(kCheckSteps, kDt, s, plain);
}

void engineStep(benchmark::State& state, int size, int threads) {
  particles::setThreadCount(1);
  particles::ParticleSystem s = warmCloth(size);
  particles::setThreadCount(threads);
  particles::Rk4Integrator rk4;
  long steps = 0, threadSteps = 0;
  for (auto _ : state) {
    threadSteps += s.step(rk4, kDt).threads;
    ++steps;
  }
  particles::setThreadCount(1);
  benchmark::DoNotOptimize(s.positions().data());
  state.counters["particles"] = s.size();
  // The threads the steps ran on, on average (ParticleSystem::step chooses: src/thread_use.h).
  state.counters["threads"] = steps ? static_cast<double>(threadSteps) / steps : 0.0;
}

void referenceStep(benchmark::State& state, int size) {
  PlainCloth plain(warmCloth(size));
  for (auto _ : state) plain.step(kDt);
  benchmark::DoNotOptimize(plain.state.x.data());
  state.counters["particles"] = plain.n;
}

}  // namespace

int main(int argc, char** argv) {
  for (int size : kSizes) {
    const std::string n = std::to_string(size);
    benchmark::RegisterBenchmark(("engine/" + n).c_str(), engineStep, size, 1)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("engine-2threads/" + n).c_str(), engineStep, size, 2)
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("reference/" + n).c_str(), referenceStep, size)->Unit(benchmark::kMicrosecond);
  }
  // --skip_check leaves out the comparison run (scripts/callgrind-cloth.sh).
  bool check = true;
  for (int k = 1; k < argc; ++k)
    if (std::string(argv[k]) == "--skip_check") {
      check = false;
      std::copy(argv + k + 1, argv + argc, argv + k);
      --argc;
      break;
    }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  for (int size : kSizes)
    if (check)
      std::printf("check %d^2: largest |engine - reference| after %d steps = %.3g\n", size, kCheckSteps,
                checkDifference(size));
  bench::RepetitionReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  for (int size : kSizes) {
    const std::string n = std::to_string(size);
    bench::printRatio(reporter, "engine/" + n, "reference/" + n, n + "^2");
    const auto& e1 = reporter.wall["engine/" + n];
    const auto& e2 = reporter.wall["engine-2threads/" + n + "/real_time"];
    if (!e1.empty() && !e2.empty())
      std::printf("speed-up 1 -> 2 threads %d^2 (wall time): %.3f, 1 thread %.1f us, 2 threads %.1f us\n", size,
                  bench::median(e1) / bench::median(e2), bench::median(e1), bench::median(e2));
  }
  benchmark::Shutdown();
  return 0;
}
