#pragma once
// How many threads a system's steps run on: the most threads allowed
// (setThreadCount) while they make the steps faster, one thread while they
// do not. Two threads beside busy programs can take far longer than one:
// each hand-off between them waits until the scheduler runs the other
// instead of a busy program. The steps' wall time on each count tells.
//
// The steps on the present count are timed (the mean of the last
// `history`: what they cost; their median is the typical step). Now and
// then a probe runs `probeSteps` steps on the other count, and the faster
// count is kept: more threads while the mean of their steps is at most
// `gain` times one thread's.
// - A probe runs after a wait that grows with what the probes that lost
//   cost (at most `probeShare` of the time spent stepping, between
//   `quickestRetry` and `longestRetry`), so the faster count comes back
//   within seconds of a change in the machine's load; on more threads also
//   as soon as their mean is over one thread's at the last probe. (Beside
//   two busy programs one thread alone on a core ran 1.9 times faster than
//   two threads sharing theirs, which compared with one thread's time from
//   a probe made while it shared a core, kept their count.)
// - A probe of more threads starts with one hand-off:
//   an empty parallel region on the threads (after one that starts them). If
//   that alone takes `handoff` times a one-thread step, a step of many
//   hand-offs cannot be faster, and the probe ends there (on a machine far
//   busier than its cores a probe step took 140 one-thread steps). It also
//   ends as soon as its steps so far decide it: once more threads could not
//   win even if every step left took one thread's mean over the thread count
//   (beside one busy program a probe's second or third step on two threads
//   stalled for 120–200 ms while the first two had already lost). A lost
//   probe is charged the threads' start, hand-off and release and what its
//   steps took beyond one thread's.
// - A probe step slower than `abandon` times the present median ends its
//   probe too.
// The first step after the system's structure changes is not timed (its
// caches are built then: a scene's first step took three times the next
// ones, which made a probe of two threads win falsely), unless the step
// before it was left out too: a structure that changes every step still
// has every other step timed.
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
  // The wall times of a probe's start on `threads` threads: an empty
  // parallel region that starts them, then one hand-off, a second empty
  // region (the threads start, meet at its end's barrier and part); unless a
  // test gives its own.
  struct HandOff {
    double start = 0.0;  // s: the threads' start, the first region
    double trip = 0.0;   // s: the hand-off, the second
  };
  std::function<HandOff(int threads)> handoff;
  // Ends the idle threads that steps on more threads started
  // (particles/threads.h: releaseIdleThreads), before a step on one thread
  // that follows them; returns the seconds it took. A test gives its own.
  std::function<double()> release;

  ThreadUse();
  // The threads for the next step (1 ≤ threads ≤ most) of a system whose
  // structure stamp is `structure`, and the start of its timing.
  int begin(int most, std::uint64_t structure = 0);
  // The end of the step begin() chose, which entered a parallel region or
  // not: its wall time is recorded.
  void end(bool parallel = true);

 private:
  bool probeDue() const;
  // Whether the probe's steps so far decide it: more threads cannot win.
  bool probeDecided() const;
  void finishProbe();
  // A probe lost, at `cost` beyond what the present count took: the next one waits longer.
  // On one thread the lost probe was of more, whose release comes next and adds to its cost.
  void lost(double cost);
  // `seconds` more of what the last lost probe cost (its start and steps, then the release of its
  // threads): the wait before the next grows to keep that within probeShare of it.
  void charge(double seconds);

  int most_ = 0;
  int present_ = 1;         // the count in use outside probes
  int threads_ = 1;         // the count of the step begun
  int previous_ = 1;        // the count of the last thread use (a step or a hand-off)
  double started_ = 0.0;
  double now_ = 0.0;        // the clock at the last end()
  std::vector<double> presentTimes_;  // the last steps on present_, oldest first
  bool probing_ = false;
  std::vector<double> probeTimes_;
  double otherMean_ = -1.0;    // the other count's mean from the last probe (< 0: none yet)
  double nextProbe_ = 0.0;     // clock time from which the other count may be probed
  double retry_ = 0.0;         // the wait after the last probe that lost
  double probeStart_ = 0.0;    // s: the present probe's start (threads' start and hand-off, or their release), charged to it if it loses
  int lostInARow_ = 0;         // probes lost since the present count last changed
  double lostCost_ = 0.0;      // s: what the last probe that lost cost, charged so far
  double lostAt_ = 0.0;        // clock time it ended
  bool releaseCharged_ = false;  // the next release is the lost probe's
  std::uint64_t structure_ = 0;
  bool untimed_ = false;         // the step begun is not timed: the first after a structure change
  bool nothingToShare_ = false;  // a step on more threads entered no region: no probes
};

}  // namespace particles
