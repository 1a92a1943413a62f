// What two threads can give on this machine, with the engine's own parallel
// loops (src/parallel_for.h), beside which the engine's speed-ups are read:
//   region        an empty OpenMP parallel region of N threads: the cost of
//                 entering and leaving one (a fork and a join);
//   barrier       one barrier inside a region (100 per iteration);
//   pass/<n>      one pass over four vectors of n doubles (d = a + b/2,
//                 a = c + 1e-9 d) by parallelRanges, as the integrators' vector
//                 passes are: memory-bound, 32n bytes; n = 32768 is the size of
//                 the 128² cloth's x, 131072 of the 256² cloth's;
//   compute/<n>   the same pass with a square root and a division per entry:
//                 bound by arithmetic, as the spring loops are.
// Each at 1 and 2 threads, wall time; the speed-up 1 -> 2 threads of each pass
// is printed at the end (ratio of the medians over the repetitions).
//
//   build/tests/bench_parallel_overhead --benchmark_repetitions=7
//     --benchmark_enable_random_interleaving=true (one command line)
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "parallel_for.h"
#include "repetition_reporter.h"

namespace {

void BM_Region(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  int sink = 0;
  for (auto _ : state) {
#pragma omp parallel num_threads(threads)
    {
#pragma omp atomic
      ++sink;
    }
  }
  benchmark::DoNotOptimize(sink);
}

void BM_Barrier(benchmark::State& state) {
  constexpr int kBarriers = 100;
  for (auto _ : state) {
#pragma omp parallel num_threads(2)
    for (int k = 0; k < kBarriers; ++k) {
#pragma omp barrier
    }
  }
  state.SetItemsProcessed(state.iterations() * kBarriers);  // items/s: barriers per second
}

template <bool kCompute>
void BM_Pass(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), threads = static_cast<int>(state.range(1));
  std::vector<double> a(n, 1.0), b(n, 2.0), c(n, 3.0), d(n, 0.0);
  double *pa = a.data(), *pb = b.data(), *pc = c.data(), *pd = d.data();
  for (auto _ : state)
    particles::parallelRanges(n, threads, 1, [&](int begin, int end) {
#pragma omp simd
      for (int k = begin; k < end; ++k) {
        pd[k] = kCompute ? std::sqrt(pa[k] * pa[k] + pb[k]) / (pc[k] + 0.5) : pa[k] + 0.5 * pb[k];
        pa[k] = pc[k] + 1e-9 * pd[k];
      }
    });
  benchmark::DoNotOptimize(pa);
}

}  // namespace

BENCHMARK(BM_Region)->ArgName("threads")->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Barrier)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_Pass, false)->ArgNames({"n", "threads"})->ArgsProduct({{32768, 131072}, {1, 2}})->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_Pass, true)->ArgNames({"n", "threads"})->ArgsProduct({{32768, 131072}, {1, 2}})->UseRealTime()->Unit(benchmark::kMicrosecond);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  bench::RepetitionReporter collector;
  benchmark::RunSpecifiedBenchmarks(&collector);
  for (const char* kind : {"BM_Pass<false>", "BM_Pass<true>"})
    for (const char* n : {"32768", "131072"}) {
      const auto& one = collector.wall[std::string(kind) + "/n:" + n + "/threads:1/real_time"];
      const auto& two = collector.wall[std::string(kind) + "/n:" + n + "/threads:2/real_time"];
      if (one.empty() || two.empty()) continue;
      std::printf("speed-up 1 -> 2 threads, %s pass of n = %s (wall time): %.3f, 1 thread %.2f us, 2 threads %.2f us\n",
                  std::string(kind) == "BM_Pass<true>" ? "compute" : "memory", n, bench::median(one) / bench::median(two),
                  bench::median(one), bench::median(two));
    }
  benchmark::Shutdown();
  return 0;
}
