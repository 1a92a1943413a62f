#include "thread_balance.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace particles {

namespace {
// How far one pass's measurement moves the shares: a few passes follow a
// core that slowed down; one noisy pass moves them little.
constexpr double kFollow = 0.2;
// No thread's share falls below this fraction of an equal one.
constexpr double kLeastShare = 0.25;
}  // namespace

#ifdef _OPENMP
int ThreadBalance::Pass::teamMember() { return omp_get_thread_num(); }
int ThreadBalance::Pass::teamSize() { return omp_get_num_threads(); }
double ThreadBalance::Pass::wallClock() { return omp_get_wtime(); }
#else
// A build without OpenMP (the WebAssembly page) runs every pass on one thread.
int ThreadBalance::Pass::teamMember() { return 0; }
int ThreadBalance::Pass::teamSize() { return 1; }
double ThreadBalance::Pass::wallClock() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
#endif

std::vector<double> ThreadBalance::cuts(int threads) {
  if (static_cast<int>(share_.size()) != threads) share_.assign(threads, 1.0 / threads);
  std::vector<double> c(threads + 1, 0.0);
  for (int t = 0; t < threads; ++t) c[t + 1] = std::min(1.0, c[t] + share_[t]);
  c[threads] = 1.0;
  return c;
}

std::vector<int> ThreadBalance::bounds(int n, int threads) {
  const std::vector<double> c = cuts(threads);
  std::vector<int> b(threads + 1, 0);
  for (int t = 1; t < threads; ++t) b[t] = std::clamp(static_cast<int>(std::lround(c[t] * n)), b[t - 1], n);
  b[threads] = n;
  return b;
}

void ThreadBalance::update(const std::vector<double>& items, const std::vector<double>& busy) {
  const int threads = static_cast<int>(busy.size());
  if (static_cast<int>(share_.size()) != threads || static_cast<int>(items.size()) != threads) return;
  std::vector<double> speed(threads, 0.0);
  double total = 0.0;
  for (int t = 0; t < threads; ++t) {
    if (!(items[t] > 0.0) || !(busy[t] > 0.0)) return;  // nothing measured: keep the shares
    speed[t] = items[t] / busy[t];
    total += speed[t];
  }
  double sum = 0.0;
  for (int t = 0; t < threads; ++t) {
    share_[t] = std::max((1.0 - kFollow) * share_[t] + kFollow * speed[t] / total, kLeastShare / threads);
    sum += share_[t];
  }
  for (double& s : share_) s /= sum;
}

}  // namespace particles
