#pragma once
// Point-to-point waits between the threads of one parallel region: each part
// (a thread's share of the particles) publishes how many stages it has
// finished a piece of, and a thread that needs that piece waits for the
// count instead of a barrier of the whole team. The store orders the piece's
// writes before the reads that follow the wait (wait_word.h: a short spin,
// then a sleep in the kernel, so that a waiter never holds a core the thread
// it waits for could use).
#include <vector>

#include "wait_word.h"

namespace particles {

class StageProgress {
 public:
  explicit StageProgress(int parts) : done_(static_cast<std::size_t>(parts)) {}
  // Part `part` has finished its piece of stages 0 … stages − 1.
  void publish(int part, int stages) { done_[part].count.store(static_cast<std::uint32_t>(stages)); }
  // Returns once part `part` has published at least `stages`.
  void waitFor(int part, int stages) const { done_[part].count.waitUntilReached(static_cast<std::uint32_t>(stages)); }

 private:
  struct alignas(64) Count {  // one cache line each: no two parts' counts share one
    WaitWord count;
  };
  std::vector<Count> done_;
};

}  // namespace particles
