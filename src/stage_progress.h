#pragma once
// Point-to-point waits between the threads of one parallel region: each part
// (a thread's share of the particles) publishes how many stages it has
// finished a piece of, and a thread that needs that piece waits for the
// count instead of a barrier of the whole team. The release store and the
// acquire load order the piece's writes before the reads that follow the wait.
#include <atomic>
#include <thread>
#include <vector>

namespace particles {

class StageProgress {
 public:
  explicit StageProgress(int parts) : done_(static_cast<std::size_t>(parts)) {}
  // Part `part` has finished its piece of stages 0 … stages − 1.
  void publish(int part, int stages) { done_[part].count.store(stages, std::memory_order_release); }
  // Returns once part `part` has published at least `stages`: spins for a
  // while (the other thread is usually a few microseconds away), then yields
  // the core, so that a team larger than the machine's cores still moves.
  void waitFor(int part, int stages) const {
    for (int spins = 0; done_[part].count.load(std::memory_order_acquire) < stages; ++spins) {
      if (spins < kSpins)
        relax();
      else
        std::this_thread::yield();
    }
  }

 private:
  static constexpr int kSpins = 4096;
  static void relax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  struct alignas(64) Count {  // one cache line each: no two parts' counts share one
    std::atomic<int> count{0};
  };
  std::vector<Count> done_;
};

}  // namespace particles
