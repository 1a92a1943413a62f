#include "real_time.h"

namespace demo {

void RealTimeMeter::record(double wallSeconds, double simSeconds, bool running) {
  if (!running) {
    window_.clear();
    return;
  }
  if (!window_.empty()) {
    const Sample& last = window_.back();
    if (simSeconds < last.sim) {  // a reset or rewind: the clock jumped back
      window_.clear();
    } else {
      totalSim_ += simSeconds - last.sim;
      totalWall_ += wallSeconds - last.wall;
    }
  }
  window_.push_back({wallSeconds, simSeconds});
  while (window_.size() > 2 && window_.back().wall - window_[1].wall >= kWindowSeconds) window_.pop_front();
}

bool RealTimeMeter::known() const { return window_.size() >= 2 && window_.back().wall - window_.front().wall >= 0.25; }

double RealTimeMeter::ratio() const {
  if (window_.size() < 2) return 0.0;
  const double wall = window_.back().wall - window_.front().wall;
  return wall > 0.0 ? (window_.back().sim - window_.front().sim) / wall : 0.0;
}

}  // namespace demo
