#pragma once
// How many threads the engine's parallel loops use (OpenMP). The results are
// the same bits for any count: every parallel loop writes disjoint entries,
// and sums keep the serial order (see src/forces/force_batch.h). With 1 (the
// library's default) no parallel region is entered and no thread is started.
//
// setThreadCount() sets the most threads; each ParticleSystem::step then runs
// on that many while they make its steps faster, else on one (the
// ThreadUseSettings below, ParticleSystem::threadUse()), and threadCount()
// gives the parallel loops that step's count.
//
// How a step chooses: the steps on the present count are timed (the mean of
// the last `history`). Now and then a probe runs `probeSteps` steps on the
// other count, and the faster count is kept: more threads while the mean of
// their steps is at most `gain` times one thread's (the whole rule, with its
// waits and hand-offs, in src/thread_use.h).
namespace particles {

struct ThreadUseSettings {
  bool adaptive = true;         // false: every step on the most threads
  double gain = 0.9;            // more threads are kept while they take at most gain × one thread's time
  int history = 5;              // steps whose mean is the present count's time
  int probeSteps = 3;           // steps on the other count in a probe
  double abandon = 4.0;         // a probe step over abandon × the present median ends the probe
  double handoff = 0.5;         // a probe's first hand-off over handoff × one thread's step ends it
  double probeShare = 0.01;     // probes that lose cost at most this share of the time
  double quickestRetry = 0.05;  // s: the shortest wait before probing the other count again
  double longestRetry = 5.0;    // s: the longest

  void validate() const;  // throws naming the bad field
};

// Sets the most threads; std::invalid_argument unless count >= 1.
void setThreadCount(int count);
// The threads the parallel loops use: inside a ThreadCountScope on this
// thread, the scope's count; otherwise the count setThreadCount() set.
int threadCount();

// threadCount() on the constructing thread is `count` until the scope ends
// (scopes nest; the innermost wins). ParticleSystem::step opens one for
// the count its ThreadUse chose.
class ThreadCountScope {
 public:
  explicit ThreadCountScope(int count);
  ~ThreadCountScope();
  ThreadCountScope(const ThreadCountScope&) = delete;
  ThreadCountScope& operator=(const ThreadCountScope&) = delete;

 private:
  int previous_;
};

// The parallel regions entered from this thread so far (parallel_for.h's
// parallelTeam counts each): a step that entered none had no work its
// threads could share.
long long parallelRegions();
void countParallelRegion();

// Ends the OpenMP threads that this thread's parallel regions started and
// that now wait for its next region. Idle OpenMP threads spin briefly before
// they sleep (src/startup/openmp_short_spin.cpp), or as long as the
// environment's OMP_WAIT_POLICY or GOMP_SPINCOUNT says; a thread that steps
// on one thread for a while releases them, so that none waits on a core a
// busy program or this thread could use (the next region starts them again,
// for some tens of microseconds). Does nothing inside a region.
void releaseIdleThreads();

// CPUs in this process's affinity mask (sched_getaffinity; taskset, Slurm's
// --cpus-per-task), at least 1: the programs' default for --threads and --jobs.
int affinityCpuCount();

}  // namespace particles
