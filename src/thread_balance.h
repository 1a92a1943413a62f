#pragma once
// How a parallel pass splits its items (particles, constraints) among its
// threads: in proportion to how fast each thread went in the passes before,
// so that on a machine whose cores run at different speeds (one shared with
// other work) the threads finish together. Every pass that uses it gives the
// same bits for any split, so the balance changes the time only.
#include <vector>

namespace particles {

class ThreadBalance {
 public:
  // c[0] = 0 ≤ c[1] ≤ … ≤ c[threads] = 1: thread t takes the fraction
  // [c[t], c[t + 1]) of the items (equal shares until update() has measured).
  std::vector<double> cuts(int threads);
  // Thread t's items among n: [bounds[t], bounds[t + 1]).
  std::vector<int> bounds(int n, int threads);
  // After a pass: each thread's items done and its busy time (s), waiting excluded.
  void update(const std::vector<double>& items, const std::vector<double>& busy);

  // One pass's measurement, taken inside its parallel region: run(work)
  // calls work(part) for each of the pass's parts (thread t's share is part
  // t), one part per thread, or several each in a smaller team (as in a
  // nested region); work returns the items it did and is timed. run() may
  // be called several times in one region: the items and times add up.
  // each(work) calls work(part) on the same parts, untimed (a later phase
  // of the pass on the same shares).
  class Pass {
   public:
    explicit Pass(int parts) : items_(parts, 0.0), busy_(parts, 0.0) {}
    template <class Work>
    void run(const Work& work) {
      each([&](int part) {
        const double start = wallClock();
        const double done = work(part);
        busy_[part] += wallClock() - start;
        items_[part] += done;
      });
    }
    template <class Work>
    void each(const Work& work) const {
      const int parts = static_cast<int>(busy_.size());
      for (int part = teamMember(); part < parts; part += teamSize()) work(part);
    }

   private:
    friend class ThreadBalance;
    static int teamMember();  // omp_get_thread_num(), omp_get_num_threads(), omp_get_wtime()
    static int teamSize();
    static double wallClock();
    std::vector<double> items_, busy_;
  };
  void update(const Pass& pass) { update(pass.items_, pass.busy_); }

 private:
  std::vector<double> share_;  // each thread's fraction of the items, summing to 1
};

}  // namespace particles
