#pragma once
// Homogeneous force sets evaluated as flat arrays, one loop per type, instead
// of one virtual call per force object. The public Force objects stay the way
// to add a force; ForceBatches is rebuilt from them whenever the system's
// structure stamp changes, and a force type without a batch keeps its virtual
// call, in its place in the list.
//
// Order: the segments add their forces in the order of the system's force
// list; within a spring segment the springs are added in runs
// (forces/spring_batch.h), so f differs from the plain loop over the force
// objects by rounding only, and is the same bits for any thread count.
// Fields on every particle (gravity, drag) that come after the last other
// force are fused with a = W f into one pass over the particles when nothing
// else is added to f between them and the division by the mass, and that
// pass is fused into the last spring segment's pass over its particles.
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "particle_range.h"
#include "particles/force.h"
#include "forces/spring_batch.h"

namespace particles {

// Below kParallelParticles particles the per-particle passes run serially.
constexpr int kParallelParticles = 4096;

// A per-particle field: f_i += m_i g (gravity) or f_i −= k_d v_i (drag),
// on movable particles only.
struct FieldTerm {
  enum class Kind { Gravity, Drag } kind;
  Eigen::Vector2d gravity = Eigen::Vector2d::Zero();  // world units / s²
  double drag;              // mass / s
};

class ForceBatches {
 public:
  // Rebuilds the segments when stamp differs from the one last built for.
  void update(const std::vector<std::unique_ptr<Force>>& forces, std::uint64_t stamp);
  void update(const std::vector<const Force*>& forces, std::uint64_t stamp);

  // f = Σ forces at s (f sized 2n here).
  void apply(const Phase& s, Eigen::VectorXd& f) const;
  // f = Σ forces at s and a = W f, the trailing fields and the division by
  // the mass fused into one pass over the particles; then(begin, end) runs
  // in that pass as soon as a's entries of particles [begin, end) are final.
  // While it runs, other ranges may still be reading s: then writes no entry
  // of s.x or s.v, nor any entry of another range.
  void applyAndDivide(const Phase& s, Eigen::VectorXd& f, Eigen::VectorXd& a, const ParticleRange& then = {}) const;
  // applyAndDivide at phases[0], phases[1], … in turn, then(k, begin, end)
  // in evaluation k's pass, on the terms of ParticleSystem::accelerations:
  // phases[k + 1] may be what then(k, ·) writes, and then touches its own
  // range only.
  // When the forces are one spring batch and trailing fields, the sequence
  // is one pass of the batch (SpringBatch::applySequence: one parallel
  // region); otherwise the evaluations run one by one.
  void applyAndDivide(const std::vector<Phase>& phases, Eigen::VectorXd& f, Eigen::VectorXd& a,
                      const StageRange& then) const;
  // Whether every force is a field (gravity, drag): then f and a = W f on a
  // particle depend on that particle alone, and applyAndDivide(begin, end, …)
  // gives them range by range, so that a caller can fuse its own
  // per-particle pass into the same loop. f and a hold the range alone,
  // 2(end − begin) entries each from particle begin's x: a caller's scratch
  // for one block, or its full vectors from entry 2·begin.
  bool fieldsOnly() const { return headSegments_ == 0; }
  void applyAndDivide(int begin, int end, const Phase& s, double* f, double* a) const {
    tailAndDivide(begin, end, s, f, a, true);
  }

  int springCount() const;
  const std::vector<SpringBatch>& springBatches() const { return springs_; }

 private:
  // One run of the force list: a spring batch, one field term, or one force
  // evaluated through its virtual call.
  struct Segment {
    enum class Kind { Springs, Field, Virtual } kind;
    int springs = 0;  // index into springs_ (Springs)
    FieldTerm field{FieldTerm::Kind::Gravity, Eigen::Vector2d::Zero(), 0.0};  // (Field)
    const Force* force = nullptr;  // (Virtual)
  };
  // Segments [begin, end) into f, which holds the earlier ones' sum; f is
  // cleared first when begin is 0. finish runs after the last one.
  void applySegments(int begin, int end, const Phase& s, Eigen::VectorXd& f,
                     const ParticleRange& finish) const;
  // The trailing fields on particles [begin, end), f cleared there first
  // when clear is set (f holds the range alone, as above).
  void addTail(int begin, int end, const Phase& s, double* f, bool clear) const;
  // The trailing fields and a = W f on particles [begin, end), as addTail.
  void tailAndDivide(int begin, int end, const Phase& s, double* f, double* a, bool clear) const;

  std::vector<Segment> segments_;
  std::vector<FieldTerm> tail_;  // the fields after the last other segment, in order
  int headSegments_ = 0;         // segments_ before the tail
  std::vector<SpringBatch> springs_;
  std::uint64_t stamp_ = 0;
  bool built_ = false;
};

}  // namespace particles
