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

 private:
  std::vector<double> share_;  // each thread's fraction of the items, summing to 1
};

}  // namespace particles
