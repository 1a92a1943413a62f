#pragma once
// Recent states of one simulation, for rewinding (key b).
#include <deque>
#include <optional>

#include "particles/particle_system.h"

namespace demo {

// One recorded moment: the state and the counters that go with it.
struct RewindEntry {
  long long frame = 0;        // frames advanced when recorded (shared by every pane)
  particles::Snapshot state;
  double owedTime = 0.0;      // simulated time not yet stepped at that frame
  long long steps = 0;
};

// Keeps a snapshot every `stride` advanced frames, keyed by the frame count,
// which every pane of compare mode shares: rewinding all panes to one frame
// brings them to one time. When full, every other snapshot is dropped and the
// stride doubles, so the whole run stays reachable at a coarser grain and a
// pane that ran on long after another diverged still has the frames the
// other one has (all keys are multiples of the base stride times a power of 2).
// Only finite states are recorded, so a rewind always lands on one.
class RewindBuffer {
 public:
  static constexpr int capacity = 40;    // snapshots: 20 MB for a 128 × 128 cloth
  static constexpr int baseStride = 12;  // frames: 0.2 s at 60 frames/s

  void clear() { entries_.clear(); stride_ = baseStride; }
  // Records when `frame` is a multiple of the current stride.
  void record(long long frame, const particles::ParticleSystem& system, double owedTime, long long steps);
  bool has(long long frame) const;
  // The recorded frames, oldest first.
  const std::deque<RewindEntry>& entries() const { return entries_; }
  // The entry of `frame` (which must be recorded); later ones are dropped, as that future is gone.
  const RewindEntry* rewindTo(long long frame);

 private:
  std::deque<RewindEntry> entries_;
  long long stride_ = baseStride;
};

}  // namespace demo
