#pragma once
// How many threads a system's steps run on: the most threads allowed
// (setThreadCount) while they make the steps faster, one thread while they
// do not. Two threads beside busy programs can take far longer than one:
// each hand-off between them waits until the scheduler runs the other
// instead of a busy program. The steps' wall time on each count tells.
//
// The steps on the present count are timed (the median of the last
// `history`). Now and then a probe runs `probeSteps` steps on the other
// count, and the faster count is kept: more threads while the median of
// their steps is at most `gain` times one thread's.
// - On more threads a probe runs as soon as their median is no faster than
//   one thread's at the last probe.
// - On one thread, a probe runs after a wait that grows with what the
//   probes that lost cost (at most `probeShare` of the time spent stepping,
//   between `quickestRetry` and `longestRetry`), so the threads come back
//   within seconds of the machine getting quiet. It starts with one hand-off:
//   an empty parallel region on the threads (after one that starts them). If
//   that alone takes `handoff` times a one-thread step, a step of many
//   hand-offs cannot be faster, and the probe ends there (on a machine far
//   busier than its cores a probe step took 140 one-thread steps). A probe
//   step slower than `abandon` times the present median ends its probe too.
// A step on more threads that entered no parallel region (a system below
// every parallel loop's threshold) ends the probing until the system's
// structure changes: its threads have nothing to share.
// The results are the same bits on any count (particles/threads.h), so the
// choice changes the time only.
#include <cstdint>
#include <functional>
#include <vector>

#include "particles/threads.h"

namespace particles {

// The controller behind ParticleSystem::threadUse(): the engine's own
// (src/), with ThreadUseSettings public in particles/threads.h.
class ThreadUse {
 public:
  ThreadUseSettings settings;
  // Wall time in seconds; a steady clock unless a test gives its own.
  std::function<double()> clock;
  // The wall time of one hand-off on `threads` threads: an empty parallel
  // region (the threads start, meet at its end's barrier and part) after one
  // that starts them, unless a test gives its own.
  std::function<double(int threads)> handoff;

  ThreadUse();
  // The threads for the next step (1 ≤ threads ≤ most) of a system whose
  // structure stamp is `structure`, and the start of its timing.
  int begin(int most, std::uint64_t structure = 0);
  // Whether the step begin() chose follows one on more threads (or a
  // hand-off): the caller releases the idle threads (releaseIdleThreads) before stepping.
  bool releasesThreads() const { return release_; }
  // The end of the step begin() chose, which entered a parallel region or
  // not: its wall time is recorded.
  void end(bool parallel = true);

 private:
  bool probeDue() const;
  void finishProbe();
  // A probe of more threads lost, at `cost` beyond what one thread took: the next one waits longer.
  void lost(double cost);

  int most_ = 0;
  int present_ = 1;         // the count in use outside probes
  int threads_ = 1;         // the count of the step begun
  int previous_ = 1;        // the count of the last thread use (a step or a hand-off)
  bool release_ = false;
  double started_ = 0.0;
  double now_ = 0.0;        // the clock at the last end()
  std::vector<double> presentTimes_;  // the last steps on present_, oldest first
  bool probing_ = false;
  std::vector<double> probeTimes_;
  double otherMedian_ = -1.0;  // the other count's median from the last probe (< 0: none yet)
  double nextProbe_ = 0.0;     // clock time from which one thread may probe more
  double retry_ = 0.0;         // the wait after the last probe of more threads that lost
  int lostInARow_ = 0;         // probes of more threads lost since more threads last won
  std::uint64_t structure_ = 0;
  bool nothingToShare_ = false;  // a step on more threads entered no region: no probes
};

}  // namespace particles
