#pragma once
// Independent sweep cells on several threads. Every cell builds its own scene
// and shares nothing mutable, and results are delivered in cell order, so the
// rows an experiment writes are identical for any number of jobs.
#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "lab/lab.h"

namespace lab {

// Threads used when --jobs is not given: every core (at least one).
int defaultJobs();

// Runs compute(k) for every k in [0, count) on `jobs` threads and calls
// deliver(k, result) on the calling thread in increasing k, each as soon as
// cells 0..k are finished (so rows stream to disk in order). A cell that an
// interrupt cut short returns std::nullopt and is not delivered; after an
// interrupt no new cell starts. An exception thrown by a cell stops the
// others from starting and is rethrown here.
//
// With `cost` (an estimate of each cell's run time, in any unit) the cells
// start in decreasing cost, so the longest ones do not run alone at the end
// while the other threads idle (longest processing time first); the results,
// and the order they are delivered in, are the same.
template <class Result>
void parallelMap(int jobs, std::size_t count, const std::function<std::optional<Result>(std::size_t)>& compute,
                 const std::function<void(std::size_t, Result&)>& deliver,
                 const std::function<double(std::size_t)>& cost = {}) {
  std::vector<std::size_t> order(count);
  for (std::size_t k = 0; k < count; ++k) order[k] = k;
  if (cost) {
    std::vector<double> estimate(count);
    for (std::size_t k = 0; k < count; ++k) estimate[k] = cost(k);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return estimate[a] > estimate[b]; });
  }
  std::vector<std::optional<Result>> results(count);
  std::vector<char> finished(count, 0);
  std::mutex mutex;
  std::condition_variable changed;
  std::size_t next = 0;
  std::exception_ptr error;
  const std::size_t threads = std::max<std::size_t>(1, std::min<std::size_t>(std::max(jobs, 1), count));
  std::size_t running = threads;

  auto worker = [&] {
    for (;;) {
      std::size_t k;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (next >= count || error || interrupted()) break;
        k = order[next++];
      }
      std::optional<Result> r;
      std::exception_ptr failure;
      try {
        r = compute(k);
      } catch (...) {
        failure = std::current_exception();
      }
      {
        std::lock_guard<std::mutex> lock(mutex);
        results[k] = std::move(r);
        finished[k] = 1;
        if (failure && !error) error = failure;
      }
      changed.notify_all();
    }
    {
      std::lock_guard<std::mutex> lock(mutex);
      --running;
    }
    changed.notify_all();
  };

  std::vector<std::thread> pool;
  if (count > 0)
    for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(worker);
  // This thread only delivers, in cell order.
  for (std::size_t k = 0; k < count; ++k) {
    std::unique_lock<std::mutex> lock(mutex);
    changed.wait(lock, [&] { return finished[k] || running == 0 || error; });
    if (error || !finished[k]) break;  // a failed cell, or the rest never started (interrupt)
    std::optional<Result> r = std::move(results[k]);
    lock.unlock();
    try {
      if (r) deliver(k, *r);
    } catch (...) {  // e.g. a row that cannot be written: stop the pool first
      std::lock_guard<std::mutex> guard(mutex);
      error = std::current_exception();
      break;
    }
  }
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace lab
