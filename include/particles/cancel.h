#pragma once
// Stopping long work at a user's request: a program that wants a signal to
// stop work inside one step or one load sets a flag with setCancelFlag (its
// signal handler raises the flag), and every long loop of the engine and of
// the scene reader watches it:
//   - each conjugate-gradient iteration (linear/conjugate_gradient.h);
//   - xpbd's substeps and its constraint passes within a substep;
//   - dopri5's attempts (seven evaluations each, up to 100,000 a step);
//   - reading a scene file: the parser, the reader's lists and the check of
//     particles starting inside colliders.
// A loop whose iterations are cheap but may be many (a contact pass's pairs
// and impacts, src/collision/) checks through a CancelPoll.
// A loop that sees the flag up ends early and leaves its result unfinished:
// a step cut short is not a result, and the caller that raised the flag
// discards it (the runner writes no row for it; the laboratory records no
// cell). The scene reader throws Cancelled instead, since a half-read scene
// is nothing. Without a flag (the default) nothing is ever cancelled.
//
// The check costs two relaxed atomic loads (a few cycles, no fence, no call),
// so a loop may check once per iteration where an iteration does a sweep or a
// solve; an inner loop of nanoseconds per iteration (a pair test, an impact)
// checks through a CancelPoll, which reads the flag once every `period`
// calls. A loop must answer within about a second of the flag going up.
#include <atomic>
#include <exception>

namespace particles {

// The flag to watch (it must outlive every step), or nullptr for none.
void setCancelFlag(const std::atomic<bool>* flag);

namespace detail {
extern std::atomic<const std::atomic<bool>*> cancelFlag;  // set by setCancelFlag
}  // namespace detail

// Whether the watched flag is up.
inline bool cancelRequested() {
  const std::atomic<bool>* flag = detail::cancelFlag.load(std::memory_order_relaxed);
  return flag != nullptr && flag->load(std::memory_order_relaxed);
}

// A countdown for inner loops: poll() reads the flag on every period-th call
// and once it has seen it up answers true from then on.
//   CancelPoll cancel;
//   for (const Pair& p : pairs) { if (cancel.poll()) return; ... }
class CancelPoll {
 public:
  explicit CancelPoll(int period = 1024) : period_(period), left_(period) {}
  bool poll() {
    if (seen_) return true;
    if (--left_ > 0) return false;
    left_ = period_;
    seen_ = cancelRequested();
    return seen_;
  }

 private:
  int period_, left_;
  bool seen_ = false;
};

// What work that cannot end early with a partial result (reading a scene)
// throws when the flag is up. Not a std::runtime_error, so that handlers of
// bad input or failed writes never take it for one.
class Cancelled : public std::exception {
 public:
  const char* what() const noexcept override { return "cancelled"; }
};

// Throws Cancelled when the flag is up.
inline void throwIfCancelled() {
  if (cancelRequested()) throw Cancelled();
}

}  // namespace particles
