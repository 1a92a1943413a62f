#include "particles/threads.h"

#include <sched.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>

namespace particles {

namespace {
// Atomic: the demo's panel sets it while its advice worker thread steps a copy of the scene.
std::atomic<int> gThreads{1};
}  // namespace

void setThreadCount(int count) {
  if (count < 1) throw std::invalid_argument("thread count must be >= 1, got " + std::to_string(count));
  gThreads.store(count, std::memory_order_relaxed);
}

int threadCount() { return gThreads.load(std::memory_order_relaxed); }

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
