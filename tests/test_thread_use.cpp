// How many threads a system's steps run on (src/thread_use.h): more
// threads while their steps are faster, one thread while a slow thread
// makes them slower, more again once it is gone; with the same bits as one
// thread throughout. The step times come from a simulated clock (a step on
// two threads takes what a slow thread would make it take), so nothing here
// depends on the machine's speed or load.
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <vector>

#include "bench/cloth_grid.h"
#include "integrators/rk4.h"
#include "particles/particle_system.h"
#include "thread_use.h"
#include "particles/threads.h"
#include "system_internals.h"

namespace {

using particles::ThreadUse;

// Step times, seconds: one thread 1 ms; two threads 0.55 ms, or 3 ms while
// one of them is slowed (descheduled in favour of another program). A
// hand-off between the threads (an empty region) takes 20 µs, or 2 ms while
// one is slowed, unless the test makes it quick whatever the threads; the
// threads' start before it as long again, not in the hand-off's own time.
struct SimulatedMachine {
  bool slowThread = false;
  bool quickHandoff = false;
  // Beside a busy program: two threads' steps alternate 0.4 ms and 2.4 ms
  // (the other thread descheduled every other step), mean 1.4 ms.
  bool alternating = false;
  mutable int twoThreadSteps = 0;
  double now = 100.0;
  double releaseTime = 0.0;  // s: what ending the idle threads takes
  int handoffs = 0;
  int releases = 0;
  std::vector<double> handoffAt;  // the clock at each hand-off's start
  double oneThread = 1e-3;     // s: a step on one thread
  double twoThreads = 0.55e-3;  // s: on two, neither slowed
  double stepTime(int threads) const {
    if (threads == 1) return oneThread;
    if (alternating) return ++twoThreadSteps % 2 ? 0.4e-3 : 2.4e-3;
    return slowThread ? 3e-3 : twoThreads;
  }
  double handoffTime() const { return slowThread && !quickHandoff ? 2e-3 : 2e-5; }
};

// Steps `count` times through use.begin()/end() on `machine`; the thread count of each step.
std::vector<int> run(ThreadUse& use, SimulatedMachine& machine, int most, int count) {
  std::vector<int> counts;
  for (int k = 0; k < count; ++k) {
    const int threads = use.begin(most);
    machine.now += machine.stepTime(threads);
    use.end();
    counts.push_back(threads);
  }
  return counts;
}

int stepsOn(const std::vector<int>& counts, int threads, std::size_t from = 0) {
  int n = 0;
  for (std::size_t k = from; k < counts.size(); ++k) n += counts[k] == threads;
  return n;
}

ThreadUse simulated(SimulatedMachine& machine) {
  ThreadUse use;
  use.clock = [&machine] { return machine.now; };
  use.handoff = [&machine](int) {
    ++machine.handoffs;
    machine.handoffAt.push_back(machine.now);
    machine.now += 2.0 * machine.handoffTime();  // the threads' start, then the hand-off
    return ThreadUse::HandOff{machine.handoffTime(), machine.handoffTime()};
  };
  use.release = [&machine] {
    ++machine.releases;
    machine.now += machine.releaseTime;
    return machine.releaseTime;
  };
  return use;
}

}  // namespace

// Quiet: after `history` steps on one thread a probe finds two faster and
// they stay. A slow thread: within a few steps back on one, which then
// tries two rarely, each try ending at its first hand-off, each try's cost
// (the threads' start and the hand-off) within the probe share of the time
// until the next. Quiet again: two threads return within the
// longest retry.
TEST(ThreadUse, FallsBackWhileAThreadIsSlowAndReturnsWhenItIsNot) {
  SimulatedMachine machine;
  ThreadUse use = simulated(machine);
  const particles::ThreadUseSettings s = use.settings;

  const std::vector<int> quiet = run(use, machine, 2, 200);
  for (int k = 0; k < s.history; ++k) EXPECT_EQ(quiet[k], 1) << "step " << k;
  EXPECT_EQ(quiet[s.history], 2) << "the first probe";
  EXPECT_GE(stepsOn(quiet, 2, s.history), 200 - s.history - s.probeSteps)
      << "two threads kept while faster, but for a probe of one thread";

  machine.slowThread = true;
  const double slowStart = machine.now;
  const int handoffsBefore = machine.handoffs;
  const std::vector<int> slow = run(use, machine, 2, 20000);  // 20 s on one thread
  int firstOnOne = 0;
  while (slow[firstOnOne] == 2) ++firstOnOne;
  EXPECT_LE(firstOnOne, s.history) << "the slowdown is noticed within the history";
  EXPECT_EQ(stepsOn(slow, 2, firstOnOne), 0) << "no step on two threads: each try ends at its hand-off";
  const int tries = machine.handoffs - handoffsBefore;
  EXPECT_GT(tries, 3) << "one thread tries two now and then";
  EXPECT_LE(tries * 2.0 * machine.handoffTime(), s.probeShare * (machine.now - slowStart)) << tries << " tries";
  // Each try that lost, its threads' start included, is at most the probe
  // share of the time until the next.
  for (std::size_t k = handoffsBefore + 1; k < machine.handoffAt.size(); ++k)
    EXPECT_LE(2.0 * machine.handoffTime(), s.probeShare * (machine.handoffAt[k] - machine.handoffAt[k - 1]))
        << "try " << k - handoffsBefore;

  machine.slowThread = false;
  const std::vector<int> after = run(use, machine, 2, 20000);
  int back = 0;
  while (back < static_cast<int>(after.size()) && after[back] == 1) ++back;
  ASSERT_LT(back, static_cast<int>(after.size())) << "two threads came back";
  EXPECT_LE(back * machine.stepTime(1), s.longestRetry + 0.1) << "within the longest retry";
  // Kept, but for probes of one thread: those after the first (which comes
  // after the quickest retry) cost at most the probe share of the time.
  const int onOne = stepsOn(after, 1, static_cast<std::size_t>(back));
  const double onTwo = (static_cast<int>(after.size()) - back) * machine.stepTime(2);
  EXPECT_LE((onOne - s.probeSteps) * (machine.stepTime(1) - machine.stepTime(2)), s.probeShare * onTwo)
      << onOne << " steps on one thread";
}

// A slow thread behind a quick hand-off: probes of two threads run their
// steps and lose; the time they lose stays within the probe share.
TEST(ThreadUse, ProbesThatLoseCostAtMostTheProbeShare) {
  SimulatedMachine machine;
  machine.slowThread = true;
  machine.quickHandoff = true;
  ThreadUse use = simulated(machine);
  const double start = machine.now;
  const std::vector<int> counts = run(use, machine, 2, 20000);
  const int probes = stepsOn(counts, 2);
  EXPECT_GT(probes, 3);
  const double lost = probes * (machine.stepTime(2) - machine.stepTime(1));
  EXPECT_LE(lost, use.settings.probeShare * (machine.now - start)) << probes << " probe steps";
}

// Two threads' steps alternating fast and slow: their mean is slower than one
// thread, though two of three probe steps can be fast. One thread is kept:
// steps on two threads are the probes' only, and the run takes at most the
// probe share longer than on one thread.
TEST(ThreadUse, AlternatingFastAndSlowStepsKeepOneThread) {
  SimulatedMachine machine;
  machine.alternating = true;
  machine.quickHandoff = true;
  ThreadUse use = simulated(machine);
  const double start = machine.now;
  const std::vector<int> counts = run(use, machine, 2, 20000);
  EXPECT_LE(stepsOn(counts, 2), 60) << "two threads kept after a probe";
  EXPECT_LE(machine.now - start, (1.0 + use.settings.probeShare) * 20000 * machine.stepTime(1));
}

// The load moves: one thread first shares its core (2 ms a step, two threads
// 1.5 ms: two are kept), then has one to itself (1 ms, two threads still
// 1.5 ms). Two threads probe one within the longest retry and one is kept,
// though two threads' steps never got slower than one thread's at the last probe.
TEST(ThreadUse, OnMoreThreadsOneThreadIsProbedAfterAWait) {
  SimulatedMachine machine;
  machine.oneThread = 2e-3;
  machine.twoThreads = 1.5e-3;
  ThreadUse use = simulated(machine);
  const std::vector<int> shared = run(use, machine, 2, 2000);
  EXPECT_EQ(shared.back(), 2) << "two threads while one shares its core";
  machine.oneThread = 1e-3;
  const std::vector<int> alone = run(use, machine, 2, 20000);
  int back = 0;
  while (back < static_cast<int>(alone.size()) && alone[back] == 2) ++back;
  ASSERT_LT(back, static_cast<int>(alone.size())) << "one thread came back";
  EXPECT_LE(back * machine.twoThreads, use.settings.longestRetry + 0.1) << "within the longest retry";
  EXPECT_EQ(alone.back(), 1);
}

// A system's first step builds its caches: 12 ms against 1 ms on one thread
// after it; two threads beside a busy program alternate 0.4 and 2.4 ms (mean
// 1.4 ms: slower). Timed, the first step would make one thread's mean 3.2 ms
// and the first probe of two threads win. Left out, that probe loses, and a
// structure that changes every step still has every other step timed.
TEST(ThreadUse, TheFirstStepAfterAStructureChangeIsNotTimed) {
  SimulatedMachine machine;
  machine.alternating = true;
  machine.quickHandoff = true;
  ThreadUse use = simulated(machine);
  std::vector<int> counts;
  for (int k = 0; k < 100; ++k) {
    const int threads = use.begin(2, 5);
    machine.now += k == 0 ? 12e-3 : machine.stepTime(threads);
    use.end();
    counts.push_back(threads);
  }
  EXPECT_LE(stepsOn(counts, 2), use.settings.probeSteps) << "two threads kept after the first probe";

  SimulatedMachine changing;
  changing.alternating = true;
  changing.quickHandoff = true;
  ThreadUse every = simulated(changing);
  counts.clear();
  for (std::uint64_t k = 0; k < 2000; ++k) {
    const int threads = every.begin(2, 10 + k);
    changing.now += changing.stepTime(threads);
    every.end();
    counts.push_back(threads);
  }
  EXPECT_GE(stepsOn(counts, 2), 1) << "probed: every other step was timed";
  EXPECT_LE(stepsOn(counts, 2), 60) << "and two threads not kept";
}

// A probe step that takes `abandon` times the present median ends the probe at once.
TEST(ThreadUse, AHopelessProbeEndsAfterOneStep) {
  SimulatedMachine machine;
  machine.slowThread = true;
  machine.quickHandoff = true;
  ThreadUse use = simulated(machine);
  use.settings.abandon = 2.0;  // a 3 ms step against 1 ms
  const std::vector<int> counts = run(use, machine, 2, use.settings.history + 3);
  EXPECT_EQ(counts[use.settings.history], 2);
  EXPECT_EQ(counts[use.settings.history + 1], 1);
  EXPECT_EQ(counts[use.settings.history + 2], 1);
}

// A step on two threads that entered no parallel region (a system too small
// for any): back on one thread, with no further probe (nor hand-off) until
// the structure changes.
TEST(ThreadUse, AStepWithNothingToShareEndsTheProbesUntilTheStructureChanges) {
  SimulatedMachine machine;
  ThreadUse use = simulated(machine);
  std::vector<int> counts;
  auto step = [&](std::uint64_t structure, bool parallel) {
    const int threads = use.begin(2, structure);
    machine.now += machine.stepTime(1);
    use.end(parallel && threads > 1);
    counts.push_back(threads);
  };
  for (int k = 0; k < 500; ++k) step(7, false);
  EXPECT_EQ(stepsOn(counts, 2), 1) << "the first probe's step, then none";
  EXPECT_EQ(machine.handoffs, 1);
  counts.clear();
  for (int k = 0; k < 20; ++k) step(8, true);  // a new structure with work to share
  EXPECT_GE(stepsOn(counts, 2), 1) << "probed again";
  EXPECT_EQ(machine.handoffs, 2);
}

// Not adaptive: every step on the most threads. One thread at most: one, and no probe.
TEST(ThreadUse, FixedOrOneThreadIsNeverProbed) {
  SimulatedMachine machine;
  machine.slowThread = true;
  ThreadUse fixed = simulated(machine);
  fixed.settings.adaptive = false;
  EXPECT_EQ(stepsOn(run(fixed, machine, 3, 50), 3), 50);
  ThreadUse one = simulated(machine);
  EXPECT_EQ(stepsOn(run(one, machine, 1, 50), 1), 50);
}

// A new most count starts over: on one thread, probing the new count.
TEST(ThreadUse, ANewMostCountStartsOver) {
  SimulatedMachine machine;
  ThreadUse use = simulated(machine);
  run(use, machine, 2, 50);
  const std::vector<int> counts = run(use, machine, 4, 10);
  EXPECT_EQ(counts.front(), 1);
  EXPECT_EQ(counts[use.settings.history], 4);
}

// The step after one on more threads releases the idle threads, and so does
// the step after a try that ended at its hand-off (which started them); no other.
TEST(ThreadUse, AStepOnOneThreadAfterMoreOrAHandoffReleasesTheIdleOnes) {
  for (const bool quickHandoff : {true, false}) {
    SCOPED_TRACE(quickHandoff ? "probes run their steps" : "tries end at the hand-off");
    SimulatedMachine machine;
    machine.slowThread = true;
    machine.quickHandoff = quickHandoff;
    ThreadUse use = simulated(machine);
    int expected = 0, previous = 1;
    for (int k = 0; k < 5000; ++k) {
      const int handoffs = machine.handoffs, releases = machine.releases;
      const int threads = use.begin(2);
      const bool lostAtHandoff = machine.handoffs > handoffs && threads == 1;
      expected += (previous > 1 && threads == 1) || lostAtHandoff;
      EXPECT_EQ(machine.releases - releases, (previous > 1 && threads == 1) || lostAtHandoff ? 1 : 0) << "step " << k;
      machine.now += machine.stepTime(threads);
      use.end();
      previous = threads;
    }
    EXPECT_GT(machine.releases, 3);
    EXPECT_EQ(machine.releases, expected);
  }
}

// Ending the threads a lost try started is part of what it cost: each try
// (start, hand-off and release) stays within the probe share of the time
// until the next even when the release is what takes long.
TEST(ThreadUse, AReleaseAfterALostProbeIsChargedToIt) {
  SimulatedMachine machine;
  machine.slowThread = true;
  machine.releaseTime = 20e-3;
  ThreadUse use = simulated(machine);
  run(use, machine, 2, 20000);
  const double cost = 2.0 * machine.handoffTime() + machine.releaseTime;
  ASSERT_GT(machine.handoffAt.size(), 3u);
  for (std::size_t k = 1; k < machine.handoffAt.size(); ++k)
    EXPECT_LE(cost, use.settings.probeShare * (machine.handoffAt[k] - machine.handoffAt[k - 1]) + 1e-12) << "try " << k;
}

// A probe whose first step on two threads already loses (3 ms against one
// thread's 1 ms: even two more steps at 0.5 ms would make a mean over
// 0.9 ms) ends after that step, though it is not hopeless (under 4 × 1 ms).
TEST(ThreadUse, AProbeEndsOnceItsStepsDecideIt) {
  SimulatedMachine machine;
  machine.slowThread = true;
  machine.quickHandoff = true;
  ThreadUse use = simulated(machine);
  ASSERT_LT(machine.stepTime(2), use.settings.abandon * machine.stepTime(1));
  const std::vector<int> counts = run(use, machine, 2, 20000);
  int probes = 0;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    if (counts[k] != 2) continue;
    ++probes;
    EXPECT_TRUE(k + 1 == counts.size() || counts[k + 1] == 1) << "a second probe step at " << k + 1;
  }
  EXPECT_GT(probes, 3);
}

TEST(ThreadUse, SettingsOutOfRangeAreRefusedByName) {
  auto message = [](const std::function<void(particles::ThreadUseSettings&)>& change) {
    particles::ThreadUseSettings s;
    change(s);
    try {
      s.validate();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message([](auto&) {}), "accepted");
  EXPECT_EQ(message([](auto& s) { s.gain = 1.5; }), "thread use gain must be in (0, 1], got 1.5");
  EXPECT_EQ(message([](auto& s) { s.history = 0; }), "thread use history must be >= 1, got 0");
  EXPECT_EQ(message([](auto& s) { s.probeSteps = 0; }), "thread use probe steps must be >= 1, got 0");
  EXPECT_EQ(message([](auto& s) { s.abandon = 1.0; }), "thread use abandon must be > 1, got 1");
  EXPECT_EQ(message([](auto& s) { s.handoff = -1.0; }), "thread use handoff must be > 0, got -1");
  EXPECT_EQ(message([](auto& s) { s.probeShare = 0.0; }), "thread use probe share must be in (0, 1], got 0");
  EXPECT_EQ(message([](auto& s) { s.longestRetry = 0.01; }),
            "thread use longest retry must be >= the quickest retry (0.05 s), got 0.01");
}

// Through ParticleSystem::step: a cloth large enough for the threaded paths
// steps on two threads, falls back to one while a simulated slow thread
// makes two slower, and returns to two; its states are the one-thread run's
// bit for bit at every step, and each step reports the threads it ran on.
TEST(ThreadUse, AStepsThreadsFollowASlowThreadWithTheOneThreadBits) {
  const int steps = 160;
  const double dt = 1e-3;
  particles::Rk4Integrator rk4;
  particles::setThreadCount(1);
  particles::ParticleSystem alone = bench::clothGrid(48, 48, 0.05);
  std::vector<Eigen::VectorXd> states;
  for (int k = 0; k < steps; ++k) {
    EXPECT_EQ(alone.step(rk4, dt).threads, 1);
    Eigen::VectorXd state(2 * alone.positions().size());
    state << alone.positions(), alone.velocities();
    states.push_back(state);
  }

  particles::setThreadCount(2);
  particles::ParticleSystem shared = bench::clothGrid(48, 48, 0.05);
  SimulatedMachine machine;
  // The step's clock, read at its start and its end: the end adds the time
  // the step takes on the simulated machine on the threads it ran on.
  bool atEnd = false;
  particles::ThreadUse& controller = particles::SystemInternals::threadUse(shared);
  controller.clock = [&] {
    if (atEnd) machine.now += machine.stepTime(particles::threadCount());
    atEnd = !atEnd;
    return machine.now;
  };
  controller.handoff = [&](int) { return ThreadUse::HandOff{0.0, machine.handoffTime()}; };
  machine.quickHandoff = true;  // the probes run their steps (on two threads, for real)
  // Probes of two threads every 20 one-thread steps, one step long while a thread is slow.
  shared.threadUse().quickestRetry = 0.02;
  shared.threadUse().longestRetry = 0.02;
  shared.threadUse().abandon = 2.5;
  std::vector<int> used;
  for (int k = 0; k < steps; ++k) {
    machine.slowThread = k >= 40 && k < 100;
    used.push_back(shared.step(rk4, dt).threads);
    Eigen::VectorXd state(2 * shared.positions().size());
    state << shared.positions(), shared.velocities();
    for (Eigen::Index e = 0; e < state.size(); ++e)
      ASSERT_EQ(state[e], states[static_cast<std::size_t>(k)][e]) << "step " << k << " entry " << e;
  }
  particles::setThreadCount(1);
  auto range = [&](int from, int to, int threads) {
    int n = 0;
    for (int k = from; k < to; ++k) n += used[static_cast<std::size_t>(k)] == threads;
    return n;
  };
  // Probes every 0.02 s of simulated time (36 steps on two threads): at most one in 30 steps.
  const int probeSteps = shared.threadUse().probeSteps;
  EXPECT_GE(range(10, 40, 2), 30 - probeSteps) << "quiet: two threads but for a probe of one";
  EXPECT_GE(range(50, 100, 1), 40) << "a slow thread: one thread but for probes";
  EXPECT_GE(range(130, 160, 2), 30 - probeSteps) << "quiet again: two threads but for a probe of one";
}
