#pragma once
// Springs as structure of arrays, evaluated in strided runs (forces/spring.h
// gives the force law, f_i = −[k_s(|l| − r) + k_d l̇·u] u = −f_j).
//
// Runs: springs (a, a + d), (a + 1, a + 1 + d), …, (a + L − 1, a + L − 1 + d)
// with one stride d read their particles from two contiguous stretches of x
// and v, so a run's forces F_t are one vectorisable loop into a scratch
// array, and its additions two more, f[a + t] += F_t and f[a + d + t] −= F_t
// (within each of the two no particle appears twice: no scatter conflict).
// build() finds the runs in any order of the springs (strided_runs.h: sorted
// by stride and first particle, cut into runs of at most kRunLength, the
// runs ordered by first particle and stride, so that the runs of one region
// of a grid are evaluated together). Springs outside runs of kMinRun or more
// keep their order and are evaluated one by one after the runs (the gather
// loop).
//
// Order of the additions: particle p receives its terms run by run (within a
// run in the springs' order: for d > 0 the − of spring t − d before the + of
// spring t), then from the other springs in order. The order differs
// from the plain loop over the force objects, so f differs from it by
// rounding (|Δf_p| ≤ (m_p − 1) ε Σ |terms of p|, m_p terms); it does not
// depend on the thread count: with several threads, each thread evaluates the
// springs that touch its own range of particles (a spring joining two ranges
// is evaluated by both, to the same bits) and adds their terms of its
// particles in the same order, so f is the same bits for any count.
#include <vector>

#include <Eigen/Core>

#include "particle_range.h"
#include "particles/phase.h"
#include "thread_balance.h"

namespace particles {

// Below kParallelSprings springs a batch runs serially whatever the thread count.
constexpr int kParallelSprings = 4096;

class SpringBatch {
 public:
  // The longest run (its forces are kept in a 2 × kRunLength scratch) and the
  // shortest one worth a vector loop.
  static constexpr int kRunLength = 256, kMinRun = 4;

  void add(int i, int j, double rest, double stiffness, double damping);
  // Groups the springs added so far into runs; call after the last add().
  void build();

  int size() const { return static_cast<int>(first_.size()); }
  int runs() const { return static_cast<int>(runs_.size()); }
  int springsInRuns() const { return gatherBegin_; }

  // f += the springs' forces at s; with clear, f = them (f sized here). Then
  // finish(begin, end) over ranges of particles covering every particle.
  // On threadCount() threads when there are several and size() ≥ kParallelSprings.
  void apply(const Phase& s, Eigen::VectorXd& f, bool clear = false, const ParticleRange& finish = {}) const;
  // f = the springs' forces at phases[k] and finish(k, begin, end) over
  // ranges covering every particle, for k = 0, 1, … in turn: a particle's
  // phase k + 1 is read only after finish(k, ·) has run on every range its
  // springs reach, so phases[k + 1] may be what finish(k, ·) writes (and
  // finish(k, ·) may write what evaluation k − 1 read); finish reads and
  // writes its own range only. With several threads the whole sequence runs
  // in one parallel region, each thread keeping its range from one
  // evaluation to the next and waiting only for its neighbours' edges of the
  // evaluation before (see evaluate()).
  void applySequence(const std::vector<Phase>& phases, Eigen::VectorXd& f, const StageRange& finish) const;

 private:
  // Springs begin … begin + length − 1 join first + t and first + t + stride.
  // uniform: every spring of the run has the parameters of its first.
  struct Run {
    int begin, first, stride, length;
    bool uniform;
  };
  // apply() and applySequence(): f cleared at each phase when clear is set
  // (with more than one phase it is).
  void evaluate(const std::vector<Phase>& phases, Eigen::VectorXd& f, bool clear, const StageRange& finish) const;
  // The forces of run r's springs t0 … t1 − 1 on their first particles into out (2 each).
  void runForces(const Run& r, int t0, int t1, const double* x, const double* v, double* out) const;
  // f += the runs' terms of particles [begin, end).
  void addRunForces(int begin, int end, const double* x, const double* v, double* f) const;
  // f += the gathered springs' terms, spring by spring (one thread).
  void scatterGathered(const double* x, const double* v, double* f) const;
  // f += the gathered springs' terms of particles [begin, end), in order, from forces_.
  void gather(int begin, int end, double* f) const;
  // Gathered springs of each particle, ascending (k for a first end, ~k for a
  // second), rebuilt when the particle count changes.
  void buildIncidence(int particles) const;

  std::vector<int> first_, second_;  // in evaluation order: runs, then gathered springs
  std::vector<double> rest_, stiffness_, damping_;
  std::vector<Run> runs_;
  // A run r touches particles only in [r.first − spanBefore_, r.first + spanAfter_).
  int spanAfter_ = 0, spanBefore_ = 0;
  int reach_ = 0;  // the largest |j − i| of a spring (i, j)
  int gatherBegin_ = 0;  // springs [gatherBegin_, size()) are evaluated one by one
  mutable std::vector<int> incidenceStart_, incidence_;
  mutable std::vector<double> forces_;  // 2 per spring: the gathered springs' forces (threads)
  mutable int incidenceParticles_ = -1;
  mutable ThreadBalance balance_;  // the split of the particles among the threads
};

}  // namespace particles
