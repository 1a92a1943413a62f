#pragma once
// What a finite set of runs says about the probability that a run fails.
// Survival of a chaotic scene is not a property of a step size: it depends on
// the start and on dt in ways no scan resolves. A scan that ran N runs (starts
// × grid steps) and saw k failures supports a statement about the per-run
// failure probability p of a run drawn like them, at a confidence level:
//
//   upper bound p_u (Clopper–Pearson, one-sided): P(X ≤ k | N, p_u) = 1 − c,
//     i.e. p_u = the c-quantile of Beta(k + 1, N − k); with k = 0 this is
//     1 − (1 − c)^(1/N) ≈ 3/N at c = 95% ("the rule of three");
//   lower bound p_l: P(X ≥ k | N, p_l) = 1 − c, the (1 − c)-quantile of
//     Beta(k, N − k + 1); 0 when k = 0.
//
// The runs are treated as independent draws: the starts are pseudo-random
// perturbations (lab_scene.h perturbStart) and the grid steps a regular
// sample of the range the statement is about.
#include <string>

namespace lab {

inline constexpr double kBoundConfidence = 0.95;

// Clopper–Pearson upper bound on p from `failures` in `runs` (1 when runs is 0).
double failureUpperBound(long failures, long runs, double confidence = kBoundConfidence);

// Clopper–Pearson lower bound on p (0 when failures is 0).
double failureLowerBound(long failures, long runs, double confidence = kBoundConfidence);

// The fewest runs without a failure whose upper bound is at most `bound`:
// ceil(ln(1 − c) / ln(1 − bound)). Throws std::invalid_argument unless 0 < bound < 1.
long runsForBound(double bound, double confidence = kBoundConfidence);

// Failures among runs, and what they support.
struct FailureCount {
  long runs = 0, failures = 0;
  double fraction() const { return runs > 0 ? static_cast<double>(failures) / runs : 0.0; }
  double upperBound() const { return failureUpperBound(failures, runs); }
  FailureCount& operator+=(const FailureCount& other) {
    runs += other.runs, failures += other.failures;
    return *this;
  }
};
template <class Io>
void fields(Io& io, FailureCount& c) {
  io("runs", c.runs), io("failures", c.failures);
}

// "p ≤ 1.3e-3" (the upper bound, 2 significant digits).
std::string boundText(const FailureCount& count);
// "0/2320" or "3/700".
std::string countText(const FailureCount& count);

}  // namespace lab
