#include "wait_word.h"

#include <chrono>
#include <climits>
#include <thread>

#if defined(__linux__)
#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace particles {

namespace {

void relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// Sleeps while *word == seen (returns at once if it differs; may also
// return spuriously: the caller checks again).
void sleepWhile(const std::atomic<std::uint32_t>& word, std::uint32_t seen) {
#if defined(__linux__)
  syscall(SYS_futex, reinterpret_cast<const std::uint32_t*>(&word), FUTEX_WAIT_PRIVATE, seen, nullptr, nullptr, 0);
#else
  (void)word, (void)seen;
  std::this_thread::yield();
#endif
}

void wakeAll(const std::atomic<std::uint32_t>& word) {
#if defined(__linux__)
  syscall(SYS_futex, reinterpret_cast<const std::uint32_t*>(&word), FUTEX_WAKE_PRIVATE, INT_MAX, nullptr, nullptr, 0);
#else
  (void)word;
#endif
}

}  // namespace

// The store and the waiter's registration are sequentially consistent, so
// of "store the value, then look for sleepers" and "register as a sleeper,
// then look at the value" at least one sees the other: either the storer
// wakes the waiter, or the waiter sees the value and does not sleep. The
// futex itself refuses to sleep when the word no longer holds what the
// waiter saw.
void WaitWord::store(std::uint32_t value) {
  value_.store(value, std::memory_order_seq_cst);
  if (sleepers_.load(std::memory_order_seq_cst) != 0) wakeAll(value_);
}

void WaitWord::waitUntilReached(std::uint32_t target) const {
  if (reached(value_.load(std::memory_order_acquire), target)) return;
  using Clock = std::chrono::steady_clock;
  const Clock::time_point until =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::micro>(kSpinMicroseconds));
  // The clock is read every 16 pauses: a pause costs 10 ns on bare metal and
  // over 300 ns in a VM that traps it, so a spin is bounded in time, not count.
  for (int spins = 1;; ++spins) {
    relax();
    if (reached(value_.load(std::memory_order_acquire), target)) return;
    if (spins % 16 == 0 && Clock::now() >= until) break;
  }
  sleepers_.fetch_add(1, std::memory_order_seq_cst);
  for (std::uint32_t seen; !reached(seen = value_.load(std::memory_order_seq_cst), target);) sleepWhile(value_, seen);
  sleepers_.fetch_sub(1, std::memory_order_release);
}

}  // namespace particles
