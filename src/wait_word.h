#pragma once
// A 32-bit word that the threads of one parallel region wait on (a stage
// count, a barrier's round). A waiter spins for kSpinMicroseconds — the
// thread it waits for is usually that close — and then sleeps in the kernel
// (a futex on the word) until a store wakes it. On a machine shared with
// other programs the thread waited for may be descheduled for milliseconds;
// a waiter that kept spinning would hold the core that thread needs (two
// threads beside one busy program ran a step 240 times slower than one
// thread did). No thread ever sleeps with the value it waits for stored.
//
// Values count up and may wrap: v has reached t when (int32)(v − t) ≥ 0.
#include <atomic>
#include <cstdint>

namespace particles {

class WaitWord {
 public:
  // How long a waiter spins before it sleeps. A sleep and a wake-up cost
  // 5–20 µs on a shared 2-core VM; spinning about as long as a sleep costs
  // keeps a wait within twice the best either choice could have done.
  static constexpr double kSpinMicroseconds = 30.0;

  std::uint32_t load() const { return value_.load(std::memory_order_acquire); }
  // Stores value (ordered after this thread's earlier writes) and wakes the
  // threads asleep on the word.
  void store(std::uint32_t value);
  // Returns once the word has reached target; the writes made before the
  // store that reached it are then visible to this thread.
  void waitUntilReached(std::uint32_t target) const;

  static bool reached(std::uint32_t value, std::uint32_t target) {
    return static_cast<std::int32_t>(value - target) >= 0;
  }

 private:
  // The futex calls see the word as a plain 32-bit int.
  static_assert(sizeof(std::atomic<std::uint32_t>) == sizeof(std::uint32_t));
  std::atomic<std::uint32_t> value_{0};
  // Waiters that may be asleep (or about to be): store() wakes only when there are some.
  mutable std::atomic<std::uint32_t> sleepers_{0};
};

}  // namespace particles
