#include "xpbd/hanging_lines.h"

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
constexpr int kShortest = 2;  // constraints on a line
constexpr int kLanes = 8;     // lines solved side by side

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
// runs across the lanes, so the lines' eliminations overlap. kLaneStride 1:
// neighbouring lines (a grid's columns), whose particles the loops read as
// pairs of doubles in a row; 0: any lane stride, read one by one. The loops hold
// no branch (a row that differs, the first or the last, has a loop of its
// own) and every quotient is taken before it is chosen, so that they run as
// vector instructions.

// The constraints' rows 1…m: directions, right sides and diagonals.
template <int kLaneStride>
PARTICLES_VECTOR_CLONES void constraintRows(const BundleArrays& b, const double* xn, const double* x,
                                            const double* w) {
  const int L = b.lanes, step = b.step, ls = kLaneStride > 0 ? kLaneStride : b.laneStride;
  const double *rest = b.rest, *alphaTilde = b.alphaTilde, *gamma = b.gamma, *lambda = b.lambda;
  double *ux = b.ux, *uy = b.uy, *rhs = b.rhs, *diagonal = b.diagonal;
  for (int t = 0; t < b.length; ++t) {
#pragma omp simd
    for (int q = 0; q < L; ++q) {
      const int pi = q * ls + t * step, pj = pi + step;
      const int i = 2 * pi, j = 2 * pj, c = t * L + q, r = c + L;
      const double dx = x[i] - x[j], dy = x[i + 1] - x[j + 1];
      const double squared = dx * dx + dy * dy;
      const double inverse = 1.0 / std::sqrt(squared);
      const double inverseLength = inverse < kLargest ? inverse : kLargest;
      const double uxt = dx * inverseLength, uyt = dy * inverseLength;
      ux[r] = uxt;
      uy[r] = uyt;
      rhs[r] = rest[c] - squared * inverseLength - alphaTilde[c] * lambda[c] -
               gamma[c] * (uxt * (dx - (xn[i] - xn[j])) + uyt * (dy - (xn[i + 1] - xn[j + 1])));
      diagonal[r] = (1.0 + gamma[c]) * (w[pi] + w[pj]) + alphaTilde[c];
    }
  }
}

// Rows a and a + L of a lane coupled by `coupling` (row a's γ factor
// `upFactor`, row a + L's its own): the upper band, and row a eliminated from
// row a + L. A zero pivot (nothing can move) eliminates nothing.
inline void eliminateRow(double* diagonal, double* upper, double* rhs, int a, int L, double coupling,
                         double upFactor, double downFactor) {
  const double up = upFactor * coupling;
  const double pivot = diagonal[a] > 0.0 ? diagonal[a] : 1.0;
  const double quotient = downFactor * coupling / pivot;
  const double factor = diagonal[a] > 0.0 ? quotient : 0.0;
  upper[a] = up;
  diagonal[a + L] -= factor * up;
  rhs[a + L] -= factor * rhs[a];
}

// Forward elimination. Rows r and r + 1 share particle r: the hold's
// gradient at p_0 with +u_0, then −u_{r−1} with u_r; each row's coupling
// carries its own 1 + γ (the hold's none).
template <int kLaneStride>
PARTICLES_VECTOR_CLONES void eliminate(const BundleArrays& b, const double* w) {
  const int L = b.lanes, step = b.step, ls = kLaneStride > 0 ? kLaneStride : b.laneStride;
  const double* gamma = b.gamma;
  double *ux = b.ux, *uy = b.uy, *diagonal = b.diagonal, *upper = b.upper, *rhs = b.rhs;
#pragma omp simd
  for (int q = 0; q < L; ++q)
    eliminateRow(diagonal, upper, rhs, q, L, w[q * ls] * (ux[q] * ux[q + L] + uy[q] * uy[q + L]), 1.0,
                 1.0 + gamma[q]);
  for (int r = 1; r < b.length; ++r) {
#pragma omp simd
    for (int q = 0; q < L; ++q) {
      const int a = r * L + q;
      const double coupling = -w[q * ls + r * step] * (ux[a] * ux[a + L] + uy[a] * uy[a + L]);
      eliminateRow(diagonal, upper, rhs, a, L, coupling, 1.0 + gamma[a - L], 1.0 + gamma[a]);
    }
  }
}

// Back substitution: Δλ left in rhs (0 on a zero pivot).
PARTICLES_VECTOR_CLONES void substituteBack(const BundleArrays& b) {
  const int L = b.lanes, m = b.length;
  double *diagonal = b.diagonal, *upper = b.upper, *rhs = b.rhs;
  auto solved = [&](int a, double known) {
    const double pivot = diagonal[a] > 0.0 ? diagonal[a] : 1.0;
    const double quotient = known / pivot;
    rhs[a] = diagonal[a] > 0.0 ? quotient : 0.0;
  };
#pragma omp simd
  for (int q = 0; q < L; ++q) solved(m * L + q, rhs[m * L + q]);
  for (int r = m - 1; r >= 0; --r) {
#pragma omp simd
    for (int q = 0; q < L; ++q) {
      const int a = r * L + q;
      solved(a, rhs[a] - upper[a] * rhs[a + L]);
    }
  }
}

// Δx = W ∇Cᵀ Δλ particle by particle: particle t of a lane takes + the hold's
// row 0 (t = 0) or − the row t above it (t ≥ 1), and + its constraint's row
// t + 1 (t < m); λ += Δλ.
template <int kLaneStride>
PARTICLES_VECTOR_CLONES void applyDisplacements(const BundleArrays& b, double* x, const double* w) {
  const int L = b.lanes, m = b.length, step = b.step, ls = kLaneStride > 0 ? kLaneStride : b.laneStride;
  const double *ux = b.ux, *uy = b.uy, *rhs = b.rhs;
  double* lambda = b.lambda;
  auto move = [&](int p, double gx, double gy) {
    x[2 * p] += w[p] * gx;
    x[2 * p + 1] += w[p] * gy;
  };
#pragma omp simd
  for (int q = 0; q < L; ++q) {
    lambda[q] += rhs[q + L];
    move(q * ls, ux[q] * rhs[q] + ux[q + L] * rhs[q + L], uy[q] * rhs[q] + uy[q + L] * rhs[q + L]);
  }
  for (int t = 1; t < m; ++t) {
#pragma omp simd
    for (int q = 0; q < L; ++q) {
      const int a = t * L + q;
      lambda[a] += rhs[a + L];
      move(q * ls + t * step, ux[a + L] * rhs[a + L] - ux[a] * rhs[a], uy[a + L] * rhs[a + L] - uy[a] * rhs[a]);
    }
  }
#pragma omp simd
  for (int q = 0; q < L; ++q) {
    const int a = m * L + q;
    move(q * ls + m * step, -ux[a] * rhs[a], -uy[a] * rhs[a]);
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
  if (start) std::fill_n(arrays.lambda, static_cast<std::size_t>(b.lanes) * static_cast<std::size_t>(b.length), 0.0);
  if (b.laneStride == 1) {
    constraintRows<1>(arrays, xn + 2 * at, x + 2 * at, w + at);
    eliminate<1>(arrays, w + at);
    substituteBack(arrays);
    applyDisplacements<1>(arrays, x + 2 * at, w + at);
  } else {
    constraintRows<0>(arrays, xn + 2 * at, x + 2 * at, w + at);
    eliminate<0>(arrays, w + at);
    substituteBack(arrays);
    applyDisplacements<0>(arrays, x + 2 * at, w + at);
  }
}

}  // namespace particles
