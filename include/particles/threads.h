#pragma once
// How many threads the engine's parallel loops use (OpenMP). The results are
// the same bits for any count: every parallel loop writes disjoint entries,
// and sums keep the serial order (see forces/force_batch.h). With 1 (the
// library's default) no parallel region is entered and no thread is started.
//
// setThreadCount() sets the most threads; each ParticleSystem::step then runs
// on that many while they make its steps faster, else on one
// (particles/thread_use.h), and threadCount() gives the parallel loops that
// step's count.
namespace particles {

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
