#pragma once
// Compliant distance constraints: damped springs in position form, laid out
// flat for the substep loop.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "thread_balance.h"
#include "xpbd/multiplier.h"

namespace particles {

// Below this many constraints a parallel stage of a pass runs on one thread,
// whatever the thread count.
constexpr std::size_t kParallelConstraints = 4096;

// Between particles i and j with d = x_i − x_j, u = d/|d|:
//   C = |d| − r,   ∇_i C = u,   ∇_j C = −u,   ∇C W ∇Cᵀ = w_i + w_j,
// and with compliance α = 1/k_s and damping β = k_d it is the spring
// f_i = −[k_s(|d| − r) + k_d ḋ·u] u of forces/spring.h.
struct CompliantDistance {
  int i = 0, j = 0;
  double rest = 0.0;  // r, world units
  Compliance compliance;
};

// The distance constraints of a scene as structure-of-arrays, built once per
// structure and substep h: particle offsets and an entry of rest length,
// inverse masses, compliance and, since ∇C W ∇Cᵀ = w_i + w_j does not depend
// on x, the denominator of Δλ. A pass is Gauss–Seidel in the batch's order,
// colour by colour, where no two constraints of a colour share a particle:
//  - first strided runs (strided_runs.h: constraints (a + t, a + t + d) of
//    one entry, found in any order of the list), cut into pieces that share
//    no particle (|d| ≥ length: the whole run; odd d: its even and its odd
//    constraints; even d: pieces of |d|), each piece one vectorised loop over
//    contiguous (or every other) particles, the pieces coloured greedily;
//  - then the other constraints, coloured greedily one by one and projected
//    in blocks whose square roots and divisions are packed and whose
//    projections the processor overlaps;
//  - constraints at a particle that already has 63 colours, one by one at the end.
// With several threads each colour's runs and blocks are shared among them
// (the same bits for any count).
class DistanceBatch {
 public:
  void build(const std::vector<CompliantDistance>& constraints, const Eigen::VectorXd& inverseMass);
  std::size_t size() const { return first_.size(); }
  std::size_t colours() const { return runColourEnd_.size() + colourEnd_.size(); }

  // Pass number `pass` of `passes` over every constraint, Gauss–Seidel at the
  // flat positions x (x0, y0, x1, ...), with xⁿ the positions at the start of
  // the substep. The multipliers start at 0 on pass 0 and are kept between
  // passes (not stored when there is one pass).
  void project(const double* xn, double* x, int pass, int passes);
  // The same pass on the calling thread alone, whatever the thread count
  // (the same bits as project()).
  void projectOnThisThread(const double* xn, double* x, int pass, int passes);
  // λ of the k-th constraint in the batch's order after a pass of several.
  double multiplier(std::size_t k) const { return lambda_[k]; }
  // The batch's order: order()[k] is the index, in build()'s list, of the
  // k-th constraint projected.
  const std::vector<int>& order() const { return order_; }
  std::size_t runs() const { return runs_.size(); }
  std::size_t constraintsInRuns() const { return runConstraints_; }

 private:
  enum class Multipliers { None, Start, Accumulate };
  using Range = void (DistanceBatch::*)(std::size_t, std::size_t, std::size_t, const double*, double*);
  static Multipliers multipliers(int pass, int passes);
  Range rangeVariant(int lambdaMode) const;
  template <bool kDamped, Multipliers kLambda>
  void projectRange(std::size_t begin, std::size_t end, std::size_t block, const double* xn, double* x);
  // Runs [begin, end) of runs_ (lambdaMode: Multipliers as an int).
  void projectRuns(std::size_t begin, std::size_t end, const double* xn, double* x, int lambdaMode);
  // The runs of one colour's runs [begin, end) that begin in the fraction [from, to) of its constraints.
  std::pair<std::size_t, std::size_t> runShare(std::size_t begin, std::size_t end, double from, double to) const;

  // Constraints begin … begin + length − 1 join particles first + step·t and
  // first + step·t + stride, with entry `entry`.
  struct Run {
    std::size_t begin;
    int first, stride, step, length;
    std::int32_t entry;
  };
  std::vector<Run> runs_;
  std::vector<std::size_t> runColourEnd_;  // runs_ of colour c: [runColourEnd_[c−1], runColourEnd_[c])
  std::size_t runConstraints_ = 0;         // constraints [0, runConstraints_) are the runs'
  std::vector<int> order_;

  // A constraint's parameters; equal ones are shared (a regular cloth has
  // two), so a pass streams 12 bytes per constraint from memory.
  struct Entry {
    double rest = 0.0;                // r
    double wi = 0.0, wj = 0.0;        // w_i, w_j
    Compliance compliance;            // α̃ = α/h², γ = αβ/h
    double inverseDenominator = 0.0;  // 1/((1 + γ)(w_i + w_j) + α̃)
  };
  std::vector<std::int32_t> first_, second_;  // 2i and 2j: offsets into x
  std::vector<std::int32_t> entry_;           // into entries_
  std::vector<Entry> entries_;
  std::vector<double> lambda_;
  std::vector<std::size_t> colourEnd_;        // colour c is [colourEnd_[c−1], colourEnd_[c]), after the runs
  std::size_t serialBegin_ = 0;               // [serialBegin_, size()) one by one
  bool damped_ = false;                       // some γ ≠ 0
  ThreadBalance balance_;                     // how the runs of a colour are shared out among threads
};

}  // namespace particles
