#include "forces/spring_batch.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "parallel_for.h"
#include "particles/threads.h"
#include "stage_progress.h"
#include "strided_runs.h"
#include "vector_kernels.h"

namespace particles {

namespace {

// springForce() written out on scalars, operation for operation (|l| as
// sqrt(lx² + ly²), u = l (1/|l|), s = k_s(|l| − r) + k_d l̇·u, f_i = −s u),
// so that the batch and the force object give each spring's force as the
// same bits. A spring of length 0 has no direction and no force: it divides
// by 1 instead and its s is multiplied by 0 (a branch would keep the loops
// from being vectorised; for any other spring the factor is 1 and the
// divisor |l| + 0, both exact).
[[gnu::always_inline]] inline void springTerm(double lx, double ly, double ldx, double ldy, double rest,
                                              double stiffness, double damping, double& fx, double& fy) {
  const double length = std::sqrt(lx * lx + ly * ly);
  const double none = length == 0.0 ? 1.0 : 0.0;
  const double inverse = 1.0 / (length + none);
  const double ux = lx * inverse, uy = ly * inverse;
  const double m = -(stiffness * (length - rest) + damping * (ldx * ux + ldy * uy)) * (1.0 - none);
  fx = m * ux;
  fy = m * uy;
}

// Springs t < count join the particles at xi + 2t and xj + 2t (and vi, vj);
// the force on the first goes to out[2t], out[2t + 1]. Parameters per spring.
PARTICLES_VECTOR_CLONES
void springForces(int count, const double* xi, const double* xj, const double* vi, const double* vj,
                  const double* rest, const double* stiffness, const double* damping, double* out) {
#pragma omp simd
  for (int t = 0; t < count; ++t)
    springTerm(xi[2 * t] - xj[2 * t], xi[2 * t + 1] - xj[2 * t + 1], vi[2 * t] - vj[2 * t],
               vi[2 * t + 1] - vj[2 * t + 1], rest[t], stiffness[t], damping[t], out[2 * t], out[2 * t + 1]);
}

// The same with one set of parameters for every spring (24 bytes a spring
// fewer to read).
PARTICLES_VECTOR_CLONES
void uniformSpringForces(int count, const double* xi, const double* xj, const double* vi, const double* vj,
                         double rest, double stiffness, double damping, double* out) {
#pragma omp simd
  for (int t = 0; t < count; ++t)
    springTerm(xi[2 * t] - xj[2 * t], xi[2 * t + 1] - xj[2 * t + 1], vi[2 * t] - vj[2 * t],
               vi[2 * t + 1] - vj[2 * t + 1], rest, stiffness, damping, out[2 * t], out[2 * t + 1]);
}

// The springs t ∈ [c0, c1) of a run of `length` whose particles first + t
// (to = first) or first + stride + t (to = first + stride) lie in [begin, end);
// false when there are none.
bool clipRun(int to, int length, int begin, int end, int& c0, int& c1) {
  c0 = std::max(0, begin - to);
  c1 = std::min(length, end - to);
  return c0 < c1;
}

// The terms of a run's springs on the particles of [begin, end) only: + at
// first + t, − at first + stride + t, spring t's force at terms[2(t − t0)],
// terms[2(t − t0) + 1] (t0: the first spring evaluated into terms, whose
// range holds every spring that touches [begin, end)). Each particle gets its
// two terms in the springs' order, as the plain scatter loop gives them: for
// stride > 0 the − of spring t − stride before the + of spring t.
void addRunTerms(int first, int stride, int length, const double* terms, int t0, int begin, int end, double* f) {
  auto clip = [&](int to, int& c0, int& c1) { return clipRun(to, length, begin, end, c0, c1); };
  int c0, c1;
  const int second = first + stride;
  if (stride > 0 && clip(second, c0, c1)) subtractTerms(2 * (c1 - c0), terms + 2 * (c0 - t0), f + 2 * (second + c0));
  if (clip(first, c0, c1)) addTerms(2 * (c1 - c0), terms + 2 * (c0 - t0), f + 2 * (first + c0));
  if (stride < 0 && clip(second, c0, c1)) subtractTerms(2 * (c1 - c0), terms + 2 * (c0 - t0), f + 2 * (second + c0));
}

}  // namespace

void SpringBatch::add(int i, int j, double rest, double stiffness, double damping) {
  first_.push_back(i);
  second_.push_back(j);
  rest_.push_back(rest);
  stiffness_.push_back(stiffness);
  damping_.push_back(damping);
  runs_.clear();
  gatherBegin_ = 0;
  incidenceParticles_ = -1;
}

void SpringBatch::build() {
  const StridedRuns found = findStridedRuns(first_, second_, kRunLength, kMinRun);
  runs_.clear();
  for (const StridedRun& r : found.runs) runs_.push_back({r.begin, r.first, r.stride, r.length, true});
  gatherBegin_ = found.leftBegin;
  auto permute = [&](auto& values) {
    auto old = values;
    for (int k = 0; k < size(); ++k) values[k] = old[found.order[k]];
  };
  permute(first_);
  permute(second_);
  permute(rest_);
  permute(stiffness_);
  permute(damping_);
  for (Run& r : runs_)
    for (int k = r.begin + 1; k < r.begin + r.length; ++k)
      r.uniform = r.uniform && rest_[k] == rest_[r.begin] && stiffness_[k] == stiffness_[r.begin] &&
                  damping_[k] == damping_[r.begin];
  spanAfter_ = spanBefore_ = reach_ = 0;
  for (int k = 0; k < size(); ++k) reach_ = std::max(reach_, std::abs(second_[k] - first_[k]));
  for (const Run& r : runs_) {
    spanAfter_ = std::max(spanAfter_, r.length + std::max(0, r.stride));
    spanBefore_ = std::max(spanBefore_, std::max(0, -r.stride));
  }
  incidenceParticles_ = -1;
}

void SpringBatch::apply(const Phase& s, Eigen::VectorXd& f, bool clear, const ParticleRange& finish) const {
  evaluate({s}, f, clear, finish ? StageRange([&](int, int begin, int end) { finish(begin, end); }) : StageRange());
}

void SpringBatch::applySequence(const std::vector<Phase>& phases, Eigen::VectorXd& f,
                                const StageRange& finish) const {
  evaluate(phases, f, true, finish);
}

void SpringBatch::evaluate(const std::vector<Phase>& phases, Eigen::VectorXd& f, bool clear,
                           const StageRange& finish) const {
  const int stages = static_cast<int>(phases.size());
  if (stages == 0) return;
  const int n = phases[0].size(), threads = threadCount();
  if (clear) f.resize(2 * n);
  double* out = f.data();
  if (threads <= 1 || size() < kParallelSprings) {
    for (int k = 0; k < stages; ++k) {
      if (clear) f.setZero();
      addRunForces(0, n, phases[k].x.data(), phases[k].v.data(), out);
      scatterGathered(phases[k].x.data(), phases[k].v.data(), out);
      if (finish) finish(k, 0, n);
    }
    return;
  }
  // Each thread adds the terms of its own range of particles, so no two
  // write one entry of f, and finishes the range as soon as its terms are
  // in: the range's f, a and integrator vectors stay in that thread's cache
  // from one pass to the next (a range finished by another thread would move
  // them between cores, which cost more than the other thread's wait saved).
  // The ranges stay the same through the sequence.
  const bool gathered = gatherBegin_ < size();
  if (gathered) {
    buildIncidence(n);
    forces_.resize(2 * static_cast<std::size_t>(size()));
  }
  double* fs = forces_.data();
  const int springs = size();
  const std::vector<int> bounds = balance_.bounds(n, threads);
  ThreadBalance::Pass measured(threads);
  // Evaluation k on particles [begin, end): their f, then finish.
  auto piece = [&](int k, int begin, int end) {
    if (begin >= end) return 0.0;
    if (clear) std::fill(out + 2 * begin, out + 2 * end, 0.0);
    addRunForces(begin, end, phases[k].x.data(), phases[k].v.data(), out);
    if (gathered) gather(begin, end, out);
    if (finish) finish(k, begin, end);
    return static_cast<double>(end - begin);
  };
  // Pipelined: a range's particles within reach_ of a neighbouring range
  // (its edges) are the only ones another thread reads, and the only ones
  // whose evaluation reads another range. Each thread does its edges first
  // and publishes them, then its interior; evaluation k of the edges waits
  // for the neighbours' edges of evaluation k − 1 only (which also ends their
  // reading of the buffer k − 1 read, should evaluation k write it), so a
  // thread a little late on one evaluation delays no one. It needs every
  // range at least reach_ long (a spring then never skips a range) and no
  // gathered springs (their forces are computed for all before any range);
  // otherwise a barrier separates the evaluations.
  bool pipelined = !gathered && stages > 1 && reach_ > 0;
  for (int t = 0; t < threads; ++t) pipelined = pipelined && bounds[t + 1] - bounds[t] >= reach_;
  StageProgress edges(pipelined ? threads : 0);
  auto interiorOf = [&](int part) {
    const int begin = bounds[part], end = bounds[part + 1];
    const int from = part > 0 ? begin + reach_ : begin;
    return std::pair<int, int>{from, std::max(from, part + 1 < threads ? end - reach_ : end)};
  };
  parallelTeam(threads, [&](const Team& team) {
    for (int k = 0; k < stages; ++k) {
      if (pipelined) {
        if (k > 0)
          measured.each([&](int part) {
            if (part > 0) edges.waitFor(part - 1, k);
            if (part + 1 < threads) edges.waitFor(part + 1, k);
          });
        measured.run([&](int part) {
          const auto [from, to] = interiorOf(part);
          const double done = piece(k, bounds[part], from) + piece(k, to, bounds[part + 1]);
          edges.publish(part, k + 1);
          return done;
        });
        measured.run([&](int part) {
          const auto [from, to] = interiorOf(part);
          return piece(k, from, to);
        });
        continue;
      }
      if (k > 0) team.wait();
      if (gathered) {  // the gathered springs' forces, shared out among the threads, then a barrier
        const double* x = phases[k].x.data();
        const double* v = phases[k].v.data();
        const int count = springs - gatherBegin_;
        for (int g = gatherBegin_ + team.rangeBegin(count), end = gatherBegin_ + team.rangeEnd(count); g < end; ++g) {
          const int i = 2 * first_[g], j = 2 * second_[g];
          springForces(1, x + i, x + j, v + i, v + j, &rest_[g], &stiffness_[g], &damping_[g], fs + 2 * g);
        }
        team.wait();
      }
      measured.run([&](int part) { return piece(k, bounds[part], bounds[part + 1]); });
    }
  });
  balance_.update(measured);
}

void SpringBatch::runForces(const Run& r, int t0, int t1, const double* x, const double* v, double* out) const {
  const int i = 2 * (r.first + t0), j = 2 * (r.first + r.stride + t0), k = r.begin + t0;
  if (r.uniform)
    uniformSpringForces(t1 - t0, x + i, x + j, v + i, v + j, rest_[k], stiffness_[k], damping_[k], out);
  else
    springForces(t1 - t0, x + i, x + j, v + i, v + j, &rest_[k], &stiffness_[k], &damping_[k], out);
}

// A run's springs that touch [begin, end) are evaluated into a scratch and
// their terms of [begin, end) added: a spring across the edge of two
// threads' ranges is evaluated by both, to the same bits.
void SpringBatch::addRunForces(int begin, int end, const double* x, const double* v, double* f) const {
  alignas(64) double forces[2 * kRunLength];
  // Runs are sorted by first particle: those that can touch [begin, end) have
  // first in (begin − spanAfter_, end + spanBefore_).
  auto from = std::partition_point(runs_.begin(), runs_.end(),
                                   [&](const Run& r) { return r.first <= begin - spanAfter_; });
  for (auto it = from; it != runs_.end() && it->first < end + spanBefore_; ++it) {
    const Run& r = *it;
    int t0 = r.length, t1 = 0;
    for (const int to : {r.first, r.first + r.stride}) {
      int c0, c1;
      if (clipRun(to, r.length, begin, end, c0, c1)) {
        t0 = std::min(t0, c0);
        t1 = std::max(t1, c1);
      }
    }
    if (t0 >= t1) continue;
    runForces(r, t0, t1, x, v, forces);
    addRunTerms(r.first, r.stride, r.length, forces, t0, begin, end, f);
  }
}

void SpringBatch::scatterGathered(const double* x, const double* v, double* f) const {
  for (int k = gatherBegin_; k < size(); ++k) {
    const int i = 2 * first_[k], j = 2 * second_[k];
    double force[2];
    springForces(1, x + i, x + j, v + i, v + j, &rest_[k], &stiffness_[k], &damping_[k], force);
    f[i] += force[0];
    f[i + 1] += force[1];
    f[j] -= force[0];
    f[j + 1] -= force[1];
  }
}

void SpringBatch::buildIncidence(int particles) const {
  if (particles == incidenceParticles_) return;
  incidenceStart_.assign(particles + 1, 0);
  for (int k = gatherBegin_; k < size(); ++k) {
    ++incidenceStart_[first_[k] + 1];
    ++incidenceStart_[second_[k] + 1];
  }
  for (int p = 0; p < particles; ++p) incidenceStart_[p + 1] += incidenceStart_[p];
  incidence_.resize(incidenceStart_[particles]);
  std::vector<int> fill(incidenceStart_.begin(), incidenceStart_.end() - 1);
  for (int k = gatherBegin_; k < size(); ++k) {  // ascending k, + before − (the serial scatter's order)
    incidence_[fill[first_[k]]++] = k;
    incidence_[fill[second_[k]]++] = ~k;
  }
  incidenceParticles_ = particles;
}

void SpringBatch::gather(int begin, int end, double* f) const {
  const int* start = incidenceStart_.data();
  const int* list = incidence_.data();
  const double* fs = forces_.data();
  for (int p = begin; p < end; ++p) {
    double fx = f[2 * p], fy = f[2 * p + 1];
    for (int e = start[p]; e < start[p + 1]; ++e) {
      const int k = list[e];
      if (k >= 0) {
        fx += fs[2 * k];
        fy += fs[2 * k + 1];
      } else {
        fx -= fs[2 * ~k];
        fy -= fs[2 * ~k + 1];
      }
    }
    f[2 * p] = fx;
    f[2 * p + 1] = fy;
  }
}

}  // namespace particles
