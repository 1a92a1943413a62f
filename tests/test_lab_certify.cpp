// Certified safe steps (lab/certify.h): the descending fine scan over an
// ensemble, on made-up survival rules whose answer is known, and on a real
// chain checked by an independent, finer scan below the certified step.
#include <cmath>
#include <cstdint>
#include <algorithm>
#include <fstream>
#include <functional>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "lab/certify.h"
#include "lab/chain.h"
#include "lab/lab.h"
#include "output/csv_writer.h"

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
  EXPECT_LT(c->survivedDt, c->smallestFailureDt);
  EXPECT_GT(c->survivedDt * 1.011, c->smallestFailureDt);
  EXPECT_TRUE(c->fullDecades);
  EXPECT_LT(c->lowest, c->smallestFailureDt / 10.0);
  EXPECT_GT(c->lowest * 1.011, c->smallestFailureDt / 10.0);
  // Every member ran at every dt at and below the certified one.
  for (const auto& [dt, members] : membersRun) {
    if (dt <= c->survivedDt) {
      EXPECT_EQ(members.size(), 10u) << dt;
    }
  }
  // The bands: none below; the lone failure, one run of ten, in the first
  // above; the 0.1 edge inside the last.
  ASSERT_EQ(c->bands.size(), 6u);
  EXPECT_EQ(c->bands[0].runs.failures + c->bands[1].runs.failures, 0);
  EXPECT_GT(c->bands[0].runs.runs, 500);
  EXPECT_EQ(c->bands[2].failedPoints, 1);
  EXPECT_EQ(c->bands[2].runs.failures, 1);
  EXPECT_GT(c->bands[2].points, 5);
  EXPECT_EQ(c->bands[3].failedPoints, 0);
  EXPECT_GT(c->bands[5].runs.failures, 0);
  EXPECT_LT(c->bands[5].failedPoints, c->bands[5].points);
  // The bound: every run at and below the survived dt, none failing.
  EXPECT_EQ(c->atAndBelow.failures, 0);
  EXPECT_NEAR(c->bound(), 3.0 / c->atAndBelow.runs, 0.1 * 3.0 / c->atAndBelow.runs);
  EXPECT_EQ(survivedText(*c), output::formatGeneral(c->survivedDt, 4));
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
  EXPECT_EQ(survivedText(*c).rfind("< ", 0), 0u);
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
  EXPECT_LE(c->survivedDt, 0.02);
  EXPECT_GT(c->survivedDt * 1.011, 0.02);
  EXPECT_EQ(survivedText(*c), output::formatGeneral(c->survivedDt, 4) + " †");
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
  EXPECT_NEAR(c->survivedDt, 0.4, 0.4 * 0.011);
  EXPECT_TRUE(c->fullDecades);
  EXPECT_LT(c->lowest, 0.04);
  EXPECT_EQ(c->runs, 10L * c->points);
  EXPECT_EQ(survivedText(*c).rfind("≥ ", 0), 0u);
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

// A made-up survival rule: every start fails above 0.1; below it each run
// fails with probability 1e-3, independently (a hash of dt and start). Then
// no step is safe, and the bound the certificate states for its survived step
// must contain the true failure rate.
TEST(Certify, ABoundContainsTheFailureRateOfARandomRule) {
  const double duration = 5.0, rate = 1e-3;
  const auto uniform = [](double dt, int member) {
    std::uint64_t h = std::hash<double>{}(dt) ^ (0x9e3779b97f4a7c15ULL * static_cast<std::uint64_t>(member + 1));
    h ^= h >> 33, h *= 0xff51afd7ed558ccdULL, h ^= h >> 33, h *= 0xc4ceb9fe1a85ec53ULL, h ^= h >> 33;
    return static_cast<double>(h >> 11) / 9007199254740992.0;
  };
  long failures = 0, runs = 0;
  const auto run = [&](double dt, int member) -> std::optional<Probe> {
    if (dt > 0.1) return failedProbe(1.0);
    ++runs;
    const bool fails = uniform(dt, member) < rate;
    failures += fails;
    return fails ? failedProbe(2.0) : survivedProbe(duration);
  };
  CertifySettings settings;
  settings.top = 0.2;
  const auto c = certifySafeStep(run, duration, settings);
  ASSERT_TRUE(c);
  ASSERT_GT(failures, 0) << "the rule never fired below 0.1: no test";
  EXPECT_GE(c->bound(), rate);
  EXPECT_EQ(c->atAndBelow.failures, 0);
  EXPECT_NEAR(c->bound(), failureUpperBound(0, c->atAndBelow.runs), 1e-15);
  // The measured fraction over every run below 0.1 is near the rate.
  EXPECT_GT(failureUpperBound(failures, runs), rate);
  EXPECT_LT(failureLowerBound(failures, runs), rate);
}

// Above the survived dt every start is run up to the last band: the bands
// count runs, and a band's failed runs are the rule's.
TEST(Certify, TheBandsAboveCountEveryStart) {
  const double duration = 3.0;
  // Starts 0-4 fail above 0.05, starts 5-9 above 0.08: half the runs of (0.05, 0.08] fail.
  const auto run = [&](double dt, int member) -> std::optional<Probe> {
    const double edge = member < 5 ? 0.05 : 0.08;
    return dt > edge ? failedProbe(1.0) : survivedProbe(duration);
  };
  CertifySettings settings;
  settings.top = 0.2;
  const auto c = certifySafeStep(run, duration, settings);
  ASSERT_TRUE(c);
  EXPECT_LE(c->survivedDt, 0.05);
  EXPECT_GT(c->survivedDt * 1.011, 0.05);
  ASSERT_EQ(c->bands.size(), settings.bandEdges.size() - 1);
  for (const FailureBand& band : c->bands) {
    EXPECT_EQ(band.runs.runs, static_cast<long>(band.points) * settings.members) << band.lo;
    if (band.hi <= 1.0) {
      EXPECT_EQ(band.runs.failures, 0) << band.lo;
    }
  }
  // (1, 1.1] × 0.05 lies inside (0.05, 0.08]: half its runs fail.
  EXPECT_EQ(2 * c->bands[2].runs.failures, c->bands[2].runs.runs);
  EXPECT_EQ(c->bands[2].failedPoints, c->bands[2].points);
}

// Starts for a bound: with the 1% grid's 233 points a decade, a bound of 1e-3
// needs 2995 runs, 13 starts; a looser one keeps the settings' 10.
TEST(Certify, MembersForABoundReachItsRuns) {
  CertifySettings settings;
  EXPECT_EQ(membersForBound(settings, 1e-3), 13);
  EXPECT_EQ(membersForBound(settings, 1e-2), settings.members);
  const int members = membersForBound(settings, 2e-4);
  EXPECT_GE(members * 232.5, runsForBound(2e-4));
  EXPECT_LT((members - 1) * 232.5, runsForBound(2e-4));
}

// A real chain: symplectic Euler on the seed 3-chain for 10 s. A finer scan
// (0.25% apart, between the 1% grid's points) of the decade below the
// survived step, on ten other starts, is consistent with the certificate's
// bound (its failures' lower bound is below it); the smallest failure the
// scan reported fails again when rerun.
TEST(Certify, AFinerScanOnOtherStartsFallsWithinTheBound) {
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
  EXPECT_GE(c->atAndBelow.runs, 2000);
  bool failedAgain = false;
  for (int member = 0; member < settings.members && !failedAgain; ++member)
    failedAgain = !run(c->smallestFailureDt, member)->survives(duration, c->smallestFailureDt);
  EXPECT_TRUE(failedAgain) << c->smallestFailureDt;
  FailureCount finer;
  for (double dt = c->survivedDt / 1.0025; dt > c->survivedDt / 10.0; dt /= 1.0025)
    for (int member = settings.members; member < 2 * settings.members; ++member) {
      ++finer.runs;
      finer.failures += !run(dt, member)->survives(duration, dt);
    }
  EXPECT_LE(failureLowerBound(finer.failures, finer.runs), c->bound())
      << finer.failures << " of " << finer.runs << " failed";
}

namespace {

// The rows of the report's stability_certified.csv, by column name.
std::vector<std::map<std::string, std::string>> reportRows(const std::string& file) {
  std::ifstream in(std::string(REPORT_DATA_DIR) + "/" + file);
  std::vector<std::map<std::string, std::string>> rows;
  std::string line;
  std::vector<std::string> header;
  if (std::getline(in, line)) header = output::csvSplit(line);
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = output::csvSplit(line);
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < header.size() && k < cells.size(); ++k) row[header[k]] = cells[k];
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

// Table 2's bounds against an independent scan in quick form: for the three
// entries where a finer scan of 21 starts once found failures below the step
// then called certified (rk4 cl 12, verlet cl 6, midpoint cl 24), one new
// start at each dt of a 0.25% grid over [0.5, 1] × the survived dt, none of
// the ten starts the report ran. The failures seen must be consistent with
// the report's bound (their 95% lower bound below it); above the step, on
// (1, 1.5] ×, the same scan does meet failures, so it can see them.
TEST(Certify, TableTwosBoundsHoldOnAnIndependentScan) {
  const std::vector<std::pair<std::string, int>> entries = {{"rk4", 12}, {"verlet", 6}, {"midpoint", 24}};
  const auto rows = reportRows("stability_certified.csv");
  ASSERT_FALSE(rows.empty()) << "no report/data/stability_certified.csv";
  for (const auto& [integrator, length] : entries) {
    const auto row = std::find_if(rows.begin(), rows.end(), [&](const auto& r) {
      return r.count("integrator") && r.at("integrator") == integrator && r.at("chain_length") == std::to_string(length);
    });
    ASSERT_NE(row, rows.end()) << integrator << " cl " << length;
    ASSERT_TRUE(row->count("survived_dt") && row->count("failure_bound")) << "the report's data predates the bounds";
    const double survived = std::stod(row->at("survived_dt")), bound = std::stod(row->at("failure_bound"));
    const double duration = std::stod(row->at("duration"));
    ASSERT_GT(survived, 0.0);
    const auto build = [length = length] { return buildChain({length}); };
    FailureCount below, above;
    int start = 100;  // the report's starts are 0-9
    for (double dt = survived; dt >= 0.5 * survived; dt /= 1.0025, ++start) {
      ++below.runs;
      below.failures += !runMember(build, integrator, dt, start, duration, FailureCriterion{})->survives(duration, dt);
    }
    for (double dt = survived * 1.0025; dt <= 1.5 * survived; dt *= 1.0025, ++start) {
      ++above.runs;
      above.failures += !runMember(build, integrator, dt, start, duration, FailureCriterion{})->survives(duration, dt);
    }
    EXPECT_LE(failureLowerBound(below.failures, below.runs), bound)
        << integrator << " cl " << length << ": " << countText(below) << " failed below " << survived;
    EXPECT_GT(above.failures, 0) << integrator << " cl " << length << ": " << countText(above)
                                 << " above: the scan sees no failure anywhere";
  }
}
