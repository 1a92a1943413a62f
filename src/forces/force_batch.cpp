#include "particles/forces/force_batch.h"

#include <cmath>

#include "parallel_for.h"
#include "particles/forces/drag.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/threads.h"

namespace particles {

void SpringBatch::clear() {
  incidenceBegin_ = incidenceEnd_ = incidenceParticles_ = -1;
  first.clear();
  second.clear();
  rest.clear();
  stiffness.clear();
  damping.clear();
}

void SpringBatch::add(int i, int j, double r, double ks, double kd) {
  first.push_back(i);
  second.push_back(j);
  rest.push_back(r);
  stiffness.push_back(ks);
  damping.push_back(kd);
}

// springForce() written out on scalars, operation for operation (|l| as
// sqrt(lx² + ly²), u = l/|l| by division, s = k_s(|l| − r) + k_d l̇·u,
// f_i = −s u), so that the batch and the virtual call give the same bits.
inline bool SpringBatch::force(int k, const double* x, const double* v, double& fx, double& fy) const {
  const int i = 2 * first[k], j = 2 * second[k];
  const double lx = x[i] - x[j], ly = x[i + 1] - x[j + 1];
  const double length = std::sqrt(lx * lx + ly * ly);
  if (length == 0.0) {  // direction undefined: no force
    fx = fy = 0.0;
    return false;
  }
  const double ux = lx / length, uy = ly / length;
  const double ldotu = (v[i] - v[j]) * ux + (v[i + 1] - v[j + 1]) * uy;
  const double m = -(stiffness[k] * (length - rest[k]) + damping[k] * ldotu);
  fx = m * ux;
  fy = m * uy;
  return true;
}

void SpringBatch::apply(int begin, int end, const Phase& s, Eigen::VectorXd& f) const {
  const int threads = threadCount();
  if (threads > 1 && end - begin >= kParallelSprings) {
    applyParallel(begin, end, s, f, threads);
    return;
  }
  const double* x = s.x.data();
  const double* v = s.v.data();
  double* out = f.data();
  for (int k = begin; k < end; ++k) {
    const int i = 2 * first[k], j = 2 * second[k];
    double fx, fy;
    if (!force(k, x, v, fx, fy)) continue;
    out[i] += fx;
    out[i + 1] += fy;
    out[j] -= fx;
    out[j + 1] -= fy;
  }
}

void SpringBatch::buildIncidence(int begin, int end, int particles) const {
  if (begin == incidenceBegin_ && end == incidenceEnd_ && particles == incidenceParticles_) return;
  incidenceStart_.assign(particles + 1, 0);
  for (int k = begin; k < end; ++k) {
    ++incidenceStart_[first[k] + 1];
    ++incidenceStart_[second[k] + 1];
  }
  for (int p = 0; p < particles; ++p) incidenceStart_[p + 1] += incidenceStart_[p];
  incidence_.resize(incidenceStart_[particles]);
  std::vector<int> fill(incidenceStart_.begin(), incidenceStart_.end() - 1);
  for (int k = begin; k < end; ++k) {  // ascending k within each particle's list
    incidence_[fill[first[k]]++] = k;
    incidence_[fill[second[k]]++] = ~k;
  }
  forces_.resize(2 * static_cast<std::size_t>(first.size()));
  incidenceBegin_ = begin;
  incidenceEnd_ = end;
  incidenceParticles_ = particles;
}

void SpringBatch::applyParallel(int begin, int end, const Phase& s, Eigen::VectorXd& f, int threads) const {
  const int n = s.size();
  buildIncidence(begin, end, n);
  const double* x = s.x.data();
  const double* v = s.v.data();
  double* out = f.data();
  double* fs = forces_.data();
  const int* start = incidenceStart_.data();
  const int* list = incidence_.data();
#pragma omp parallel num_threads(threads)
  {
#pragma omp for schedule(static)
    for (int k = begin; k < end; ++k) force(k, x, v, fs[2 * k], fs[2 * k + 1]);
#pragma omp for schedule(static)
    for (int p = 0; p < n; ++p) {
      double fx = out[2 * p], fy = out[2 * p + 1];
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
      out[2 * p] = fx;
      out[2 * p + 1] = fy;
    }
  }
}

namespace {

// f_i += term on movable particle i (as GravityForce::apply / DragForce::apply).
inline void addField(const FieldTerm& t, int i, const Phase& s, double* f) {
  if (t.kind == FieldTerm::Kind::Gravity) {
    f[2 * i] += s.mass[i] * t.gravity.x();
    f[2 * i + 1] += s.mass[i] * t.gravity.y();
  } else {
    f[2 * i] -= t.drag * s.v[2 * i];
    f[2 * i + 1] -= t.drag * s.v[2 * i + 1];
  }
}

// The force types that have a batch: each entry takes a force it knows into
// the batches and returns true, or returns false for the next entry to try.
struct Batcher {
  bool (*take)(const Force&, SpringBatch&, FieldTerm&, bool& isField);
};

const Batcher kBatchers[] = {
    {[](const Force& force, SpringBatch& springs, FieldTerm&, bool& isField) {
       const auto* spring = dynamic_cast<const SpringForce*>(&force);
       if (!spring) return false;
       isField = false;
       if (spring->enabled())
         springs.add(spring->first(), spring->second(), spring->restLength(), spring->stiffness(),
                     spring->damping());
       return true;
     }},
    {[](const Force& force, SpringBatch&, FieldTerm& field, bool& isField) {
       const auto* gravity = dynamic_cast<const GravityForce*>(&force);
       if (!gravity) return false;
       isField = true;
       field = {FieldTerm::Kind::Gravity, gravity->acceleration(), 0.0};
       return true;
     }},
    {[](const Force& force, SpringBatch&, FieldTerm& field, bool& isField) {
       const auto* drag = dynamic_cast<const DragForce*>(&force);
       if (!drag) return false;
       isField = true;
       field = {FieldTerm::Kind::Drag, Eigen::Vector2d::Zero(), drag->damping()};
       return true;
     }},
};

}  // namespace

void ForceBatches::update(const std::vector<std::unique_ptr<Force>>& forces, std::uint64_t stamp) {
  if (built_ && stamp == stamp_) return;
  segments_.clear();
  tail_.clear();
  springs_.clear();
  for (const auto& force : forces) {
    FieldTerm field{FieldTerm::Kind::Gravity, Eigen::Vector2d::Zero(), 0.0};
    bool isField = false, taken = false;
    const int before = springs_.size();
    for (const Batcher& b : kBatchers)
      if ((taken = b.take(*force, springs_, field, isField))) break;
    if (!taken) {
      segments_.push_back({Segment::Kind::Virtual, 0, 0, field, force.get()});
    } else if (isField) {
      segments_.push_back({Segment::Kind::Field, 0, 0, field, nullptr});
    } else if (springs_.size() > before) {
      // Consecutive springs share one segment.
      if (!segments_.empty() && segments_.back().kind == Segment::Kind::Springs)
        segments_.back().end = springs_.size();
      else
        segments_.push_back({Segment::Kind::Springs, before, springs_.size(), field, nullptr});
    }
  }
  headSegments_ = static_cast<int>(segments_.size());
  while (headSegments_ > 0 && segments_[headSegments_ - 1].kind == Segment::Kind::Field) --headSegments_;
  for (int k = headSegments_; k < static_cast<int>(segments_.size()); ++k) tail_.push_back(segments_[k].field);
  stamp_ = stamp;
  built_ = true;
}

void ForceBatches::apply(const Phase& s, Eigen::VectorXd& f, bool fuseTail) const {
  f.setZero(s.x.size());
  const int n = s.size(), threads = threadCount();
  const int last = fuseTail ? headSegments_ : static_cast<int>(segments_.size());
  for (int k = 0; k < last; ++k) {
    const Segment& seg = segments_[k];
    switch (seg.kind) {
      case Segment::Kind::Springs: springs_.apply(seg.begin, seg.end, s, f); break;
      case Segment::Kind::Field: {
        double* fd = f.data();
        parallelFor(n, threads, kParallelParticles, [&](int i) {
          if (s.inverseMass[i] > 0.0) addField(seg.field, i, s, fd);
        });
        break;
      }
      case Segment::Kind::Virtual: seg.force->apply(s, f); break;
    }
  }
}

void ForceBatches::applyTailAndDivide(const Phase& s, Eigen::VectorXd& f, Eigen::VectorXd& a) const {
  const int n = s.size();
  a.resize(2 * n);
  double* fd = f.data();
  double* ad = a.data();
  const int threads = threadCount();
  parallelFor(n, threads, kParallelParticles, [&](int i) {
    const double w = s.inverseMass[i];
    if (w > 0.0)
      for (const FieldTerm& t : tail_) addField(t, i, s, fd);
    ad[2 * i] = w * fd[2 * i];
    ad[2 * i + 1] = w * fd[2 * i + 1];
  });
}

}  // namespace particles
