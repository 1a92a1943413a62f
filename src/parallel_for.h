#pragma once
#include <algorithm>
#include <limits>
#include <vector>

// The engine's parallel loops: body(i) for every i in [0, n), or
// body(begin, end) over contiguous ranges covering [0, n), on `threads`
// OpenMP threads when threads > 1 and n >= grain, else as a plain loop on the
// calling thread. The plain loop enters no parallel region at all: an OpenMP
// region switched off by an if clause still builds a team and makes a futex
// call each time, which cost a 12-rod chain's step a third of its time.
namespace particles {

// Below kParallelEntries entries a pass over a vector runs serially.
constexpr int kParallelEntries = 8192;

template <class Body>
void parallelFor(int n, int threads, int grain, const Body& body) {
  if (threads > 1 && n >= grain) {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = 0; i < n; ++i) body(i);
    return;
  }
  for (int i = 0; i < n; ++i) body(i);
}

// Thread id of team gets [n·id/team, n·(id + 1)/team): one range each, so
// the body's inner loop over its range can be vectorised.
template <class Body>
void parallelRanges(int n, int threads, int grain, const Body& body) {
  if (threads > 1 && n >= grain) {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int id = 0; id < threads; ++id)
      body(static_cast<int>(static_cast<long long>(n) * id / threads),
           static_cast<int>(static_cast<long long>(n) * (id + 1) / threads));
    return;
  }
  body(0, n);
}

// value(begin, end) over the ranges parallelRanges gives, the results in
// range order: one per thread, or a single one for [0, n) when the loop runs
// serially. Combined by an exact operation (a minimum, a maximum) they give
// the same bits on any thread count.
template <class Result, class Value>
std::vector<Result> parallelRangeResults(int n, int threads, int grain, const Value& value) {
  if (threads > 1 && n >= grain) {
    std::vector<Result> results(static_cast<std::size_t>(threads));
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int id = 0; id < threads; ++id)
      results[static_cast<std::size_t>(id)] = value(static_cast<int>(static_cast<long long>(n) * id / threads),
                                                    static_cast<int>(static_cast<long long>(n) * (id + 1) / threads));
    return results;
  }
  return {value(0, n)};
}

// The largest value(i) over [0, n) (−∞ for n = 0), as parallelFor splits
// it. A maximum is exact whatever the order, so the result is the same bits
// on any thread count (a NaN value is passed over).
template <class Value>
double parallelMax(int n, int threads, int grain, const Value& value) {
  double largest = -std::numeric_limits<double>::infinity();
  if (threads > 1 && n >= grain) {
#pragma omp parallel for schedule(static) num_threads(threads) reduction(max : largest)
    for (int i = 0; i < n; ++i) largest = std::max(largest, value(i));
    return largest;
  }
  for (int i = 0; i < n; ++i) largest = std::max(largest, value(i));
  return largest;
}

}  // namespace particles
