#pragma once
#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <limits>
#include <vector>

#include "particles/threads.h"
#include "team_barrier.h"

// The engine's parallel loops: body(i) for every i in [0, n), or
// body(begin, end) over contiguous ranges covering [0, n), on `threads`
// OpenMP threads when threads > 1 and n >= grain, else as a plain loop on the
// calling thread. The plain loop enters no parallel region at all: an OpenMP
// region switched off by an if clause still builds a team and makes a futex
// call each time, which cost a 12-rod chain's step a third of its time.
//
// Every region is a parallelTeam: its threads wait for each other only in
// the engine's own barrier (team_barrier.h: a short spin, then a sleep in
// the kernel), never in one of libgomp's, whose waiting threads spin.
namespace particles {

// Below kParallelEntries entries a pass over a vector runs serially.
constexpr int kParallelEntries = 8192;

// One thread of a parallelTeam: member in [0, size); wait() is a barrier of the team.
struct Team {
  int member, size;
  TeamBarrier& barrier;
  void wait() const { barrier.arriveAndWait(size); }
  // The member's range of [0, n) when n is split into size equal ranges in order.
  int rangeBegin(int n) const { return static_cast<int>(static_cast<long long>(n) * member / size); }
  int rangeEnd(int n) const { return static_cast<int>(static_cast<long long>(n) * (member + 1) / size); }
};

// body(team) once on each thread of an OpenMP team of `threads` (fewer if
// the runtime gives fewer, e.g. inside another region: team.size says how
// many). The region ends with the team's barrier, so that the threads meet
// there and not in libgomp's join, which spins.
template <class Body>
void parallelTeam(int threads, const Body& body) {
  countParallelRegion();
  TeamBarrier barrier;
#ifdef _OPENMP
#pragma omp parallel num_threads(threads)
  {
    const Team team{omp_get_thread_num(), omp_get_num_threads(), barrier};
    body(team);
    team.wait();
  }
#else
  // A build without OpenMP (the WebAssembly page): a team of one.
  (void)threads;
  body(Team{0, 1, barrier});
#endif
}

template <class Body>
void parallelFor(int n, int threads, int grain, const Body& body) {
  if (threads > 1 && n >= grain) {
    parallelTeam(threads, [&](const Team& team) {
      for (int i = team.rangeBegin(n), end = team.rangeEnd(n); i < end; ++i) body(i);
    });
    return;
  }
  for (int i = 0; i < n; ++i) body(i);
}

// Thread id of team gets [n·id/team, n·(id + 1)/team): one range each, so
// the body's inner loop over its range can be vectorised.
template <class Body>
void parallelRanges(int n, int threads, int grain, const Body& body) {
  if (threads > 1 && n >= grain) {
    parallelTeam(threads, [&](const Team& team) { body(team.rangeBegin(n), team.rangeEnd(n)); });
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
    int size = threads;
    parallelTeam(threads, [&](const Team& team) {
      results[static_cast<std::size_t>(team.member)] = value(team.rangeBegin(n), team.rangeEnd(n));
      if (team.member == 0) size = team.size;
    });
    results.resize(static_cast<std::size_t>(size));
    return results;
  }
  return {value(0, n)};
}

// The largest value(i) over [0, n) (−∞ for n = 0), as parallelFor splits
// it. A maximum is exact whatever the order, so the result is the same bits
// on any thread count (a NaN value is passed over).
template <class Value>
double parallelMax(int n, int threads, int grain, const Value& value) {
  auto largestOf = [&](int begin, int end) {
    double largest = -std::numeric_limits<double>::infinity();
    for (int i = begin; i < end; ++i) largest = std::max(largest, value(i));
    return largest;
  };
  double largest = -std::numeric_limits<double>::infinity();
  for (const double part : parallelRangeResults<double>(n, threads, grain, largestOf)) largest = std::max(largest, part);
  return largest;
}

}  // namespace particles
