#include "particles/threads.h"

#ifdef _OPENMP
#include <omp.h>
#endif
#include <sched.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>

namespace particles {

namespace {
// Atomic: the demo's panel sets it while its advice worker thread steps a copy of the scene.
std::atomic<int> gThreads{1};
// The count of the innermost ThreadCountScope open on this thread, 0 for none.
thread_local int tScoped = 0;
thread_local long long tRegions = 0;
}  // namespace

void setThreadCount(int count) {
  if (count < 1) throw std::invalid_argument("thread count must be >= 1, got " + std::to_string(count));
  gThreads.store(count, std::memory_order_relaxed);
}

int threadCount() { return tScoped > 0 ? tScoped : gThreads.load(std::memory_order_relaxed); }

ThreadCountScope::ThreadCountScope(int count) : previous_(tScoped) {
  if (count < 1) throw std::invalid_argument("thread count must be >= 1, got " + std::to_string(count));
  tScoped = count;
}

ThreadCountScope::~ThreadCountScope() { tScoped = previous_; }

long long parallelRegions() { return tRegions; }
void countParallelRegion() { ++tRegions; }

void releaseIdleThreads() {
#ifdef _OPENMP  // without OpenMP there are no other threads
  if (omp_in_parallel()) return;
  omp_pause_resource_all(omp_pause_soft);
#endif
}

int affinityCpuCount() {
#ifndef __EMSCRIPTEN__  // a browser has no affinity mask
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) {
    const int n = CPU_COUNT(&set);
    if (n > 0) return n;
  }
#endif
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? static_cast<int>(hw) : 1;
}

}  // namespace particles
