// Certified safe steps (lab/certify.h): the descending fine scan over an
// ensemble, on made-up survival rules whose answer is known, and on a real
// chain checked by an independent, finer scan below the certified step.
#include <cmath>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "lab/certify.h"
#include "lab/chain.h"
#include "lab/lab.h"

using namespace lab;

namespace {

Probe survivedProbe(double duration) {
  Probe p;
  p.time = duration;
  return p;
}

Probe failedProbe(double time) {
  Probe p;
  p.failed = true;
  p.failure = Failure::EnergyGrowth;
  p.time = time;
  return p;
}

}  // namespace

// Every member fails above 0.1; member 7 alone fails at one grid dt near
// 0.06, far below the rest: the certificate sits below that lone failure,
// and the scan goes a whole decade further down.
TEST(Certify, ALoneFailureOnOneMemberSetsTheCertifiedStep) {
  const double duration = 10.0;
  std::map<double, std::set<int>> membersRun;
  const auto run = [&](double dt, int member) -> std::optional<Probe> {
    membersRun[dt].insert(member);
    if (dt > 0.1) return failedProbe(1.0);
    if (member == 7 && dt > 0.0597 && dt < 0.0603) return failedProbe(8.0);
    return survivedProbe(duration);
  };
  CertifySettings settings;
  const std::optional<Certificate> c = certifySafeStep(run, duration, settings);
  ASSERT_TRUE(c);
  EXPECT_GT(c->smallestFailureDt, 0.0597);
  EXPECT_LT(c->smallestFailureDt, 0.0603);
  EXPECT_LT(c->safeDt, c->smallestFailureDt);
  EXPECT_GT(c->safeDt * 1.011, c->smallestFailureDt);
  EXPECT_TRUE(c->fullDecades);
  EXPECT_LT(c->lowest, c->smallestFailureDt / 10.0);
  EXPECT_GT(c->lowest * 1.011, c->smallestFailureDt / 10.0);
  // Every member ran at every dt at and below the certified one.
  for (const auto& [dt, members] : membersRun) {
    if (dt <= c->safeDt) {
      EXPECT_EQ(members.size(), 10u) << dt;
    }
  }
  // The bands: the lone failure in the first, the 0.1 edge inside the last.
  ASSERT_EQ(c->bands.size(), 4u);
  EXPECT_EQ(c->bands[0].failed, 1);
  EXPECT_GT(c->bands[0].points, 5);
  EXPECT_EQ(c->bands[1].failed, 0);
  EXPECT_GT(c->bands[3].failed, 0);
  EXPECT_LT(c->bands[3].failed, c->bands[3].points);
  EXPECT_EQ(certifiedText(*c), output::formatGeneral(c->safeDt, 4));
}

TEST(Certify, NothingSurvivingDownToTheFloorCertifiesNothing) {
  CertifySettings settings;
  settings.top = 0.1;
  settings.floor = 0.01;
  const auto c = certifySafeStep([](double, int) -> std::optional<Probe> { return failedProbe(0.5); }, 5.0, settings);
  ASSERT_TRUE(c);
  EXPECT_TRUE(c->belowFloor());
  EXPECT_FALSE(c->fullDecades);
  EXPECT_GE(c->lowest, 0.01);
  EXPECT_LT(c->lowest, 0.0102);
  EXPECT_EQ(c->runs, c->points);  // one member per failing dt
  EXPECT_EQ(certifiedText(*c).rfind("< ", 0), 0u);
}

TEST(Certify, AScanThatReachesTheFloorBeforeADecadeIsMarked) {
  // Failures above 0.02, survival below: a decade below the failure (0.002)
  // lies under the floor 0.005, so the certificate covers [0.005, 0.02) only.
  CertifySettings settings;
  settings.top = 0.1;
  settings.floor = 0.005;
  const double duration = 2.0;
  const auto c = certifySafeStep(
      [&](double dt, int) -> std::optional<Probe> { return dt > 0.02 ? failedProbe(0.5) : survivedProbe(duration); },
      duration, settings);
  ASSERT_TRUE(c);
  EXPECT_FALSE(c->fullDecades);
  EXPECT_FALSE(c->belowFloor());
  EXPECT_LE(c->safeDt, 0.02);
  EXPECT_GT(c->safeDt * 1.011, 0.02);
  EXPECT_EQ(certifiedText(*c), output::formatGeneral(c->safeDt, 4) + " †");
}

TEST(Certify, NothingFailingIsALowerBoundAtTheTop) {
  CertifySettings settings;
  settings.top = 0.4;
  settings.members = 10;
  const double duration = 3.0;
  const auto c =
      certifySafeStep([&](double, int) -> std::optional<Probe> { return survivedProbe(duration); }, duration, settings);
  ASSERT_TRUE(c);
  EXPECT_TRUE(c->aboveGrid());
  EXPECT_NEAR(c->safeDt, 0.4, 0.4 * 0.011);
  EXPECT_TRUE(c->fullDecades);
  EXPECT_LT(c->lowest, 0.04);
  EXPECT_EQ(c->runs, 10L * c->points);
  EXPECT_EQ(certifiedText(*c).rfind("≥ ", 0), 0u);
}

TEST(Certify, AnInterruptedRunEndsTheScanWithoutACertificate) {
  int calls = 0;
  const auto c = certifySafeStep(
      [&](double, int) -> std::optional<Probe> {
        if (++calls > 5) return std::nullopt;
        return survivedProbe(1.0);
      },
      1.0, CertifySettings{});
  EXPECT_FALSE(c);
}

// A real chain: symplectic Euler on the seed 3-chain for 10 s. A finer scan
// (0.25% apart, between the 1% grid's points) of the decade below the
// certified step, on the same ten starts, finds no failure; the smallest
// failure the certification reported fails again when rerun.
TEST(Certify, AFinerScanBelowTheCertifiedStepFindsNoFailure) {
  const double duration = 10.0;
  const FailureCriterion criterion;
  const auto build = [] { return buildChain({3}); };
  const auto run = [&](double dt, int member) {
    return runMember(build, "symplectic-euler", dt, member, duration, criterion);
  };
  CertifySettings settings;
  settings.top = 0.3;
  const auto c = certifySafeStep(run, duration, settings);
  ASSERT_TRUE(c);
  ASSERT_FALSE(c->aboveGrid());
  ASSERT_FALSE(c->belowFloor());
  EXPECT_TRUE(c->fullDecades);
  bool failedAgain = false;
  for (int member = 0; member < settings.members && !failedAgain; ++member)
    failedAgain = !run(c->smallestFailureDt, member)->survives(duration, c->smallestFailureDt);
  EXPECT_TRUE(failedAgain) << c->smallestFailureDt;
  for (double dt = c->safeDt / 1.0025; dt > c->safeDt / 10.0; dt /= 1.0025)
    for (int member = 0; member < settings.members; ++member)
      ASSERT_TRUE(run(dt, member)->survives(duration, dt)) << "dt " << dt << " member " << member;
}
