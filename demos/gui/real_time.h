#pragma once
// Simulated time over wall time, the demo's "× real time" readout: over the
// last second of wall time (a sliding window of frames), and over the whole
// run. A pause, a reset or a rewind starts the window again, since simulated
// time then stands or jumps.
#include <deque>

namespace demo {

class RealTimeMeter {
 public:
  // A frame drawn at `wallSeconds` (a monotonic clock) with the simulation
  // at `simSeconds`; `running` false (paused, stopped) restarts the window.
  void record(double wallSeconds, double simSeconds, bool running);
  void restart() { window_.clear(); }

  // Simulated over wall seconds across the window; known once it spans at
  // least a quarter of a second of wall time.
  bool known() const;
  double ratio() const;

  // Across every running frame since the start: simulated and wall seconds.
  double totalSimSeconds() const { return totalSim_; }
  double totalWallSeconds() const { return totalWall_; }

  static constexpr double kWindowSeconds = 1.0;
  // Below this the demo says "slow motion" (a readout of 0.95-1 is the pacing's own jitter).
  static constexpr double kSlowMotionBelow = 0.95;

 private:
  struct Sample {
    double wall, sim;
  };
  std::deque<Sample> window_;
  double totalSim_ = 0.0, totalWall_ = 0.0;
};

}  // namespace demo
