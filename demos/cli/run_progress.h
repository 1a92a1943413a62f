#pragma once
// The progress line of `particle-lab run` on a terminal: once the run has
// taken a second, at most four times a second, stderr's last line is
//   particle-lab: step 41200/100000 (41%), t = 82.4 s, 1.8 s elapsed, ~2.6 s left
// rewritten in place (carriage return) and erased when the run ends, so that
// what stays on the terminal is what a run without it prints. Off when
// stderr is not a terminal (a file, a pipe, the tests).
#include <chrono>
#include <cstdio>

namespace cli {

class RunProgress {
 public:
  // steps: the run's length; shown: whether the line is drawn at all.
  RunProgress(long long steps, bool shown, std::FILE* out = stderr);
  ~RunProgress() { erase(); }
  RunProgress(const RunProgress&) = delete;
  RunProgress& operator=(const RunProgress&) = delete;

  // After step `step` at simulated time t.
  void update(long long step, double t);
  // Erases the line if one is drawn (before any other output to the terminal).
  void erase();

  // Whether stderr is a terminal.
  static bool stderrIsTerminal();

 private:
  using Clock = std::chrono::steady_clock;
  long long steps_;
  bool shown_, drawn_ = false;
  std::FILE* out_;
  Clock::time_point start_, next_;
};

}  // namespace cli
