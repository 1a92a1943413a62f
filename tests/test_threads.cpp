// How the engine's threads wait and how many there are: a wait that lasts
// longer than its short spin sleeps in the kernel (the waiting thread's CPU
// time stays far below the time it waits) at a stage count, at the team's
// barrier and at the end of a region, where libgomp's own join would spin
// (300000 pauses by default: 3 ms on bare metal, longer in a VM); the
// barrier orders every thread's writes before the others' reads; the idle
// OpenMP threads are released on request; the thread count of a scope. No
// timing is asserted: only that a thread waiting 20 × 5 ms used a small
// part of that in CPU time.
#include <gtest/gtest.h>

#include <sched.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <thread>
#include <vector>

#include "parallel_for.h"
#include "particles/threads.h"
#include "stage_progress.h"
#include "team_barrier.h"
#include "wait_word.h"

namespace {

// Each wait: the other thread is held back this long, this many times.
constexpr auto kHeldBack = std::chrono::milliseconds(5);
constexpr int kWaits = 20;

double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double wallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// One thread's waits: the wall time they took and the CPU time the thread used meanwhile.
struct Waited {
  double wall = 0.0, cpu = 0.0;
  template <class Wait>
  void add(const Wait& wait) {
    const double w = wallSeconds(), c = threadCpuSeconds();
    wait();
    wall += wallSeconds() - w;
    cpu += threadCpuSeconds() - c;
  }
};

// The measured waits with the smallest share of CPU time of up to three
// tries: a machine shared with other programs can deschedule the thread
// waited for (or a thread of the runtime's) for milliseconds at any moment,
// which one try can catch; a spinning wait spends all of every try.
// A sleeping wait uses under this share of its wall time in CPU time.
constexpr double kSleepingShare = 0.25;

bool sleptThrough(const Waited& w) { return w.cpu < kSleepingShare * w.wall; }

template <class Measure>
Waited leastBusyOf(const Measure& measure) {
  Waited best = measure();
  for (int attempt = 1; attempt < 3 && !sleptThrough(best); ++attempt) {
    const Waited again = measure();
    if (again.cpu * best.wall < best.cpu * again.wall) best = again;
  }
  return best;
}

// The waits lasted about as long as the other thread was held back, and
// the waiting thread used under a quarter of that in CPU time (a spinning
// wait uses all of it on a quiet machine; a sleeping one its short spin).
void expectSlept(const Waited& w, const char* what) {
  EXPECT_GE(w.wall, 0.5 * kWaits * std::chrono::duration<double>(kHeldBack).count()) << what << ": it did wait";
  EXPECT_LT(w.cpu, kSleepingShare * w.wall) << what << ": the waiting thread used " << w.cpu << " s of CPU in " << w.wall
                                  << " s of waiting";
}

int threadsOfThisProcess() {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) n += entry.is_directory();
  return n;
}

}  // namespace

TEST(WaitWord, AWaitThatOutlastsItsSpinSleepsAndWakesAtTheStore) {
  particles::WaitWord word;
  Waited waited;
  bool sawEach = true;
  std::thread waiter([&] {
    for (std::uint32_t k = 1; k <= kWaits; ++k) {
      waited.add([&] { word.waitUntilReached(2 * k); });
      sawEach = sawEach && particles::WaitWord::reached(word.load(), 2 * k);
    }
  });
  for (std::uint32_t k = 1; k <= kWaits; ++k) {
    std::this_thread::sleep_for(kHeldBack / 2);
    word.store(2 * k - 1);  // not yet reached: the waiter sleeps on
    std::this_thread::sleep_for(kHeldBack / 2);
    word.store(2 * k);
  }
  waiter.join();
  EXPECT_TRUE(sawEach);
  expectSlept(waited, "WaitWord");
}

// Values wrap: a count past 2³² − 1 has still reached the targets below it.
TEST(WaitWord, ReachedCountsAcrossTheWrap) {
  EXPECT_TRUE(particles::WaitWord::reached(5, 5));
  EXPECT_FALSE(particles::WaitWord::reached(4, 5));
  EXPECT_TRUE(particles::WaitWord::reached(2, 0xfffffffeu));
  EXPECT_FALSE(particles::WaitWord::reached(0xfffffffeu, 2));
}

// In a region of two threads, thread 1 waits for thread 0's stage, then at
// the team's barrier, while thread 0 is held back before each.
TEST(ParallelTeam, AThreadWaitingForAStageOrAtTheBarrierSleeps) {
  particles::StageProgress progress(2);
  Waited atStage, atBarrier;
  int team = 0;
  particles::parallelTeam(2, [&](const particles::Team& t) {
    if (t.member == 0) team = t.size;
    if (t.size != 2) return;
    for (int k = 1; k <= kWaits; ++k) {
      if (t.member == 0) {
        std::this_thread::sleep_for(kHeldBack);
        progress.publish(0, k);
        std::this_thread::sleep_for(kHeldBack);
        t.wait();
      } else {
        atStage.add([&] { progress.waitFor(0, k); });
        atBarrier.add([&] { t.wait(); });
      }
    }
  });
  ASSERT_EQ(team, 2) << "the runtime gave a team of 2";
  expectSlept(atStage, "stage count");
  expectSlept(atBarrier, "team barrier");
}

// At the end of a region the master (the test's thread, thread 0) waits for
// thread 1, held back: it sleeps where libgomp's join would spin.
TEST(ParallelTeam, TheMasterWaitingAtTheRegionsEndSleeps) {
  expectSlept(leastBusyOf([] {
                Waited atEnd;
                for (int k = 0; k < kWaits; ++k) {
                  double wall = 0.0, cpu = 0.0;
                  particles::parallelTeam(2, [&](const particles::Team& t) {
                    if (t.member == 1) std::this_thread::sleep_for(kHeldBack);
                    if (t.member == 0) {
                      wall = wallSeconds();
                      cpu = threadCpuSeconds();
                    }
                  });
                  atEnd.wall += wallSeconds() - wall;
                  atEnd.cpu += threadCpuSeconds() - cpu;
                }
                return atEnd;
              }),
              "region end");
}

// Every thread's writes before a barrier are seen by every thread after it,
// round after round, on teams larger than the machine's cores too.
TEST(TeamBarrier, EachRoundSeesEveryThreadsWritesOfTheRoundBefore) {
  for (const int threads : {2, 3, 5}) {
    SCOPED_TRACE(testing::Message() << threads << " threads");
    const int rounds = 200;
    std::vector<int> written(static_cast<std::size_t>(threads), -1);
    std::atomic<int> wrong{0};
    particles::parallelTeam(threads, [&](const particles::Team& team) {
      for (int r = 0; r < rounds; ++r) {
        written[static_cast<std::size_t>(team.member)] = r;
        team.wait();
        for (int t = 0; t < team.size; ++t)
          if (written[static_cast<std::size_t>(t)] != r) ++wrong;
        team.wait();
      }
    });
    EXPECT_EQ(wrong.load(), 0);
  }
}

// A step on one thread after steps on more releases libgomp's idle threads:
// the process is back to its one thread.
TEST(Threads, ReleasingTheIdleThreadsEndsThem) {
  ASSERT_EQ(threadsOfThisProcess(), 1) << "the test process starts with one thread";
  std::atomic<int> ran{0};
  particles::parallelRanges(100000, 2, 1, [&](int, int) { ++ran; });
  ASSERT_EQ(ran.load(), 2);
  EXPECT_EQ(threadsOfThisProcess(), 2) << "the region's thread waits for the next region";
  particles::releaseIdleThreads();
  // An ended thread leaves /proc/self/task as it exits, shortly after the call returns.
  for (int k = 0; k < 1000 && threadsOfThisProcess() > 1; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_EQ(threadsOfThisProcess(), 1);
  ran = 0;
  particles::parallelRanges(100000, 2, 1, [&](int, int) { ++ran; });
  EXPECT_EQ(ran.load(), 2) << "a region after the release starts its thread again";
}

// Between regions libgomp's idle threads spin only briefly, then sleep
// (src/startup/openmp_short_spin.cpp): while the stepping thread is away
// for 20 × 5 ms after a region each time, the process uses under a quarter
// of that in CPU time (by default an idle thread would spin through each
// 5 ms: 300000 pauses, 7 ms on a 2-core EPYC VM, 3 ms or more on bare metal).
TEST(Threads, AnIdleThreadBetweenRegionsSleeps) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT"))
    GTEST_SKIP() << "the environment sets how OpenMP's threads wait";
  const Waited w = leastBusyOf([] {
    Waited waited;
    for (int k = 0; k < kWaits; ++k) {
      particles::parallelRanges(100000, 2, 1, [](int, int) {});
      const double wall = wallSeconds(), cpu = processCpuSeconds();
      std::this_thread::sleep_for(kHeldBack);
      waited.wall += wallSeconds() - wall;
      waited.cpu += processCpuSeconds() - cpu;
    }
    return waited;
  });
  expectSlept(w, "between regions (the process's CPU time)");
}

// The executable's start narrows its affinity while libgomp counts the CPUs
// and restores it: the program runs with the CPUs it was given (its parent's).
TEST(Threads, TheProgramKeepsTheCpusItWasGiven) {
  cpu_set_t mine, parents;
  ASSERT_EQ(sched_getaffinity(0, sizeof mine, &mine), 0);
  ASSERT_EQ(sched_getaffinity(getppid(), sizeof parents, &parents), 0);
  EXPECT_TRUE(CPU_EQUAL(&mine, &parents)) << CPU_COUNT(&mine) << " CPUs, the parent has " << CPU_COUNT(&parents);
  EXPECT_EQ(particles::affinityCpuCount(), CPU_COUNT(&parents));
}

// threadCount() is the innermost scope's count on the thread that opened it,
// the setting elsewhere and once the scopes end.
TEST(Threads, AScopesCountHoldsOnItsThreadUntilItEnds) {
  particles::setThreadCount(4);
  {
    const particles::ThreadCountScope outer(2);
    EXPECT_EQ(particles::threadCount(), 2);
    {
      const particles::ThreadCountScope inner(1);
      EXPECT_EQ(particles::threadCount(), 1);
      int elsewhere = 0;
      std::thread([&] { elsewhere = particles::threadCount(); }).join();
      EXPECT_EQ(elsewhere, 4);
    }
    EXPECT_EQ(particles::threadCount(), 2);
  }
  EXPECT_EQ(particles::threadCount(), 4);
  EXPECT_THROW(particles::ThreadCountScope(0), std::invalid_argument);
  particles::setThreadCount(1);
}
