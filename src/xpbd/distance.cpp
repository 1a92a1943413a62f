#include "xpbd/distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "parallel_for.h"
#include "particles/threads.h"
#include "strided_runs.h"
#include "vector_kernels.h"

namespace particles {

namespace {

constexpr int kColours = 63;        // colours of independent constraints; the rest are serial
constexpr std::size_t kBlock = 64;  // constraints whose lengths are taken together
constexpr double kLargest = std::numeric_limits<double>::max();
constexpr int kRunLength = 256, kMinRun = 8;        // strided runs (strided_runs.h)

// Greedy colouring: each item takes the lowest of the kColours colours none
// of its particles has yet, and marks them; kColours when none is free.
// Particles lo … hi − 1 are the ones the items may name.
class GreedyColours {
 public:
  GreedyColours(int lo, int hi) : lo_(lo), used_(std::max(0, hi - lo), 0) {}
  template <class Particles>
  int take(const Particles& particles) {
    std::uint64_t taken = 0;
    for (int p : particles) taken |= used_[p - lo_];
    const std::uint64_t free = ~taken & ((std::uint64_t{1} << kColours) - 1);
    const int c = free == 0 ? kColours : __builtin_ctzll(free);
    if (c < kColours)
      for (int p : particles) used_[p - lo_] |= std::uint64_t{1} << c;
    return c;
  }

 private:
  int lo_;
  std::vector<std::uint64_t> used_;
};

// A strided run cut into pieces whose constraints share no particle (see
// DistanceBatch): stride ≥ length, one piece; an odd stride, the even and the
// odd constraints (step 2); an even one, pieces of |stride| constraints.
// Members are indices into the found runs' order.
struct Piece {
  int first, stride, step, length;
  std::vector<int> members;
};

std::vector<Piece> independentPieces(const StridedRuns& found) {
  std::vector<Piece> pieces;
  for (const StridedRun& r : found.runs) {
    const int d = std::abs(r.stride);
    auto piece = [&](int t0, int step, int length) {
      Piece p{r.first + t0, r.stride, step, length, {}};
      for (int t = 0; t < length; ++t) p.members.push_back(found.order[r.begin + t0 + step * t]);
      pieces.push_back(std::move(p));
    };
    if (d >= r.length) {
      piece(0, 1, r.length);
    } else if (d % 2 == 1) {
      piece(0, 2, (r.length + 1) / 2);
      piece(1, 2, r.length / 2);
    } else {
      for (int t0 = 0; t0 < r.length; t0 += d) piece(t0, 1, std::min(d, r.length - t0));
    }
  }
  return pieces;
}

// One run of constraints t < length joining the particles at x + 2·step·t
// and x + 2·step·t + 2·stride, no two sharing a particle, with one entry's
// parameters: projectRange's formulas (below), operation for operation, as a
// vectorisable loop. kLambda: 0 not kept, 1 started, 2 accumulated; kStep 1 or 2.
template <bool kDamped, int kLambda, int kStep>
PARTICLES_VECTOR_CLONES void projectRun(int length, int stride, const double* xn, double* x, double* lambda,
                                        double rest, double wi, double wj, double alphaTilde, double gamma,
                                        double inverseDenominator) {
  const int s = 2 * kStep, d = 2 * stride;
#pragma omp simd
  for (int t = 0; t < length; ++t) {
    const int i = s * t, j = s * t + d;
    const double dx = x[i] - x[j], dy = x[i + 1] - x[j + 1];
    const double squared = dx * dx + dy * dy;
    const double inverse = 1.0 / std::sqrt(squared);
    const double inverseLength = inverse < kLargest ? inverse : kLargest;
    const double ux = dx * inverseLength, uy = dy * inverseLength;
    double numerator = rest - squared * inverseLength;
    if constexpr (kDamped)
      numerator -= gamma * (ux * (dx - (xn[i] - xn[j])) + uy * (dy - (xn[i + 1] - xn[j + 1])));
    if constexpr (kLambda == 2) numerator -= alphaTilde * lambda[t];
    const double dl = numerator * inverseDenominator;
    if constexpr (kLambda == 1) lambda[t] = dl;
    if constexpr (kLambda == 2) lambda[t] += dl;
    const double si = wi * dl, sj = wj * dl;
    x[i] += si * ux;
    x[i + 1] += si * uy;
    x[j] -= sj * ux;
    x[j + 1] -= sj * uy;
  }
}

}  // namespace

// Entries (parameters shared by equal constraints), then runs of one entry,
// cut into independent pieces and coloured; what no run takes is coloured
// constraint by constraint. Layout: the runs colour by colour, then the
// other constraints colour by colour, then the serial ones.
void DistanceBatch::build(const std::vector<CompliantDistance>& constraints, const Eigen::VectorXd& inverseMass) {
  const std::size_t n = constraints.size();
  // The colour tables cover the particles the constraints name, not the
  // whole state: a block of a large cloth (xpbd/distance_blocks.h) is small.
  int lo = static_cast<int>(inverseMass.size()), hi = 0;
  for (const CompliantDistance& c : constraints) {
    lo = std::min({lo, c.i, c.j});
    hi = std::max({hi, c.i + 1, c.j + 1});
  }
  std::vector<int> entryOf(n), firsts(n), seconds(n);
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
    entryOf[k] = it->second;
    firsts[k] = c.i;
    seconds[k] = c.j;
  }

  // Runs: pieces coloured in their order; a piece with no free colour is left to the others.
  std::vector<Piece> pieces = independentPieces(findStridedRuns(firsts, seconds, kRunLength, kMinRun, entryOf));
  std::stable_sort(pieces.begin(), pieces.end(),
                   [](const Piece& a, const Piece& b) { return std::abs(a.stride) < std::abs(b.stride); });
  GreedyColours runColours(lo, hi);
  std::vector<std::vector<const Piece*>> byColour(kColours);
  std::vector<bool> inRun(n, false);
  for (const Piece& p : pieces) {
    std::vector<int> touched;
    for (int t = 0; t < p.length; ++t) {
      touched.push_back(p.first + p.step * t);
      touched.push_back(p.first + p.step * t + p.stride);
    }
    const int c = runColours.take(touched);
    if (c == kColours) continue;
    byColour[c].push_back(&p);
    for (int k : p.members) inRun[k] = true;
  }
  order_.clear();
  runs_.clear();
  runColourEnd_.clear();
  for (auto& colour : byColour) {
    if (colour.empty()) continue;
    // Within a colour by first particle: a thread's share of it is a region
    // of the particles, the same region from one colour to the next.
    std::stable_sort(colour.begin(), colour.end(), [](const Piece* a, const Piece* b) { return a->first < b->first; });
    for (const Piece* p : colour) {
      runs_.push_back({order_.size(), p->first, p->stride, p->step, p->length, entryOf[p->members[0]]});
      order_.insert(order_.end(), p->members.begin(), p->members.end());
    }
    runColourEnd_.push_back(runs_.size());
  }
  runConstraints_ = order_.size();

  // The rest, constraint by constraint in their order.
  GreedyColours colours(lo, hi);
  std::vector<std::vector<int>> rest(kColours + 1);
  for (std::size_t k = 0; k < n; ++k)
    if (!inRun[k]) rest[colours.take(std::array<int, 2>{constraints[k].i, constraints[k].j})].push_back(static_cast<int>(k));
  colourEnd_.clear();
  for (int c = 0; c <= kColours; ++c) {
    if (c == kColours) serialBegin_ = order_.size();
    order_.insert(order_.end(), rest[c].begin(), rest[c].end());
    if (c < kColours && !rest[c].empty()) colourEnd_.push_back(order_.size());
  }

  first_.resize(n);
  second_.resize(n);
  entry_.resize(n);
  for (std::size_t at = 0; at < n; ++at) {
    const int k = order_[at];
    first_[at] = 2 * constraints[k].i;
    second_[at] = 2 * constraints[k].j;
    entry_[at] = entryOf[k];
  }
  lambda_.assign(n, 0.0);
}

void DistanceBatch::projectRuns(std::size_t begin, std::size_t end, const double* xn, double* x, int lambdaMode) {
  using Kernel = void (*)(int, int, const double*, double*, double*, double, double, double, double, double, double);
  static constexpr Kernel variants[2][3][2] = {
      {{&projectRun<false, 0, 1>, &projectRun<false, 0, 2>},
       {&projectRun<false, 1, 1>, &projectRun<false, 1, 2>},
       {&projectRun<false, 2, 1>, &projectRun<false, 2, 2>}},
      {{&projectRun<true, 0, 1>, &projectRun<true, 0, 2>},
       {&projectRun<true, 1, 1>, &projectRun<true, 1, 2>},
       {&projectRun<true, 2, 1>, &projectRun<true, 2, 2>}},
  };
  const auto& kernels = variants[damped_ ? 1 : 0][lambdaMode];
  for (std::size_t r = begin; r < end; ++r) {
    const Run& run = runs_[r];
    const Entry& e = entries_[run.entry];
    const std::size_t offset = 2 * static_cast<std::size_t>(run.first);
    kernels[run.step - 1](run.length, run.stride, xn + offset, x + offset, lambda_.data() + run.begin, e.rest, e.wi,
                          e.wj, e.compliance.alphaTilde, e.compliance.gamma, e.inverseDenominator);
  }
}

// Runs [begin, end) of one colour, ordered by first particle, shared out by
// their constraints: the runs that begin in the fraction [from, to) of the
// colour's constraints.
std::pair<std::size_t, std::size_t> DistanceBatch::runShare(std::size_t begin, std::size_t end, double from,
                                                            double to) const {
  const std::size_t lo = runs_[begin].begin, hi = runs_[end - 1].begin + runs_[end - 1].length;
  auto at = [&](double fraction) {
    const std::size_t target = lo + static_cast<std::size_t>(std::llround(fraction * static_cast<double>(hi - lo)));
    return static_cast<std::size_t>(
        std::lower_bound(runs_.begin() + static_cast<long>(begin), runs_.begin() + static_cast<long>(end), target,
                         [](const Run& r, std::size_t t) { return r.begin < t; }) -
        runs_.begin());
  };
  return {at(from), to >= 1.0 ? end : at(to)};
}

DistanceBatch::Multipliers DistanceBatch::multipliers(int pass, int passes) {
  return passes == 1 ? Multipliers::None : pass == 0 ? Multipliers::Start : Multipliers::Accumulate;
}

DistanceBatch::Range DistanceBatch::rangeVariant(int lambdaMode) const {
  // The loop's six variants (damped or not × how the multipliers are kept),
  // one table row per damping, chosen once per pass.
  static constexpr Range variants[2][3] = {
      {&DistanceBatch::projectRange<false, Multipliers::None>, &DistanceBatch::projectRange<false, Multipliers::Start>,
       &DistanceBatch::projectRange<false, Multipliers::Accumulate>},
      {&DistanceBatch::projectRange<true, Multipliers::None>, &DistanceBatch::projectRange<true, Multipliers::Start>,
       &DistanceBatch::projectRange<true, Multipliers::Accumulate>},
  };
  return variants[damped_ ? 1 : 0][lambdaMode];
}

void DistanceBatch::project(const double* xn, double* x, int pass, int passes) {
  const int lambdaMode = static_cast<int>(multipliers(pass, passes));
  const Range run = rangeVariant(lambdaMode);
  const int threads = threadCount();
  if (threads > 1 && size() >= kParallelConstraints) {
    // Within a colour no two runs or constraints share a particle: its runs
    // and blocks are projected on any thread with the same bits; the colours
    // stay in order.
    // Each colour's runs are shared out by the threads' speeds in the passes
    // before (thread_balance.h): the threads reach each barrier together.
    const std::vector<double> cuts = balance_.cuts(threads);
    ThreadBalance::Pass measured(threads);
    parallelTeam(threads, [&](const Team& team) {
      // A barrier between one colour and the next; none after the last: the region's end is one.
      bool started = false;
      auto nextColour = [&]() {
        if (started) team.wait();
        started = true;
      };
      std::size_t begin = 0;
      for (std::size_t end : runColourEnd_) {
        nextColour();
        measured.run([&](int part) {
          const auto [from, to] = runShare(begin, end, cuts[part], cuts[part + 1]);
          projectRuns(from, to, xn, x, lambdaMode);
          return from < to ? static_cast<double>(runs_[to - 1].begin + runs_[to - 1].length - runs_[from].begin) : 0.0;
        });
        begin = end;
      }
      begin = runConstraints_;
      for (std::size_t end : colourEnd_) {
        nextColour();
        const int blocks = static_cast<int>((end - begin + kBlock - 1) / kBlock);
        for (int b = team.rangeBegin(blocks), last = team.rangeEnd(blocks); b < last; ++b)
          (this->*run)(begin + static_cast<std::size_t>(b) * kBlock,
                       std::min(end, begin + static_cast<std::size_t>(b + 1) * kBlock), kBlock, xn, x);
        begin = end;
      }
      if (serialBegin_ < size()) {
        nextColour();
        if (team.member == 0) (this->*run)(serialBegin_, size(), 1, xn, x);
      }
    });
    balance_.update(measured);
    return;
  }
  projectOnThisThread(xn, x, pass, passes);
}

void DistanceBatch::projectOnThisThread(const double* xn, double* x, int pass, int passes) {
  const int lambdaMode = static_cast<int>(multipliers(pass, passes));
  const Range run = rangeVariant(lambdaMode);
  projectRuns(0, runs_.size(), xn, x, lambdaMode);
  std::size_t begin = runConstraints_;
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
