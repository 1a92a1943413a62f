#pragma once
// Homogeneous force sets evaluated as flat arrays, one loop per type, instead
// of one virtual call per force object. The public Force objects stay the way
// to add a force; ForceBatches is rebuilt from them whenever the system's
// structure stamp changes, and a force type without a batch keeps its virtual
// call, in its place in the list.
//
// Order: the force accumulator gets every contribution in the order of the
// system's force list, so each f_i is summed in the same order as the plain
// loop over forces and the results are the same bits. Fields on every particle
// (gravity, drag) that come after the last other force are fused with
// a = W f into one pass over the particles when there are no constraints
// (nothing else is added to f between them and the division by the mass).
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "particles/force.h"

namespace particles {

// Springs as structure of arrays (see forces/spring.h for the force law).
// Below kParallelSprings springs a batch runs serially whatever the thread count.
constexpr int kParallelSprings = 4096;
// Below kParallelParticles particles the per-particle passes run serially.
constexpr int kParallelParticles = 4096;
struct SpringBatch {
  std::vector<int> first, second;
  std::vector<double> rest, stiffness, damping;
  int size() const { return static_cast<int>(first.size()); }
  void clear();
  void add(int i, int j, double r, double ks, double kd);
  // Adds springs [begin, end) at phase s into f, on threadCount() threads
  // when there are several (same bits: see applyParallel).
  void apply(int begin, int end, const Phase& s, Eigen::VectorXd& f) const;

 private:
  // The force of spring k on its first particle, f_i (f_j = −f_i); false
  // (and 0) for a spring of length 0.
  bool force(int k, const double* x, const double* v, double& fx, double& fy) const;
  // Parallel: every spring's force into forces_ (independent), then each
  // particle gathers its springs in ascending order, + for a first end and
  // − for a second: the same additions in the same order as the serial
  // scatter, so the same bits, with no two threads writing one entry.
  void applyParallel(int begin, int end, const Phase& s, Eigen::VectorXd& f, int threads) const;
  // Springs of each particle, ascending, as a compressed list (rebuilt when
  // the range or the particle count changes).
  void buildIncidence(int begin, int end, int particles) const;
  mutable std::vector<int> incidenceStart_, incidence_;  // incidence_: k, or ~k for a second end
  mutable std::vector<double> forces_;                   // 2 per spring
  mutable int incidenceBegin_ = -1, incidenceEnd_ = -1, incidenceParticles_ = -1;
};

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

  // f = Σ forces at s (f sized 2n, cleared here). When fuseTail is true the
  // trailing fields are left out of f for applyTailAndDivide().
  void apply(const Phase& s, Eigen::VectorXd& f, bool fuseTail) const;
  // The fused last pass: f_i += trailing fields, then a_i = w_i f_i.
  void applyTailAndDivide(const Phase& s, Eigen::VectorXd& f, Eigen::VectorXd& a) const;

  const SpringBatch& springs() const { return springs_; }

 private:
  // One run of the force list: springs [begin, end) of springs_, one field
  // term, or one force evaluated through its virtual call.
  struct Segment {
    enum class Kind { Springs, Field, Virtual } kind;
    int begin = 0, end = 0;   // springs_ range (Springs)
    FieldTerm field{FieldTerm::Kind::Gravity, Eigen::Vector2d::Zero(), 0.0};  // (Field)
    const Force* force = nullptr;  // (Virtual)
  };
  std::vector<Segment> segments_;
  std::vector<FieldTerm> tail_;  // the fields after the last other segment, in order
  int headSegments_ = 0;         // segments_ before the tail
  SpringBatch springs_;
  std::uint64_t stamp_ = 0;
  bool built_ = false;
};

}  // namespace particles
