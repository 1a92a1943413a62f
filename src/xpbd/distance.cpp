#include "particles/xpbd/distance.h"

#include <algorithm>
#include <limits>
#include <map>
#include <tuple>

#include "particles/threads.h"

namespace particles {

namespace {

constexpr int kColours = 63;        // colours of independent constraints; the rest are serial
constexpr std::size_t kBlock = 64;  // constraints whose lengths are taken together
constexpr double kLargest = std::numeric_limits<double>::max();
constexpr std::size_t kParallelConstraints = 4096;  // fewer: one thread whatever the count

// Greedy colouring in the given order: each constraint takes the lowest colour
// neither of its particles has yet; kColours for none free.
std::vector<int> greedyColours(const std::vector<CompliantDistance>& constraints, int particles) {
  std::vector<std::uint64_t> used(particles, 0);
  std::vector<int> colour(constraints.size());
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    const int i = constraints[k].i, j = constraints[k].j;
    const std::uint64_t free = ~(used[i] | used[j]) & ((std::uint64_t{1} << kColours) - 1);
    const int c = free == 0 ? kColours : __builtin_ctzll(free);
    if (c < kColours) {
      used[i] |= std::uint64_t{1} << c;
      used[j] |= std::uint64_t{1} << c;
    }
    colour[k] = c;
  }
  return colour;
}

}  // namespace

void DistanceBatch::build(const std::vector<CompliantDistance>& constraints, const Eigen::VectorXd& inverseMass) {
  const std::vector<int> colour = greedyColours(constraints, static_cast<int>(inverseMass.size()));
  std::vector<std::size_t> start(kColours + 2, 0);
  for (int c : colour) ++start[c + 1];
  for (int c = 0; c <= kColours; ++c) start[c + 1] += start[c];
  colourEnd_.clear();
  for (int c = 1; c <= kColours; ++c)
    if (start[c] > start[c - 1]) colourEnd_.push_back(start[c]);
  serialBegin_ = start[kColours];

  const std::size_t n = constraints.size();
  first_.assign(n, 0);
  second_.assign(n, 0);
  entry_.assign(n, 0);
  entries_.clear();
  damped_ = false;
  std::map<std::tuple<double, double, double, double, double>, std::int32_t> shared;
  for (std::size_t k = 0; k < n; ++k) {
    const CompliantDistance& c = constraints[k];
    Entry e;
    e.rest = c.rest;
    e.wi = inverseMass[c.i];
    e.wj = inverseMass[c.j];
    e.compliance = c.compliance;
    e.inverseDenominator = inverseDenominator(e.wi + e.wj, e.compliance);
    const auto key = std::make_tuple(e.rest, e.wi, e.wj, e.compliance.alphaTilde, e.compliance.gamma);
    const auto [it, added] = shared.emplace(key, static_cast<std::int32_t>(entries_.size()));
    if (added) entries_.push_back(e);
    damped_ |= e.compliance.gamma != 0.0;
    const std::size_t at = start[colour[k]]++;
    first_[at] = 2 * c.i;
    second_[at] = 2 * c.j;
    entry_[at] = it->second;
  }
  lambda_.assign(n, 0.0);
}

void DistanceBatch::project(const double* xn, double* x, int pass, int passes) {
  // The loop's six variants (damped or not × how the multipliers are kept),
  // one table row per damping, chosen once per pass.
  using Range = void (DistanceBatch::*)(std::size_t, std::size_t, std::size_t, const double*, double*);
  static constexpr Range variants[2][3] = {
      {&DistanceBatch::projectRange<false, Multipliers::None>, &DistanceBatch::projectRange<false, Multipliers::Start>,
       &DistanceBatch::projectRange<false, Multipliers::Accumulate>},
      {&DistanceBatch::projectRange<true, Multipliers::None>, &DistanceBatch::projectRange<true, Multipliers::Start>,
       &DistanceBatch::projectRange<true, Multipliers::Accumulate>},
  };
  const Multipliers lambda = passes == 1 ? Multipliers::None : pass == 0 ? Multipliers::Start : Multipliers::Accumulate;
  const Range run = variants[damped_ ? 1 : 0][static_cast<int>(lambda)];
  const int threads = threadCount();
  if (threads > 1 && size() >= kParallelConstraints) {
    // Within a colour no two constraints share a particle: its blocks are
    // projected on any thread with the same bits; the colours stay in order.
#pragma omp parallel num_threads(threads)
    {
      std::size_t begin = 0;
      for (std::size_t end : colourEnd_) {
        const long blocks = static_cast<long>((end - begin + kBlock - 1) / kBlock);
#pragma omp for schedule(static)
        for (long b = 0; b < blocks; ++b)
          (this->*run)(begin + static_cast<std::size_t>(b) * kBlock,
                       std::min(end, begin + static_cast<std::size_t>(b + 1) * kBlock), kBlock, xn, x);
        begin = end;
      }
#pragma omp single
      (this->*run)(serialBegin_, size(), 1, xn, x);
    }
    return;
  }
  std::size_t begin = 0;
  for (std::size_t end : colourEnd_) {
    (this->*run)(begin, end, kBlock, xn, x);
    begin = end;
  }
  (this->*run)(serialBegin_, size(), 1, xn, x);
}

// Per block of independent constraints: gather d = x_i − x_j, take 1/|d| for
// the whole block at once (packed square roots and divisions; at |d| = 0 the
// largest double, so that u = d/|d| = 0: no direction, nothing moves), then
// per constraint
//   Δλ = (−C − α̃ λ − γ u·(d − dⁿ)) / ((1 + γ)(w_i + w_j) + α̃),
//   x_i += w_i Δλ u,   x_j −= w_j Δλ u
// (xpbd/multiplier.h; u·(d − dⁿ) = ∇C·(x − xⁿ)). Within a block no particle is
// shared, so d gathered first is still current when its constraint is projected.
template <bool kDamped, DistanceBatch::Multipliers kLambda>
void DistanceBatch::projectRange(std::size_t begin, std::size_t end, std::size_t block, const double* xn,
                                 double* x) {
  alignas(64) double dx[kBlock], dy[kBlock], squared[kBlock], inverseLength[kBlock];
  const std::int32_t* first = first_.data();
  const std::int32_t* second = second_.data();
  const std::int32_t* entry = entry_.data();
  const Entry* entries = entries_.data();
  double* lambda = lambda_.data();
  for (std::size_t b = begin; b < end; b += block) {
    const std::size_t m = std::min(block, end - b);
    for (std::size_t k = 0; k < m; ++k) {
      const std::int32_t i = first[b + k], j = second[b + k];
      dx[k] = x[i] - x[j];
      dy[k] = x[i + 1] - x[j + 1];
      squared[k] = dx[k] * dx[k] + dy[k] * dy[k];
    }
    using Lengths = Eigen::Map<Eigen::ArrayXd, Eigen::Aligned64>;
    const Lengths s(squared, static_cast<Eigen::Index>(m));
    Lengths(inverseLength, static_cast<Eigen::Index>(m)) = s.sqrt().inverse().min(kLargest);
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t c = b + k;
      const std::int32_t i = first[c], j = second[c];
      const Entry& e = entries[entry[c]];
      const double ux = dx[k] * inverseLength[k], uy = dy[k] * inverseLength[k];
      double numerator = e.rest - squared[k] * inverseLength[k];  // −C
      if constexpr (kDamped)
        numerator -= e.compliance.gamma * (ux * (dx[k] - (xn[i] - xn[j])) + uy * (dy[k] - (xn[i + 1] - xn[j + 1])));
      if constexpr (kLambda == Multipliers::Accumulate) numerator -= e.compliance.alphaTilde * lambda[c];
      const double dl = numerator * e.inverseDenominator;  // multiplierStep, its terms spelled out
      if constexpr (kLambda == Multipliers::Start) lambda[c] = dl;
      if constexpr (kLambda == Multipliers::Accumulate) lambda[c] += dl;
      const double si = e.wi * dl, sj = e.wj * dl;
      x[i] += si * ux;
      x[i + 1] += si * uy;
      x[j] -= sj * ux;
      x[j + 1] -= sj * uy;
    }
  }
}

}  // namespace particles
