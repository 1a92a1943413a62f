#pragma once
// A flag through which a program stops long work inside one step: a signal
// handler raises it, and the engine's iterative loops (each conjugate-gradient
// iteration) end early when it is up. A step cut short so is not a result:
// the caller that raised the flag discards it. Without a flag (the default)
// nothing is ever cancelled.
#include <atomic>

namespace particles {

// The flag to watch (it must outlive every step), or nullptr for none.
void setCancelFlag(const std::atomic<bool>* flag);
// Whether the watched flag is up (a relaxed load: cheap enough per iteration).
bool cancelRequested();

}  // namespace particles
