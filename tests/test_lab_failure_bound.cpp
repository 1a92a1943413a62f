// The failure bound's arithmetic (lab/failure_bound.h): Clopper–Pearson
// bounds against their defining identities, closed forms and tabulated values.
#include <cmath>

#include <gtest/gtest.h>

#include "lab/failure_bound.h"

using namespace lab;

namespace {

// P(X ≤ k | n, p) by summing the binomial terms in logs.
double binomialCdf(long k, long n, double p) {
  double sum = 0.0;
  for (long i = 0; i <= k; ++i)
    sum += std::exp(std::lgamma(n + 1.0) - std::lgamma(i + 1.0) - std::lgamma(n - i + 1.0) + i * std::log(p) +
                    (n - i) * std::log1p(-p));
  return sum;
}

}  // namespace

TEST(FailureBound, NoFailureIsTheRuleOfThree) {
  for (long n : {10L, 300L, 2320L, 3000L, 100000L}) {
    const double p = failureUpperBound(0, n);
    EXPECT_NEAR(p, 1.0 - std::pow(0.05, 1.0 / n), 1e-15) << n;
    EXPECT_NEAR(std::pow(1.0 - p, n), 0.05, 1e-12) << n;  // P(no failure | p) = 5%
  }
  EXPECT_NEAR(failureUpperBound(0, 3000), 9.98e-4, 1e-6);
  EXPECT_NEAR(failureUpperBound(0, 100000) * 100000, 3.0, 0.01);  // ≈ 3/N
  EXPECT_EQ(failureUpperBound(0, 0), 1.0);
  EXPECT_EQ(failureLowerBound(0, 50), 0.0);
}

TEST(FailureBound, UpperAndLowerBoundsMeetTheirIdentities) {
  // One-sided 95%: P(X ≤ k | n, p_u) = 0.05 and P(X ≥ k | n, p_l) = 0.05.
  for (auto [k, n] : {std::pair{1L, 10L}, {5L, 5838L}, {2L, 700L}, {30L, 30L - 1 + 12}, {1L, 12922L}}) {
    const double upper = failureUpperBound(k, n), lower = failureLowerBound(k, n);
    EXPECT_NEAR(binomialCdf(k, n, upper), 0.05, 1e-9) << k << "/" << n;
    EXPECT_NEAR(1.0 - binomialCdf(k - 1, n, lower), 0.05, 1e-9) << k << "/" << n;
    EXPECT_LT(lower, static_cast<double>(k) / n);
    EXPECT_GT(upper, static_cast<double>(k) / n);
  }
  // Tabulated: 1 failure in 10, one-sided 95% (two-sided 90%) interval (0.0051, 0.3942).
  EXPECT_NEAR(failureUpperBound(1, 10), 0.3942, 1e-4);
  EXPECT_NEAR(failureLowerBound(1, 10), 0.0051, 1e-4);
  EXPECT_EQ(failureUpperBound(7, 7), 1.0);
}

TEST(FailureBound, RunsForABoundReachIt) {
  EXPECT_EQ(runsForBound(1e-3), 2995);
  for (double bound : {0.3, 1e-2, 1e-3, 1e-4}) {
    const long n = runsForBound(bound);
    EXPECT_LE(failureUpperBound(0, n), bound) << bound;
    EXPECT_GT(failureUpperBound(0, n - 1), bound) << bound;
  }
  EXPECT_THROW(runsForBound(0.0), std::invalid_argument);
  EXPECT_THROW(runsForBound(1.0), std::invalid_argument);
  EXPECT_THROW(failureUpperBound(3, 2), std::invalid_argument);
  EXPECT_THROW(failureUpperBound(0, 10, 1.0), std::invalid_argument);
}

TEST(FailureBound, CountsAddAndPrint) {
  FailureCount count{700, 2};
  count += FailureCount{300, 0};
  EXPECT_EQ(count.runs, 1000);
  EXPECT_EQ(count.failures, 2);
  EXPECT_EQ(countText(count), "2/1000");
  EXPECT_EQ(boundText(FailureCount{2320, 0}), "p ≤ 0.0013");
}
