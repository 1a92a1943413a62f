#pragma once
// The compliant distance constraints of a large scene cut along blocks of
// particles, so that a Gauss–Seidel pass works through the state one
// cache-sized piece at a time and threads meet at two barriers a pass, not
// at one per colour.
#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "particle_range.h"
#include "particles/phase.h"
#include "thread_balance.h"
#include "xpbd/distance.h"

namespace particles {

// Particles per block, at least (their positions and start positions, 32 KB,
// fit in the first-level cache).
constexpr int kBlockParticles = 1024;
// And at least this many times the constraints' reach (the 90th percentile
// of |i − j|: a cloth's width): the cuts are projected after the blocks, and
// cut every 8 rows the 128² and 256² stiff cloths (xpbd 30 × 1 at 60 Hz)
// grew a mode along the cuts and blew up within 5 s; every 12 and 16 rows
// they held for 20 and 40 s, as with no blocks (test_integrators_xpbd).
constexpr int kBlockReaches = 16;

// Particles b·B … (b + 1)·B − 1 form block b (B: build()'s blockParticles). A
// constraint is
//  - in block b when both its particles are,
//  - in cut b when one is in block b and the other in block b + 1,
//  - in the rest otherwise (particles more than a block apart),
// and each of these groups is a DistanceBatch of its own. A pass projects
// every block, then the even cuts, then the odd cuts, then the rest, each
// group in its own colour order. No two blocks share a particle, nor two
// even cuts (cut b touches blocks b and b + 1 alone), nor two odd ones: the
// groups of each stage run on any thread in any order with the same bits.
// The blocks are shared among the threads by their speeds in the passes
// before (thread_balance.h); a thread takes contiguous blocks. Below two
// blocks of particles every constraint is in the rest: one DistanceBatch,
// as before blocks.
class DistanceBlocks {
 public:
  // blockParticles 0: max(kBlockParticles, kBlockReaches × reach).
  void build(const std::vector<CompliantDistance>& constraints, const Eigen::VectorXd& inverseMass,
             int blockParticles = 0);
  std::size_t size() const { return order_.size(); }
  std::size_t blocks() const { return blocks_.size(); }
  std::size_t cuts() const { return evenCuts_.size() + oddCuts_.size(); }
  std::size_t rest() const { return rest_.size(); }

  // As DistanceBatch::project, over the groups in the order above.
  // before(begin, end), when given, runs once on every particle before any
  // constraint on it is projected: on each block's particles just before
  // the block, on the thread that projects it (on [0, n) first when there
  // are no blocks). A caller's per-particle pass (xpbd's prediction) is
  // fused into the pass so; it may write x and xⁿ of its range alone.
  // after(begin, end), when given, runs once on every particle after every
  // constraint on it is projected, on ranges covering [0, n): on the blocks
  // each thread projected, in the same parallel region, when every
  // constraint is in a block or a cut (xpbd's velocity update, on the last
  // pass). It may read x and write anything of its range but x and xⁿ.
  void project(const double* xn, double* x, int pass, int passes, const ParticleRange& before = {},
               const ParticleRange& after = {});
  // The pass's order: order()[k] is the index, in build()'s list, of the
  // k-th constraint projected, and multiplier(k) its λ after a pass of several.
  const std::vector<int>& order() const { return order_; }
  double multiplier(std::size_t k) const;

 private:
  // A group: its constraints' indices in build()'s list and their batch.
  struct Group {
    std::vector<int> members;
    DistanceBatch batch;
  };
  // The blocks [first, last) whose constraints begin in the fraction [from, to) of the blocks' constraints.
  std::pair<std::size_t, std::size_t> blockShare(double from, double to) const;
  int blockBegin(std::size_t b) const;  // block b's first particle (n past the last block)

  std::vector<Group> blocks_;               // every block, empty or not (none below two blocks)
  std::vector<Group> evenCuts_, oddCuts_;  // the cuts that hold constraints
  int particles_ = 0, blockParticles_ = 1;
  DistanceBatch rest_;
  std::vector<int> restMembers_;
  std::vector<std::size_t> blockStart_;  // constraints in blocks_[0, b): blockStart_[b]
  std::vector<int> order_;
  std::vector<std::pair<std::size_t, const DistanceBatch*>> starts_;  // where each group begins in order_
  ThreadBalance balance_;
};

}  // namespace particles
