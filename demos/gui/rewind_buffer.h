#pragma once
// Recent states of one simulation, for rewinding after a divergence (key b).
#include <deque>

#include "particles/particle_system.h"

namespace demo {

// Keeps a snapshot every `interval` simulated seconds over the last `span`
// seconds. Only finite states are recorded, so a rewind always lands on one.
class RewindBuffer {
 public:
  // 40 snapshots: 20 MB for a 128 × 128 cloth. The span covers a compare pane
  // that ran on for seconds after another diverged, since 'b' rewinds every
  // pane to a second before the first divergence.
  static constexpr double interval = 0.2;  // simulated seconds between snapshots
  static constexpr double span = 8.0;      // simulated seconds kept

  void clear() { snapshots_.clear(); }
  // Records the state if `interval` has passed since the last record.
  void record(const particles::ParticleSystem& system);
  // The newest snapshot taken at or before `time` (the oldest if none is that
  // old); null when empty. Later snapshots are dropped, as that future is gone.
  const particles::Snapshot* rewindTo(double time);

 private:
  std::deque<particles::Snapshot> snapshots_;
};

}  // namespace demo
