#include "rewind_buffer.h"

namespace demo {

void RewindBuffer::record(const particles::ParticleSystem& system) {
  if (!system.finite()) return;
  if (!snapshots_.empty() && system.time() < snapshots_.back().time + interval * (1.0 - 1e-9)) return;
  snapshots_.push_back(system.snapshot());
  while (snapshots_.size() > 1 && snapshots_.back().time - snapshots_.front().time > span)
    snapshots_.pop_front();
}

const particles::Snapshot* RewindBuffer::rewindTo(double time) {
  if (snapshots_.empty()) return nullptr;
  while (snapshots_.size() > 1 && snapshots_.back().time > time) snapshots_.pop_back();
  return &snapshots_.back();
}

}  // namespace demo
