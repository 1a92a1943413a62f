#pragma once
// A barrier of the threads of one parallel region that waits as WaitWord
// does (a short spin, then a sleep in the kernel), used in place of
// OpenMP's barriers: libgomp's waiting threads spin for 300000 pauses (3 ms
// on bare metal, 7 ms on a 2-core EPYC VM) unless the environment or the
// executable's start (src/startup/openmp_short_spin.cpp) says otherwise, and
// a count of pauses is not a time.
#include <atomic>
#include <cstdint>

#include "wait_word.h"

namespace particles {

class TeamBarrier {
 public:
  // Returns once `parties` threads (the whole team, the same every round)
  // have called it this round; what each wrote before is then visible to all.
  void arriveAndWait(int parties) {
    if (parties <= 1) return;
    // The round is read before arriving: it cannot move on until this thread has arrived.
    const std::uint32_t round = round_.load();
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == parties) {
      arrived_.store(0, std::memory_order_relaxed);  // published by the round's store
      round_.store(round + 1);
    } else {
      round_.waitUntilReached(round + 1);
    }
  }

 private:
  alignas(64) std::atomic<int> arrived_{0};
  alignas(64) WaitWord round_;
};

}  // namespace particles
