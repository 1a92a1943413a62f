// The engine's RK4 step of the 80-particle rod chain (rod_chain.h: squared
// rods, the first particle pinned, released horizontally under gravity) at
// the solver's defaults (the direct solve) against a plain O(m) RK4 step of
// the same physics, dt 1 ms:
//   engine/<n>     ParticleSystem::step with Rk4Integrator;
//   reference/<n>  PlainChain::step below: flat arrays, plain loops, each
//                  evaluation one pass over the rods for C, Ċ, J, J̇ and b,
//                  the tridiagonal J W Jᵀ solved by the Thomas algorithm,
//                  compiled at -O2 (this file's own flags).
// Both run episodes of kEpisodeSteps steps from the same state, restored
// untimed between episodes (the chain's free end whips through the bottom
// later). Before timing, one episode of each from the same start is compared
// and the largest difference of any coordinate is printed. Repetitions are
// interleaved; the ratio engine / reference of the medians of the CPU time
// per step is printed at the end, with its range over the repetitions.
//
//   ./build/tests/bench_chain_reference --benchmark_repetitions=9
//     --benchmark_enable_random_interleaving=true (one command line)
// (scripts/callgrind-chain.sh counts the two steps' instructions instead.)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "particles/constraints/rod.h"
#include "integrators/rk4.h"
#include "plain_rk4.h"
#include "repetition_reporter.h"
#include "rod_chain.h"

namespace {

constexpr double kDt = 0.001;      // s
constexpr double kLink = 0.05;     // m
constexpr double kGravity = -9.81;  // m/s², as rod_chain.h
constexpr int kEpisodeSteps = 300;  // 0.3 s, before the free end whips through the bottom
constexpr int kSizes[] = {80};

// The reference: the chain's physics written as simply as possible. Rod k
// joins particles k and k + 1 (d = x_k − x_{k+1}): C = d·d − L², Ċ = 2 d·ḋ,
// J = (2d, −2d), J̇ = (2ḋ, −2ḋ); (J W Jᵀ)_kk = 4|d_k|² (w_k + w_{k+1}),
// (J W Jᵀ)_{k,k+1} = −4 w_{k+1} d_k·d_{k+1}; b = −J̇ q̇ − J W Q − k_s C − k_d Ċ.
struct PlainChain {
  int n = 0, m = 0;
  double length = 0.0, ks = 0.0, kd = 0.0;
  std::vector<double> mass, w;
  std::vector<double> acc, f;
  bench::PlainRk4 state;  // x, v and the RK4 stages
  std::vector<double> dX, dY, diagonal, upper, rhs, lambda;  // per rod

  PlainChain(const particles::ParticleSystem& s, double link) {
    n = s.size();
    m = n - 1;
    length = link;
    ks = s.solver().settings.stiffness;
    kd = s.solver().settings.damping;
    mass.assign(s.masses().data(), s.masses().data() + n);
    w.assign(s.inverseMasses().data(), s.inverseMasses().data() + n);
    restart(s);
    state.resize(n);
    for (auto* vec : {&acc, &f}) vec->assign(2 * n, 0.0);
    for (auto* vec : {&dX, &dY, &diagonal, &upper, &rhs, &lambda}) vec->assign(m, 0.0);
  }

  void restart(const particles::ParticleSystem& s) {
    state.x.assign(s.positions().data(), s.positions().data() + 2 * n);
    state.v.assign(s.velocities().data(), s.velocities().data() + 2 * n);
  }

  void accel(const std::vector<double>& px, const std::vector<double>& pv) {
    for (int p = 0; p < n; ++p) {
      f[2 * p] = 0.0;
      f[2 * p + 1] = w[p] > 0.0 ? mass[p] * kGravity : 0.0;
    }
    for (int k = 0; k < m; ++k) {
      const int i = 2 * k, j = 2 * k + 2;
      const double ddx = px[i] - px[j], ddy = px[i + 1] - px[j + 1];
      const double vx = pv[i] - pv[j], vy = pv[i + 1] - pv[j + 1];
      const double c = ddx * ddx + ddy * ddy - length * length, cdot = 2.0 * (ddx * vx + ddy * vy);
      const double jdotqdot = 2.0 * (vx * vx + vy * vy);
      const double jwq = 2.0 * (ddx * (w[k] * f[i] - w[k + 1] * f[j]) + ddy * (w[k] * f[i + 1] - w[k + 1] * f[j + 1]));
      rhs[k] = -jdotqdot - jwq - ks * c - kd * cdot;
      diagonal[k] = 4.0 * (ddx * ddx + ddy * ddy) * (w[k] + w[k + 1]);
      dX[k] = ddx;
      dY[k] = ddy;
    }
    for (int k = 0; k + 1 < m; ++k) upper[k] = -4.0 * w[k + 1] * (dX[k] * dX[k + 1] + dY[k] * dY[k + 1]);
    // Thomas: forward elimination, then back substitution.
    for (int k = 1; k < m; ++k) {
      const double factor = upper[k - 1] / diagonal[k - 1];
      diagonal[k] -= factor * upper[k - 1];
      rhs[k] -= factor * rhs[k - 1];
    }
    lambda[m - 1] = rhs[m - 1] / diagonal[m - 1];
    for (int k = m - 2; k >= 0; --k) lambda[k] = (rhs[k] - upper[k] * lambda[k + 1]) / diagonal[k];
    for (int k = 0; k < m; ++k) {
      const double fx = 2.0 * dX[k] * lambda[k], fy = 2.0 * dY[k] * lambda[k];
      f[2 * k] += fx;
      f[2 * k + 1] += fy;
      f[2 * k + 2] -= fx;
      f[2 * k + 3] -= fy;
    }
    for (int p = 0; p < n; ++p) {
      acc[2 * p] = w[p] * f[2 * p];
      acc[2 * p + 1] = w[p] * f[2 * p + 1];
    }
  }

  void step(double h) {
    state.step(h, [&](const std::vector<double>& px, const std::vector<double>& pv) { accel(px, pv); }, acc);
  }
};

// Largest |engine − reference| over every coordinate after one episode from the same start.
double checkDifference(int size) {
  particles::ParticleSystem s = bench::horizontalRodChain(size, kLink);
  PlainChain plain(s, kLink);
  return bench::largestDifferenceAfter(kEpisodeSteps, kDt, s, plain);
}

void engineStep(benchmark::State& state, int size) {
  particles::ParticleSystem s = bench::horizontalRodChain(size, kLink);
  const particles::Snapshot start = s.snapshot();
  particles::Rk4Integrator rk4;
  long steps = 0;
  for (auto _ : state) {
    s.step(rk4, kDt);
    if (++steps % kEpisodeSteps == 0) {
      state.PauseTiming();
      s.restore(start);
      state.ResumeTiming();
    }
  }
  benchmark::DoNotOptimize(s.positions().data());
  state.counters["rods"] = size - 1;
}

void referenceStep(benchmark::State& state, int size) {
  const particles::ParticleSystem s = bench::horizontalRodChain(size, kLink);
  PlainChain plain(s, kLink);
  long steps = 0;
  for (auto _ : state) {
    plain.step(kDt);
    if (++steps % kEpisodeSteps == 0) {
      state.PauseTiming();
      plain.restart(s);
      state.ResumeTiming();
    }
  }
  benchmark::DoNotOptimize(plain.state.x.data());
  state.counters["rods"] = size - 1;
}

}  // namespace

int main(int argc, char** argv) {
  for (int size : kSizes) {
    const std::string n = std::to_string(size);
    benchmark::RegisterBenchmark(("engine/" + n).c_str(), engineStep, size)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("reference/" + n).c_str(), referenceStep, size)->Unit(benchmark::kMicrosecond);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  for (int size : kSizes)
    std::printf("check %d particles: largest |engine - reference| after %d steps = %.3g\n", size, kEpisodeSteps,
                checkDifference(size));
  bench::RepetitionReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  for (int size : kSizes) {
    const std::string n = std::to_string(size);
    bench::printRatio(reporter, "engine/" + n, "reference/" + n, n + " particles");
  }
  benchmark::Shutdown();
  return 0;
}
