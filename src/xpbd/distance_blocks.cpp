#include "xpbd/distance_blocks.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "parallel_for.h"
#include "forces/force_batch.h"
#include "particles/threads.h"

namespace particles {

namespace {
// The 90th percentile of |i − j| (0 for no constraints).
int reach(const std::vector<CompliantDistance>& constraints) {
  if (constraints.empty()) return 0;
  std::vector<int> spans;
  spans.reserve(constraints.size());
  for (const CompliantDistance& c : constraints) spans.push_back(std::abs(c.i - c.j));
  const auto at = spans.begin() + static_cast<long>(spans.size() * 9 / 10);
  std::nth_element(spans.begin(), at, spans.end());
  return *at;
}

std::vector<CompliantDistance> subset(const std::vector<CompliantDistance>& constraints,
                                      const std::vector<int>& members) {
  std::vector<CompliantDistance> picked;
  picked.reserve(members.size());
  for (int k : members) picked.push_back(constraints[k]);
  return picked;
}
}  // namespace

void DistanceBlocks::build(const std::vector<CompliantDistance>& constraints, const Eigen::VectorXd& inverseMass,
                           int blockParticles) {
  if (blockParticles <= 0)
    blockParticles = static_cast<int>(std::min<long long>(
        std::numeric_limits<int>::max(),
        std::max<long long>(kBlockParticles, static_cast<long long>(kBlockReaches) * reach(constraints))));
  const int particles = static_cast<int>(inverseMass.size());
  const int count = static_cast<int>((static_cast<long long>(particles) + blockParticles - 1) / blockParticles);
  std::vector<std::vector<int>> inBlock(count >= 2 ? count : 0), inCut(count >= 2 ? count - 1 : 0);
  restMembers_.clear();
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    const int bi = constraints[k].i / blockParticles, bj = constraints[k].j / blockParticles;
    const int member = static_cast<int>(k);
    if (count < 2 || std::abs(bi - bj) > 1)
      restMembers_.push_back(member);
    else if (bi == bj)
      inBlock[bi].push_back(member);
    else
      inCut[std::min(bi, bj)].push_back(member);
  }
  // Every block, empty or not (block b is particles [b·B, (b + 1)·B)); the
  // cuts that hold constraints.
  auto groups = [&](const std::vector<std::vector<int>>& lists, int first, int step, bool keepEmpty) {
    std::vector<Group> made;
    for (std::size_t b = first; b < lists.size(); b += step)
      if (keepEmpty || !lists[b].empty()) {
        made.push_back({lists[b], DistanceBatch{}});
        made.back().batch.build(subset(constraints, lists[b]), inverseMass);
      }
    return made;
  };
  blocks_ = groups(inBlock, 0, 1, true);
  evenCuts_ = groups(inCut, 0, 2, false);
  oddCuts_ = groups(inCut, 1, 2, false);
  particles_ = particles;
  blockParticles_ = blockParticles;
  rest_.build(subset(constraints, restMembers_), inverseMass);

  blockStart_.assign(1, 0);
  for (const Group& g : blocks_) blockStart_.push_back(blockStart_.back() + g.batch.size());
  order_.clear();
  starts_.clear();
  auto append = [&](const std::vector<int>& members, const DistanceBatch& batch) {
    starts_.emplace_back(order_.size(), &batch);
    for (int k : batch.order()) order_.push_back(members[k]);
  };
  for (const auto* stage : {&blocks_, &evenCuts_, &oddCuts_})
    for (const Group& g : *stage) append(g.members, g.batch);
  append(restMembers_, rest_);
}

double DistanceBlocks::multiplier(std::size_t k) const {
  const auto at = std::upper_bound(starts_.begin(), starts_.end(), k,
                                   [](std::size_t value, const auto& start) { return value < start.first; }) -
                  1;
  return at->second->multiplier(k - at->first);
}

std::pair<std::size_t, std::size_t> DistanceBlocks::blockShare(double from, double to) const {
  const double total = static_cast<double>(blockStart_.back());
  // The block boundary nearest the fraction: blocks are coarse (8 on the
  // 128² cloth), and always rounding up would hand a thread a whole block
  // more whenever its share crept past an even split.
  auto at = [&](double fraction) {
    const double target = fraction * total;
    auto next = std::lower_bound(blockStart_.begin(), blockStart_.end() - 1, target,
                                 [](std::size_t start, double t) { return static_cast<double>(start) < t; });
    if (next != blockStart_.begin() && target - static_cast<double>(*(next - 1)) < static_cast<double>(*next) - target)
      --next;
    return static_cast<std::size_t>(next - blockStart_.begin());
  };
  return {at(from), to >= 1.0 ? blocks_.size() : at(to)};
}

void DistanceBlocks::project(const double* xn, double* x, int pass, int passes, const ParticleRange& before,
                             const ParticleRange& after) {
  const int threads = threadCount();
  auto projectBlocks = [&](std::size_t first, std::size_t last) {
    for (std::size_t b = first; b < last; ++b) {
      if (before) before(blockBegin(b), blockBegin(b + 1));
      blocks_[b].batch.projectOnThisThread(xn, x, pass, passes);
    }
  };
  if (blocks_.empty() && before) before(0, particles_);
  if (threads > 1 &&
      (blockStart_.back() >= kParallelConstraints || (before && !blocks_.empty() && particles_ >= kParallelParticles))) {
    const std::vector<double> cuts = balance_.cuts(threads);
    std::vector<std::pair<std::size_t, std::size_t>> shares;  // each part's blocks [first, last)
    for (int part = 0; part < threads; ++part) shares.push_back(blockShare(cuts[part], cuts[part + 1]));
    ThreadBalance::Pass measured(threads);
    const bool afterInRegion = after && rest_.size() == 0;
    parallelTeam(threads, [&](const Team& team) {
      measured.run([&](int part) {
        const auto [first, last] = shares[part];
        projectBlocks(first, last);
        return static_cast<double>(blockStart_[last] - blockStart_[first]);
      });
      team.wait();
      const int even = static_cast<int>(evenCuts_.size()), odd = static_cast<int>(oddCuts_.size());
      for (int g = team.rangeBegin(even), end = team.rangeEnd(even); g < end; ++g)
        evenCuts_[g].batch.projectOnThisThread(xn, x, pass, passes);
      team.wait();
      for (int g = team.rangeBegin(odd), end = team.rangeEnd(odd); g < end; ++g)
        oddCuts_[g].batch.projectOnThisThread(xn, x, pass, passes);
      if (afterInRegion) {
        // Every constraint is in a block or a cut, all projected: each thread
        // takes the particles of the blocks it projected, still in its cache.
        team.wait();
        measured.each([&](int part) {
          const auto [first, last] = shares[part];
          if (first < last) after(blockBegin(first), blockBegin(last));
        });
      }
    });
    balance_.update(measured);
    if (afterInRegion) return;
  } else {
    projectBlocks(0, blocks_.size());
    for (auto* stage : {&evenCuts_, &oddCuts_})
      for (Group& g : *stage) g.batch.projectOnThisThread(xn, x, pass, passes);
  }
  rest_.project(xn, x, pass, passes);
  if (after) parallelRanges(particles_, threads, kParallelParticles, after);
}

int DistanceBlocks::blockBegin(std::size_t b) const {
  return static_cast<int>(std::min<long long>(particles_, static_cast<long long>(b) * blockParticles_));
}

}  // namespace particles
