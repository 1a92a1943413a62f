#include "rewind_buffer.h"

#include <algorithm>

namespace demo {

void RewindBuffer::record(long long frame, const particles::ParticleSystem& system, double owedTime,
                          long long steps) {
  if (frame % stride_ != 0 || !system.finite() || has(frame)) return;
  entries_.push_back({frame, system.snapshot(), owedTime, steps});
  if (static_cast<int>(entries_.size()) < capacity) return;
  stride_ *= 2;
  std::deque<RewindEntry> kept;
  for (RewindEntry& e : entries_)
    if (e.frame % stride_ == 0) kept.push_back(std::move(e));
  entries_ = std::move(kept);
}

bool RewindBuffer::has(long long frame) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const RewindEntry& e) { return e.frame == frame; });
}

const RewindEntry* RewindBuffer::rewindTo(long long frame) {
  while (!entries_.empty() && entries_.back().frame > frame) entries_.pop_back();
  if (entries_.empty() || entries_.back().frame != frame) return nullptr;
  // Later records continue on the current stride from here.
  return &entries_.back();
}

}  // namespace demo
