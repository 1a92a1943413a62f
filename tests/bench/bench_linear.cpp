// The LDLᵀ of src/linear (Eigen's public SimplicialLDLT::factorize on the
// stored, already permuted upper triangle) against the in-place variant that
// calls Eigen's protected factorize_preordered() directly, on the matrices
// the engine factorises each step:
//   jwjt/<m>   J W Jᵀ of a rod chain with m rods (tridiagonal), as the
//              constraint solve assembles it;
//   cloth/<n>  A = M − h² K of an n × n 8-way spring cloth (9-point stencil
//              per coordinate pair), as implicit Euler's direct solve does.
// Only the numeric factorisation is timed; the analysis is done once.
//
//   build/tests/bench_linear --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Medians of 5 repetitions, CPU time (standard deviation), shared 2-core AMD
// EPYC with wall time ~3× CPU time from other builds, 2026-12-01:
//                    public factorize()     in place
//   jwjt/79           0.886 µs (0.049)      0.767 µs (0.027)
//   jwjt/499          5.05 µs (0.16)        4.96 µs (0.16)
//   cloth/16 (512)    214 µs (7)            207 µs (10)
//   cloth/32 (2048)   2159 µs (148)         2214 µs (142)
// The in-place call saves ~0.1 µs per factorisation (one empty temporary
// matrix): about 3% of an RK4 step of the 80-rod chain, which makes four of
// them in ~15 µs (bench_solvers), within this machine's noise, and nothing on
// a cloth. Not worth depending on Eigen's protected members: the engine uses
// the public API.
#include <benchmark/benchmark.h>

#include "linear/ldlt.h"
#include "linear/symmetric_pattern.h"

using particles::linear::SymmetricPattern;

namespace {

// The in-place variant: the one call the public factorize() adds around it
// is the construction of an empty temporary matrix.
struct InPlaceLdlt : Eigen::SimplicialLDLT<particles::linear::SparseMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>> {
  void factorizeInPlace(const particles::linear::SparseMatrix& upper) { this->template factorize_preordered<true>(upper); }
};

// Tridiagonal J W Jᵀ of m rods: diagonal 2, neighbours −cos θ ≈ −0.9.
void chainMatrix(int m, SymmetricPattern& pattern) {
  pattern.reset(m);
  for (int k = 0; k + 1 < m; ++k) pattern.add(k, k + 1);
  pattern.finish(SymmetricPattern::Ordering::Amd);
  double* value = pattern.values();
  for (int k = 0; k < m; ++k) value[pattern.slot(k, k)] = 2.0;
  for (int k = 0; k + 1 < m; ++k) value[pattern.slot(k, k + 1)] = -0.9;
}

// 2n² unknowns, each particle coupled to its 8 neighbours in both coordinates.
void clothMatrix(int n, SymmetricPattern& pattern) {
  const int dofs = 2 * n * n;
  auto id = [&](int r, int c) { return r * n + c; };
  pattern.reset(dofs);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      for (int dr = 0; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) {
          if ((dr == 0 && dc <= 0) || r + dr >= n || c + dc < 0 || c + dc >= n) continue;
          for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b) pattern.add(2 * id(r, c) + a, 2 * id(r + dr, c + dc) + b);
        }
  for (int p = 0; p < n * n; ++p) pattern.add(2 * p, 2 * p + 1);
  pattern.finish(SymmetricPattern::Ordering::Amd);
  double* value = pattern.values();
  for (int s = 0; s < pattern.nonZeros(); ++s) value[s] = -0.01;
  for (int d = 0; d < dofs; ++d) value[pattern.slot(d, d)] = 1.0;
}

void build(benchmark::State& state, SymmetricPattern& pattern) {
  const int size = static_cast<int>(state.range(0));
  if (state.range(1) == 0) chainMatrix(size, pattern);
  else clothMatrix(size, pattern);
  state.counters["unknowns"] = pattern.size();
}

void BM_PublicFactorize(benchmark::State& state) {
  SymmetricPattern pattern;
  build(state, pattern);
  particles::linear::Ldlt ldlt;
  ldlt.analyze(pattern.matrix());
  for (auto _ : state) benchmark::DoNotOptimize(ldlt.factorize(pattern.matrix()));
}

void BM_InPlaceFactorize(benchmark::State& state) {
  SymmetricPattern pattern;
  build(state, pattern);
  InPlaceLdlt ldlt;
  ldlt.analyzePattern(pattern.matrix());
  for (auto _ : state) {
    ldlt.factorizeInPlace(pattern.matrix());
    benchmark::DoNotOptimize(ldlt.info());
  }
}

void sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"size", "cloth"});  // cloth 0: chain J W Jᵀ with `size` rods; 1: size × size cloth
  for (int m : {79, 499}) b->Args({m, 0});
  for (int n : {16, 32}) b->Args({n, 1});
  b->Unit(benchmark::kMicrosecond);
}

BENCHMARK(BM_PublicFactorize)->Apply(sizes);
BENCHMARK(BM_InPlaceFactorize)->Apply(sizes);

}  // namespace

BENCHMARK_MAIN();
