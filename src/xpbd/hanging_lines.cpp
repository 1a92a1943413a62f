#include "particles/xpbd/hanging_lines.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "parallel_for.h"
#include "vector_kernels.h"
#include "particles/threads.h"

namespace particles {

namespace {

constexpr double kLargest = std::numeric_limits<double>::max();
constexpr std::size_t kParallelConstraints = 4096;  // fewer: one thread whatever the count
constexpr int kShortest = 2;                        // constraints on a line
constexpr int kLanes = 8;                           // lines solved side by side

// The constraint from particle p to p + step, by (p, step); a pair listed
// twice is on no line (its key is marked ambiguous).
class Links {
 public:
  explicit Links(const std::vector<CompliantDistance>& distances) {
    for (std::size_t k = 0; k < distances.size(); ++k) {
      const CompliantDistance& c = distances[k];
      if (c.i == c.j) continue;
      add(c.i, c.j - c.i, static_cast<int>(k));
      add(c.j, c.i - c.j, static_cast<int>(k));
    }
  }
  // The constraint from p to p + step; −1 if none or ambiguous.
  int at(int p, int step) const {
    const auto it = links_.find(key(p, step));
    return it == links_.end() ? -1 : it->second;
  }
  // The steps of the constraints at p, smallest first.
  std::vector<int> steps(int p) const {
    const auto it = stepsAt_.find(p);
    if (it == stepsAt_.end()) return {};
    std::vector<int> s = it->second;
    std::sort(s.begin(), s.end());
    return s;
  }

 private:
  static std::int64_t key(int p, int step) { return (static_cast<std::int64_t>(p) << 32) ^ static_cast<std::uint32_t>(step); }
  void add(int p, int step, int k) {
    const auto [it, added] = links_.emplace(key(p, step), k);
    if (!added) {
      it->second = -1;
      return;
    }
    stepsAt_[p].push_back(step);
  }
  std::unordered_map<std::int64_t, int> links_;
  std::unordered_map<int, std::vector<int>> stepsAt_;
};

struct Candidate {
  int first, step, length;
  double score, restLength;
};

// The best line starting at p (Links above), with the hold's gradient g (zero
// for a pin): the most particles it carries that are not held themselves,
// times its alignment with g, ties to the shorter rest length (a column
// before a diagonal), then the smaller step.
Candidate bestLine(const std::vector<CompliantDistance>& distances, const Links& links, const Phase& s,
                   const std::vector<bool>& held, int p, const Eigen::Vector2d& g) {
  Candidate best{p, 0, 0, 0.0, 0.0};
  for (int step : links.steps(p)) {
    int length = 0, movable = 0;
    double restLength = 0.0;
    for (int k; (k = links.at(p + step * length, step)) >= 0; ++length) {
      restLength += distances[static_cast<std::size_t>(k)].rest;
      movable += held[static_cast<std::size_t>(p + step * (length + 1))] ? 0 : 1;
    }
    if (length < kShortest) continue;
    const Eigen::Vector2d d = s.position(p) - s.position(p + step);
    double alignment = 1.0;
    if (g.squaredNorm() > 0.0) alignment = d.norm() > 0.0 ? std::abs(g.dot(d)) / (g.norm() * d.norm()) : 0.0;
    const double score = movable * alignment;
    if (score > best.score || (score == best.score && score > 0.0 && restLength < best.restLength))
      best = {p, step, length, score, restLength};
  }
  return best;
}

// The held particles in order: pins, then each one-particle constraint's
// particle (the constraint and its gradient at s), the first hold of a particle kept.
struct Held {
  int particle;
  const Constraint* hold;
  Eigen::Vector2d gradient;
};

std::vector<Held> heldParticles(const ConstraintList& holds, const Phase& s) {
  std::vector<Held> held;
  std::vector<bool> seen(s.size(), false);
  for (int p = 0; p < s.size(); ++p)
    if (s.inverseMass[p] == 0.0) {
      held.push_back({p, nullptr, Eigen::Vector2d::Zero()});
      seen[p] = true;
    }
  Eigen::Vector2d blocks[2];
  for (const auto& constraint : holds) {
    if (constraint->particles().size() != 1) continue;
    const int p = constraint->particles()[0];
    if (seen[p]) continue;
    ConstraintRow row;
    row.J = &blocks[0];
    row.Jdot = &blocks[1];
    constraint->evaluate(s, row);
    if (blocks[0].squaredNorm() == 0.0) continue;
    held.push_back({p, constraint.get(), blocks[0]});
    seen[p] = true;
  }
  return held;
}

// One bundle's arrays (HangingLines::Bundle), x, xⁿ and w offset to its
// first particle: lane q's particle t at q·laneStride + t·step.
struct BundleArrays {
  int lanes, length, step, laneStride;
  const double *rest, *alphaTilde, *gamma;
  double *lambda, *ux, *uy, *diagonal, *upper, *rhs;
};

// The tridiagonal solve of hanging_lines.h for every lane at once, in four
// phases, row 0 (the holds) filled by the caller; each phase's inner loop
// runs across the lanes, so the lines' eliminations overlap.

// The constraints' rows 1…m: directions, right sides and diagonals.
PARTICLES_VECTOR_CLONES void constraintRows(const BundleArrays& b, const double* xn, const double* x, const double* w,
                                            bool start) {
  const int L = b.lanes;
  for (int t = 0; t < b.length; ++t) {
#pragma omp simd
    for (int q = 0; q < L; ++q) {
      const int pi = q * b.laneStride + t * b.step, pj = pi + b.step;
      const int i = 2 * pi, j = 2 * pj, c = t * L + q, r = c + L;
      const double dx = x[i] - x[j], dy = x[i + 1] - x[j + 1];
      const double squared = dx * dx + dy * dy;
      const double inverse = 1.0 / std::sqrt(squared);
      const double inverseLength = inverse < kLargest ? inverse : kLargest;
      const double ux = dx * inverseLength, uy = dy * inverseLength;
      const double lambda = start ? 0.0 : b.lambda[c];
      b.ux[r] = ux;
      b.uy[r] = uy;
      b.rhs[r] = b.rest[c] - squared * inverseLength - b.alphaTilde[c] * lambda -
                 b.gamma[c] * (ux * (dx - (xn[i] - xn[j])) + uy * (dy - (xn[i + 1] - xn[j + 1])));
      b.diagonal[r] = (1.0 + b.gamma[c]) * (w[pi] + w[pj]) + b.alphaTilde[c];
      b.lambda[c] = lambda;
    }
  }
}

// Forward elimination. Rows r and r + 1 share particle r: the hold's
// gradient at p_0 with +u_0, then −u_{r−1} with u_r; each row's coupling
// carries its own 1 + γ. A zero pivot (nothing can move) eliminates nothing.
PARTICLES_VECTOR_CLONES void eliminate(const BundleArrays& b, const double* w) {
  const int L = b.lanes;
  for (int r = 0; r < b.length; ++r) {
#pragma omp simd
    for (int q = 0; q < L; ++q) {
      const int a = r * L + q, below = a + L;
      const double shared = r == 0 ? w[q * b.laneStride] : -w[q * b.laneStride + r * b.step];
      const double coupling = shared * (b.ux[a] * b.ux[below] + b.uy[a] * b.uy[below]);
      const double up = r == 0 ? coupling : (1.0 + b.gamma[a - L]) * coupling;
      const double lower = (1.0 + b.gamma[a]) * coupling;
      const double pivot = b.diagonal[a] > 0.0 ? b.diagonal[a] : 1.0;
      const double factor = b.diagonal[a] > 0.0 ? lower / pivot : 0.0;
      b.upper[a] = up;
      b.diagonal[below] -= factor * up;
      b.rhs[below] -= factor * b.rhs[a];
    }
  }
}

// Back substitution: Δλ left in rhs (0 on a zero pivot).
PARTICLES_VECTOR_CLONES void substituteBack(const BundleArrays& b) {
  const int L = b.lanes, m = b.length;
  for (int r = m; r >= 0; --r) {
#pragma omp simd
    for (int q = 0; q < L; ++q) {
      const int a = r * L + q;
      const double pivot = b.diagonal[a] > 0.0 ? b.diagonal[a] : 1.0;
      const double known = r == m ? b.rhs[a] : b.rhs[a] - b.upper[a] * b.rhs[a + L];
      b.rhs[a] = b.diagonal[a] > 0.0 ? known / pivot : 0.0;
    }
  }
}

// Δx = W ∇Cᵀ Δλ particle by particle: particle t of a lane takes + its
// constraint's row t + 1 (t < m), and the hold's row 0 for t = 0 or − the
// row t above it; λ += Δλ.
PARTICLES_VECTOR_CLONES void applyDisplacements(const BundleArrays& b, double* x, const double* w) {
  const int L = b.lanes, m = b.length;
  for (int t = 0; t <= m; ++t) {
#pragma omp simd
    for (int q = 0; q < L; ++q) {
      const int p = q * b.laneStride + t * b.step, a = t * L + q;
      double gx = t == 0 ? b.ux[a] * b.rhs[a] : -b.ux[a] * b.rhs[a];
      double gy = t == 0 ? b.uy[a] * b.rhs[a] : -b.uy[a] * b.rhs[a];
      if (t < m) {
        gx += b.ux[a + L] * b.rhs[a + L];
        gy += b.uy[a + L] * b.rhs[a + L];
        b.lambda[a] += b.rhs[a + L];
      }
      x[2 * p] += w[p] * gx;
      x[2 * p + 1] += w[p] * gy;
    }
  }
}

}  // namespace

std::vector<CompliantDistance> HangingLines::build(const std::vector<CompliantDistance>& distances,
                                                   const ConstraintList& holds, const Phase& s) {
  clear();
  const Links links(distances);
  std::vector<bool> used(s.size(), false), onLine(distances.size(), false);
  std::vector<Candidate> taken;
  std::vector<const Constraint*> takenHolds;
  const std::vector<Held> heldList = heldParticles(holds, s);
  std::vector<bool> held(s.size(), false);
  for (const Held& h : heldList) held[static_cast<std::size_t>(h.particle)] = true;
  for (const Held& h : heldList) {
    const Candidate c = bestLine(distances, links, s, held, h.particle, h.gradient);
    if (c.length == 0) continue;
    bool free = true;
    for (int t = 0; t <= c.length; ++t) free = free && !used[c.first + c.step * t];
    if (!free) continue;
    for (int t = 0; t <= c.length; ++t) used[c.first + c.step * t] = true;
    taken.push_back(c);
    takenHolds.push_back(h.hold);
  }

  // Bundles of consecutive lines alike, their constraints row by row.
  for (std::size_t l = 0; l < taken.size();) {
    const Candidate& c = taken[l];
    Bundle b{rest_.size(), l, c.first, 0, c.step, c.length, 1};
    if (l + 1 < taken.size()) b.laneStride = taken[l + 1].first - c.first;
    while (b.lanes < kLanes && l + b.lanes < taken.size() && b.laneStride != 0) {
      const Candidate& next = taken[l + b.lanes];
      if (next.step != c.step || next.length != c.length || next.first != c.first + b.lanes * b.laneStride) break;
      ++b.lanes;
    }
    for (int t = 0; t < b.length; ++t)
      for (int q = 0; q < b.lanes; ++q) {
        const int k = links.at(b.first + q * b.laneStride + t * b.step, b.step);
        onLine[k] = true;
        rest_.push_back(distances[k].rest);
        alphaTilde_.push_back(distances[k].compliance.alphaTilde);
        gamma_.push_back(distances[k].compliance.gamma);
      }
    for (int q = 0; q < b.lanes; ++q) holds_.push_back(takenHolds[l + q]);
    bundles_.push_back(b);
    l += static_cast<std::size_t>(b.lanes);
  }
  lambda_.assign(rest_.size(), 0.0);
  const std::size_t rows = rest_.size() + holds_.size();
  for (auto* scratch : {&ux_, &uy_, &diagonal_, &upper_, &rhs_}) scratch->assign(rows, 0.0);
  std::vector<CompliantDistance> left;
  for (std::size_t k = 0; k < distances.size(); ++k)
    if (!onLine[k]) left.push_back(distances[k]);
  return left;
}

void HangingLines::project(const Eigen::VectorXd& xn, Eigen::VectorXd& x, const Eigen::VectorXd& v,
                           const Eigen::VectorXd& mass, const Eigen::VectorXd& inverseMass, int pass) {
  const Phase s{x, v, mass, inverseMass};
  const int count = static_cast<int>(bundles_.size());
  const int threads = rest_.size() >= kParallelConstraints ? threadCount() : 1;
  parallelFor(count, threads, 1, [&](int b) { solve(static_cast<std::size_t>(b), s, xn.data(), x.data(), pass == 0); });
}

// Row 0 of each lane: the hold's row, C_h and its gradient g at p_0 from the
// constraint's kernel, when it can move p_0; else the row Δλ_h = 0.
void HangingLines::solve(std::size_t index, const Phase& s, const double* xn, double* x, bool start) {
  const Bundle& b = bundles_[index];
  const std::size_t row0 = b.begin + b.line;
  const double* w = s.inverseMass.data();
  for (int q = 0; q < b.lanes; ++q) {
    const std::size_t r = row0 + static_cast<std::size_t>(q);
    const int p0 = b.first + q * b.laneStride;
    ux_[r] = uy_[r] = rhs_[r] = 0.0;
    diagonal_[r] = 1.0;
    const Constraint* hold = holds_[b.line + static_cast<std::size_t>(q)];
    if (hold == nullptr || w[p0] == 0.0) continue;
    Eigen::Vector2d blocks[2];
    ConstraintRow row;
    row.J = &blocks[0];
    row.Jdot = &blocks[1];
    hold->evaluate(s, row);
    if (blocks[0].squaredNorm() == 0.0) continue;
    ux_[r] = blocks[0].x();
    uy_[r] = blocks[0].y();
    diagonal_[r] = w[p0] * blocks[0].squaredNorm();
    rhs_[r] = -row.C;
  }
  const BundleArrays arrays{b.lanes,
                            b.length,
                            b.step,
                            b.laneStride,
                            rest_.data() + b.begin,
                            alphaTilde_.data() + b.begin,
                            gamma_.data() + b.begin,
                            lambda_.data() + b.begin,
                            ux_.data() + row0,
                            uy_.data() + row0,
                            diagonal_.data() + row0,
                            upper_.data() + row0,
                            rhs_.data() + row0};
  const std::size_t at = static_cast<std::size_t>(b.first);
  constraintRows(arrays, xn + 2 * at, x + 2 * at, w + at, start);
  eliminate(arrays, w + at);
  substituteBack(arrays);
  applyDisplacements(arrays, x + 2 * at, w + at);
}

}  // namespace particles
