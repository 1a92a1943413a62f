#pragma once
// How many threads the engine's parallel loops use (OpenMP). The results are
// the same bits for any count: every parallel loop writes disjoint entries,
// and sums keep the serial order (see forces/force_batch.h). With 1 (the
// library's default) no parallel region is entered and no thread is started.
namespace particles {

// Sets the thread count; std::invalid_argument unless count >= 1.
void setThreadCount(int count);
int threadCount();
// CPUs in this process's affinity mask (sched_getaffinity; taskset, Slurm's
// --cpus-per-task), at least 1: the programs' default for --threads and --jobs.
int affinityCpuCount();

}  // namespace particles
