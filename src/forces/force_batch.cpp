#include "forces/force_batch.h"

#include <algorithm>

#include "forces/force_kinds.h"
#include "parallel_for.h"
#include "particles/threads.h"
#include "vector_kernels.h"

namespace particles {

namespace {

// Particles per block of the per-particle passes: one block's f, a, x and v
// stay in the first-level cache between the passes of its field terms.
constexpr int kParticleBlock = 512;

// f_i += term on movable particles i in [begin, end), f from the range's
// first entry (as GravityForce::apply and DragForce::apply). The term is multiplied by 1 on a movable particle
// (exact) and by 0 on a pinned one, whose f_i + 0 equals f_i: a branch would
// keep the loops from being vectorised.
PARTICLES_VECTOR_CLONES
void addField(const FieldTerm& t, int begin, int end, const Phase& s, double* f) {
  const int count = end - begin;
  const double* w = s.inverseMass.data() + begin;
  if (t.kind == FieldTerm::Kind::Gravity) {
    const double* m = s.mass.data() + begin;
    const double gx = t.gravity.x(), gy = t.gravity.y();
#pragma omp simd
    for (int u = 0; u < count; ++u) {
      const double movable = w[u] > 0.0 ? 1.0 : 0.0;
      f[2 * u] += movable * (m[u] * gx);
      f[2 * u + 1] += movable * (m[u] * gy);
    }
  } else {
    const double* v = s.v.data() + 2 * static_cast<std::ptrdiff_t>(begin);
    const double k = t.drag;
#pragma omp simd
    for (int u = 0; u < count; ++u) {
      const double movable = w[u] > 0.0 ? 1.0 : 0.0;
      f[2 * u] -= movable * (k * v[2 * u]);
      f[2 * u + 1] -= movable * (k * v[2 * u + 1]);
    }
  }
}

// a_i = w_i f_i for particles i in [begin, end) (f and a from the range's first entry).
PARTICLES_VECTOR_CLONES
void divideByMass(int begin, int end, const double* w, const double* f, double* a) {
  const int count = end - begin;
  w += begin;
#pragma omp simd
  for (int u = 0; u < count; ++u) {
    a[2 * u] = w[u] * f[2 * u];
    a[2 * u + 1] = w[u] * f[2 * u + 1];
  }
}

}  // namespace

void ForceBatches::update(const std::vector<std::unique_ptr<Force>>& forces, std::uint64_t stamp) {
  if (built_ && stamp == stamp_) return;
  std::vector<const Force*> list;
  for (const auto& force : forces) list.push_back(force.get());
  update(list, stamp);
}

void ForceBatches::update(const std::vector<const Force*>& forces, std::uint64_t stamp) {
  if (built_ && stamp == stamp_) return;
  segments_.clear();
  tail_.clear();
  springs_.clear();
  SpringBatch open;  // springs since the last other force
  auto closeSprings = [&]() {
    if (open.size() == 0) return;
    open.build();
    segments_.push_back({Segment::Kind::Springs, static_cast<int>(springs_.size()), {}, nullptr});
    springs_.push_back(std::move(open));
    open = SpringBatch();
  };
  for (const auto& force : forces) {
    FieldTerm field{FieldTerm::Kind::Gravity, Eigen::Vector2d::Zero(), 0.0};
    const ForceKind* kind = forceKind(*force);
    const Batched batched = kind && kind->batch ? kind->batch(*force, open, field) : Batched::No;
    if (batched == Batched::Springs) continue;  // consecutive springs share one segment
    closeSprings();
    if (batched == Batched::No)
      segments_.push_back({Segment::Kind::Virtual, 0, field, force});
    else
      segments_.push_back({Segment::Kind::Field, 0, field, nullptr});
  }
  closeSprings();
  headSegments_ = static_cast<int>(segments_.size());
  while (headSegments_ > 0 && segments_[headSegments_ - 1].kind == Segment::Kind::Field) --headSegments_;
  for (int k = headSegments_; k < static_cast<int>(segments_.size()); ++k) tail_.push_back(segments_[k].field);
  stamp_ = stamp;
  built_ = true;
}

int ForceBatches::springCount() const {
  int count = 0;
  for (const SpringBatch& b : springs_) count += b.size();
  return count;
}

void ForceBatches::applySegments(int begin, int end, const Phase& s, Eigen::VectorXd& f,
                                 const ParticleRange& finish) const {
  const int n = s.size(), threads = threadCount();
  if (begin == end || segments_[begin].kind != Segment::Kind::Springs) f.setZero(2 * n);
  bool finished = false;
  for (int k = begin; k < end; ++k) {
    const Segment& seg = segments_[k];
    switch (seg.kind) {
      case Segment::Kind::Springs:
        finished = k == end - 1;
        springs_[seg.springs].apply(s, f, k == 0, finished ? finish : ParticleRange{});
        break;
      case Segment::Kind::Field: {
        double* fd = f.data();
        parallelRanges(n, threads, kParallelParticles,
                       [&](int from, int to) { addField(seg.field, from, to, s, fd + 2 * from); });
        break;
      }
      case Segment::Kind::Virtual: seg.force->apply(s, f); break;
    }
  }
  if (finish && !finished) parallelRanges(n, threads, kParallelParticles, finish);
}

// The trailing fields are added in the last pass of the segments before
// them, range by range (one parallel region where there would be one per
// field), each particle's terms in the order of the force list.
void ForceBatches::apply(const Phase& s, Eigen::VectorXd& f) const {
  if (fieldsOnly()) {
    f.resize(2 * s.size());
    double* fd = f.data();
    parallelRanges(s.size(), threadCount(), kParallelParticles,
                   [&](int begin, int end) { addTail(begin, end, s, fd + 2 * begin, true); });
    return;
  }
  applySegments(0, headSegments_, s, f, [&](int begin, int end) { addTail(begin, end, s, f.data() + 2 * begin, false); });
}

void ForceBatches::addTail(int begin, int end, const Phase& s, double* f, bool clear) const {
  for (int b = begin; b < end; b += kParticleBlock) {
    const int e = std::min(end, b + kParticleBlock);
    double* fb = f + 2 * (b - begin);
    if (clear) std::fill(fb, fb + 2 * (e - b), 0.0);
    for (const FieldTerm& t : tail_) addField(t, b, e, s, fb);
  }
}

void ForceBatches::tailAndDivide(int begin, int end, const Phase& s, double* f, double* a, bool clear) const {
  const double* w = s.inverseMass.data();
  for (int b = begin; b < end; b += kParticleBlock) {
    const int e = std::min(end, b + kParticleBlock);
    addTail(b, e, s, f + 2 * (b - begin), clear);
    divideByMass(b, e, w, f + 2 * (b - begin), a + 2 * (b - begin));
  }
}

void ForceBatches::applyAndDivide(const Phase& s, Eigen::VectorXd& f, Eigen::VectorXd& a,
                                  const ParticleRange& then) const {
  a.resize(s.x.size());
  double* ad = a.data();
  if (fieldsOnly()) {
    // Fields alone: each range clears its own f as it goes, so no pass over
    // the whole of f runs on one thread (and pulls it into one core's cache).
    f.resize(s.x.size());
    double* fd = f.data();
    parallelRanges(s.size(), threadCount(), kParallelParticles, [&](int begin, int end) {
      applyAndDivide(begin, end, s, fd + 2 * begin, ad + 2 * begin);
      if (then) then(begin, end);
    });
    return;
  }
  applySegments(0, headSegments_, s, f, [&](int begin, int end) {
    tailAndDivide(begin, end, s, f.data() + 2 * begin, ad + 2 * begin, false);
    if (then) then(begin, end);
  });
}

void ForceBatches::applyAndDivide(const std::vector<Phase>& phases, Eigen::VectorXd& f, Eigen::VectorXd& a,
                                  const StageRange& then) const {
  if (headSegments_ == 1 && segments_[0].kind == Segment::Kind::Springs && !phases.empty()) {
    a.resize(phases[0].x.size());
    springs_[segments_[0].springs].applySequence(phases, f, [&](int k, int begin, int end) {
      tailAndDivide(begin, end, phases[k], f.data() + 2 * begin, a.data() + 2 * begin, false);
      if (then) then(k, begin, end);
    });
    return;
  }
  for (int k = 0; k < static_cast<int>(phases.size()); ++k)
    applyAndDivide(phases[k], f, a, stagePass(then, k));
}

}  // namespace particles
