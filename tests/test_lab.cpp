// The laboratory: the explosion detector, the report renderer, and each
// experiment's --quick mode producing CSVs with the expected columns and
// sane values.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include <gtest/gtest.h>

#include "particles/constants.h"
#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/lab_scene.h"
#include "lab/parallel.h"
#include "lab/scan.h"
#include "particles/constraints/circular_wire.h"
#include "output/csv_writer.h"
#include "output/format_number.h"
#include "lab/render.h"
#include "lab/values.h"
#include "particles/integrator.h"
#include "test_support.h"

using namespace lab;

namespace {

// A CSV as rows of column name → cell.
using Table = std::vector<std::map<std::string, std::string>>;

Table readCsv(const std::string& path, const std::vector<std::string>& expectedColumns) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << "missing " << path;
  std::string line;
  std::getline(in, line);
  std::vector<std::string> columns;
  std::stringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');) columns.push_back(cell);
  EXPECT_EQ(columns, expectedColumns) << path;
  Table rows;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::map<std::string, std::string> row;
    std::size_t k = 0;
    for (std::string cell; std::getline(s, cell, ',') && k < columns.size(); ++k) row[columns[k]] = cell;
    EXPECT_EQ(k, columns.size()) << path << ": short row " << line;
    rows.push_back(row);
  }
  return rows;
}

LabOptions quickOptions(const std::string& name) {
  LabOptions o;
  o.quick = true;
  o.outDir = (std::filesystem::temp_directory_path() / ("particle-lab-test-" + name)).string();
  std::filesystem::remove_all(o.outDir);
  return o;
}

}  // namespace

TEST(Failure, FlagsADivergingRunAndPassesAStableOne) {
  scenes::Scene unstable = buildChain({12});
  auto euler = particles::makeIntegrator("euler");
  const RunResult bad = simulate(unstable, *euler, 0.2, 20.0);
  EXPECT_TRUE(bad.failed);
  EXPECT_FALSE(bad.reason.empty());
  EXPECT_LT(bad.time, 20.0);

  scenes::Scene stable = buildChain({12});
  auto rk4 = particles::makeIntegrator("rk4");
  const RunResult good = simulate(stable, *rk4, 0.01, 2.0);
  EXPECT_FALSE(good.failed) << good.reason;
  EXPECT_EQ(good.steps, 200);
  EXPECT_LT(good.maxRelativeStretch, 0.01);
}

TEST(Failure, EachCriterionTriggersOnItsOwn) {
  scenes::Scene chain = buildChain({6});
  const int tip = chain.system->size() - 1;
  chain.system->setVelocity(tip, Eigen::Vector2d(chain.system->velocity(tip).x(), std::nan("")));
  auto rk4 = particles::makeIntegrator("rk4");
  const RunResult nonFinite = simulate(chain, *rk4, 0.01, 0.1);
  EXPECT_EQ(nonFinite.failure, Failure::NonFinite);
  EXPECT_TRUE(nonFinite.blewUp());

  scenes::Scene stretched = buildChain({6});
  const int stretchedTip = stretched.system->size() - 1;
  stretched.system->setPosition(stretchedTip, stretched.system->position(stretchedTip) + Eigen::Vector2d(1.0, 0.0));  // pull the tip off
  const RunResult constraint = simulate(stretched, *rk4, 0.01, 0.1);
  EXPECT_EQ(constraint.reason, "constraint");
  EXPECT_FALSE(constraint.blewUp());  // a violated rod is reported apart from a blow-up

  // Explicit Euler pumps energy into an undamped oscillator: (1 + ω²h²) per step.
  scenes::Scene oscillator = scenes::buildScene("oscillator", {{"damping", "0"}});
  FailureCriterion energyOnly;
  energyOnly.energyRiseFraction = 0.01;
  auto euler = particles::makeIntegrator("euler");
  const RunResult energy = simulate(oscillator, *euler, 0.05, 100.0, energyOnly);
  EXPECT_EQ(energy.failure, Failure::EnergyGrowth);
  EXPECT_GT(energy.maxEnergyRise, 0.01);
  scenes::Scene calm = scenes::buildScene("oscillator", {{"damping", "0"}});
  auto rk4Again = particles::makeIntegrator("rk4");
  EXPECT_FALSE(simulate(calm, *rk4Again, 0.01, 10.0, energyOnly).failed);
}

// E_s of the test chain is its potential drop from horizontal to hanging
// straight: Σ_{i=1}^{cl−1} m g (i L) = g m L cl(cl−1)/2.
TEST(Failure, ReleasableEnergyOfTheTestChainIsItsDropToHangingStraight) {
  for (int cl : {2, 6, 24}) {
    scenes::Scene chain = buildChain({cl});
    const auto& s = *chain.system;
    const double m = s.masses()[1], g = gravityMagnitude(s), L = chainRodLength(chain);
    EXPECT_NEAR(releasableEnergy(s), g * m * L * cl * (cl - 1) / 2.0, 1e-12) << "cl " << cl;
  }
  // A bead on a circular wire can fall to the wire's lowest point: m g L (1 − cos θ₀).
  for (const char* preset : {scenes::kSeedPreset, "default"}) {
    scenes::Scene pendulum = scenes::buildScene("pendulum", {{"angle", "60"}}, preset);
    const auto& p = *pendulum.system;
    const auto* wire = dynamic_cast<const particles::CircularWireConstraint*>(p.constraints().at(0).get());
    ASSERT_NE(wire, nullptr);
    EXPECT_NEAR(releasableEnergy(p), p.masses()[0] * gravityMagnitude(p) * wire->radius() * (1 - std::cos(particles::kPi / 3)),
                1e-9 * releasableEnergy(p))
        << preset;
  }
}

// A survival function of dt that is not monotone: it survives below 0.071,
// fails in [0.072, 0.086), survives again in [0.087, 0.11] and fails above —
// the RK4 24-chain of the review. Bisection between 0.001 and 0.5 lands in
// the island; the scan finds the true safe boundary.
TEST(Scan, FindsTheSafeBoundaryOfANonMonotoneSurvivalWhereBisectionDoesNot) {
  auto survives = [](double dt) { return dt < 0.0715 || (dt >= 0.087 && dt <= 0.11); };
  const std::vector<double> grid = stepGrid(0.001, 0.5);
  ASSERT_GT(grid.size(), 100u);
  for (std::size_t k = 1; k < grid.size(); ++k) EXPECT_LE(grid[k] / grid[k - 1], 1.05);
  EXPECT_NE(std::find(grid.begin(), grid.end(), 0.05), grid.end());
  EXPECT_NE(std::find(grid.begin(), grid.end(), 0.1), grid.end());
  EXPECT_NE(std::find(grid.begin(), grid.end(), 0.2), grid.end());

  // Log bisection as the lab used to do it: survives(mid) moves lo up.
  double lo = 0.001, hi = 0.5;
  for (int k = 0; k < 12; ++k) {
    const double mid = std::sqrt(lo * hi);
    (survives(mid) ? lo : hi) = mid;
  }
  EXPECT_GT(lo, 0.085) << "the synthetic case must defeat bisection";

  ScanSettings settings;
  settings.grid = grid;
  settings.members = 3;
  settings.durations = {60.0};
  int calls = 0;
  const auto runs = scanSteps(
      [&](double dt, int member, double duration) -> std::optional<Probe> {
        ++calls;
        Probe p;
        // Member 2 alone fails at one dt, well below the boundary.
        const bool ok = survives(dt) && !(member == 2 && std::abs(dt - grid[60]) < 1e-15);
        p.failed = !ok;
        p.failure = ok ? Failure::None : Failure::EnergyGrowth;
        p.time = ok ? duration : 0.5 * duration;
        return p;
      },
      settings);
  ASSERT_TRUE(runs);
  const Boundary b = boundaryOf(survivalAt(*runs, 60.0, 3));
  // grid[60] (≈ 0.017) fails on one member only, so the safe dt is the grid point below it.
  EXPECT_EQ(b.safeDt, grid[59]);
  EXPECT_EQ(b.firstFailureDt, grid[60]);

  // Without the member failure: the largest grid dt below 0.0715, and the island seen above it.
  const auto clean = scanSteps(
      [&](double dt, int, double duration) -> std::optional<Probe> {
        Probe p;
        p.failed = !survives(dt);
        p.time = p.failed ? 1.0 : duration;
        return p;
      },
      settings);
  ASSERT_TRUE(clean);
  const Boundary c = boundaryOf(survivalAt(*clean, 60.0, 3));
  double expected = 0.0;
  for (double dt : grid)
    if (dt < 0.0715) expected = dt;
  EXPECT_EQ(c.safeDt, expected);
  EXPECT_GE(c.firstFailureDt, 0.0715);
  EXPECT_LT(c.firstFailureDt, 0.0715 * 1.05);
  ASSERT_FALSE(c.survivalAbove.empty());
  EXPECT_GE(c.survivalAbove.front(), 0.087);
  EXPECT_LE(c.survivalAbove.back(), 0.11);
  EXPECT_LT(c.safeDt, lo);
  EXPECT_FALSE(survives(0.08));  // below bisection's answer: it is not safe
}

// A run that fails only at a later T: the same runs give each T its boundary.
TEST(Scan, OneRunToTheLongestTGivesEveryShorterT) {
  ScanSettings settings;
  settings.grid = stepGrid(0.01, 0.2);
  settings.members = 1;
  settings.durations = {30.0, 60.0};
  // Fails at t = 45 for dt ≥ 0.05, at t = 1 for dt ≥ 0.1.
  const auto runs = scanSteps(
      [](double dt, int, double duration) -> std::optional<Probe> {
        Probe p;
        p.failed = dt >= 0.05 - 1e-12;
        p.time = !p.failed ? duration : dt >= 0.1 - 1e-12 ? 1.0 : 45.0;
        return p;
      },
      settings);
  ASSERT_TRUE(runs);
  EXPECT_LT(boundaryOf(survivalAt(*runs, 30.0, 1)).firstFailureDt, 0.1 + 1e-12);
  EXPECT_GE(boundaryOf(survivalAt(*runs, 30.0, 1)).firstFailureDt, 0.1 - 1e-12);
  EXPECT_LT(boundaryOf(survivalAt(*runs, 60.0, 1)).safeDt, 0.05);
  EXPECT_GE(boundaryOf(survivalAt(*runs, 60.0, 1)).firstFailureDt, 0.05 - 1e-12);
}

TEST(Parallel, DeliversEveryCellInOrderForAnyNumberOfJobs) {
  for (int jobs : {1, 2, 5}) {
    std::vector<std::size_t> order;
    parallelMap<std::size_t>(
        jobs, 40, [](std::size_t k) -> std::optional<std::size_t> { return k * k; },
        [&](std::size_t k, std::size_t& v) {
          EXPECT_EQ(v, k * k);
          order.push_back(k);
        });
    ASSERT_EQ(order.size(), 40u) << jobs;
    for (std::size_t k = 0; k < order.size(); ++k) EXPECT_EQ(order[k], k);
  }
  // With costs, the cells start in decreasing cost (one job: in exactly that
  // order), and are still delivered in index order with the same results.
  for (int jobs : {1, 2}) {
    std::vector<std::size_t> started, delivered;
    std::mutex mutex;
    parallelMap<std::size_t>(
        jobs, 12,
        [&](std::size_t k) -> std::optional<std::size_t> {
          std::lock_guard<std::mutex> lock(mutex);
          started.push_back(k);
          return k * k;
        },
        [&](std::size_t k, std::size_t& v) {
          EXPECT_EQ(v, k * k);
          delivered.push_back(k);
        },
        [](std::size_t k) { return static_cast<double>((k * 7) % 12); });
    ASSERT_EQ(delivered.size(), 12u);
    for (std::size_t k = 0; k < delivered.size(); ++k) EXPECT_EQ(delivered[k], k);
    if (jobs == 1) {
      for (std::size_t k = 0; k < started.size(); ++k) EXPECT_EQ((started[k] * 7) % 12, 11 - k) << k;
    }
  }
  EXPECT_THROW(parallelMap<int>(
                   2, 10,
                   [](std::size_t k) -> std::optional<int> {
                     if (k == 3) throw std::runtime_error("cell 3");
                     return 1;
                   },
                   [](std::size_t, int&) {}),
               std::runtime_error);
}

TEST(RenderTemplate, FillsTablesAndValuesAndRejectsMissingOnes) {
  const std::string dir = quickOptions("render").outDir;
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/t.md") << "| a |\n| --- |\n| 1 |\n";
  std::ofstream(dir + "/values.csv") << "key,value\nspeed,42\n";
  EXPECT_EQ(renderTemplate("x {{value:speed}} y\n{{table:t}}\n", dir), "x 42 y\n| a |\n| --- |\n| 1 |\n");
  EXPECT_THROW(renderTemplate("{{value:nope}}", dir), std::runtime_error);
  EXPECT_THROW(renderTemplate("{{table:nope}}", dir), std::runtime_error);
  EXPECT_THROW(renderTemplate("{{value:speed", dir), std::runtime_error);
}

// Every image the report shows exists beside it, once.
TEST(RenderReport, RefusesAMissingOrRepeatedFigure) {
  const std::string dir = quickOptions("render-figures").outDir;
  std::filesystem::create_directories(dir + "/figures");
  std::ofstream(dir + "/values.csv") << "key,value\n";
  std::ofstream(dir + "/figures/a.png") << "png";
  RenderOptions options;
  options.dataDir = dir;
  options.templatePath = dir + "/template.md";
  options.outPath = dir + "/README.md";
  const auto renders = [&](const std::string& text) {
    std::ofstream(options.templatePath) << text;
    return renderReport(options);
  };
  EXPECT_EQ(renders("![a](figures/a.png) and a [link](figures/b.png)\n"), 0);
  EXPECT_EQ(renders("![a](figures/a.png)\n![b](figures/b.png)\n"), 1);
  EXPECT_EQ(renders("![a](figures/a.png)\n![a again](figures/a.png)\n"), 1);
}

std::string fileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A cell with a comma, a quote or a line break is quoted as RFC 4180 does, in
// the CSVs and in values.csv, and reads back as written.
TEST(Csv, CellsWithCommasAndQuotesAreQuotedAndReadBack) {
  const std::string dir = quickOptions("csv-quoting").outDir;
  std::filesystem::create_directories(dir);
  {
    output::CsvWriter csv(dir + "/t.csv", "the CSV", {"solver", "n"});
    csv << "plain CG, cold start" << 80L;
    csv.endRow();
    csv << "say \"hi\"" << 1L;
    csv.endRow();
    csv.close();
  }
  EXPECT_EQ(fileText(dir + "/t.csv"), "solver,n\n\"plain CG, cold start\",80\n\"say \"\"hi\"\"\",1\n");
  for (const std::string text : {"plain", "a, b", "\"", "x \"y\", z", "", "line\nbreak"})
    EXPECT_EQ(output::csvUnquote(output::csvField(text)), text) << text;
  writeValue(dir, "durations", "30, 60, 120");
  writeValue(dir, "quote", "a \"b\", c");
  EXPECT_EQ(readValues(dir).at("durations"), "30, 60, 120");
  EXPECT_EQ(readValues(dir).at("quote"), "a \"b\", c");
  EXPECT_EQ(fileText(dir + "/values.csv"), "key,value\ndurations,\"30, 60, 120\"\nquote,\"a \"\"b\"\", c\"\n");
}

TEST(StabilityQuick, WritesTheBoundaryAndRk4SafeStepExceedsEulers) {
  LabOptions o = quickOptions("stability");
  StabilityOptions s;
  s.duration = 10.0;
  ASSERT_EQ(runStability(o, s), 0);
  const Table rows = readCsv(o.outDir + "/stability_boundary.csv",
                             {"integrator", "chain_length", "feedback_ks", "duration", "largest_surviving_dt",
                              "first_failure_dt", "first_failure", "survival_above", "grid_lo", "grid_hi", "members",
                              "omega_feedback", "omega_chain", "omega_whip", "stiffest"});
  std::map<std::string, std::map<std::string, double>> safe;
  for (const auto& row : rows)
    if (row.at("duration") == "10" && row.at("feedback_ks") == "60")
      safe[row.at("integrator")][row.at("chain_length")] = std::stod(row.at("largest_surviving_dt"));
  ASSERT_FALSE(safe["rk4"].empty());
  // A longer chain whips faster: the measured link rate grows with its length.
  std::map<int, double> whip;
  for (const auto& row : rows) whip[std::stoi(row.at("chain_length"))] = std::stod(row.at("omega_whip"));
  EXPECT_GT(whip.rbegin()->second, whip.begin()->second);
  for (const auto& [cl, dt] : safe["euler"]) EXPECT_GT(safe["rk4"][cl], dt) << "chain " << cl;
  // The map is measured: every scanned dt has a row, and a dt at or below the
  // safe boundary survived on every member.
  const Table map = readCsv(o.outDir + "/stability_map.csv",
                            {"integrator", "chain_length", "feedback_ks", "duration", "dt", "members_run", "survivors",
                             "survived", "failure", "max_relative_stretch", "max_energy_rise"});
  int checked = 0;
  for (const auto& row : map)
    if (row.at("duration") == "10" && row.at("feedback_ks") == "60" &&
        std::stod(row.at("dt")) <= safe[row.at("integrator")][row.at("chain_length")]) {
      EXPECT_EQ(row.at("survived"), "1");
      EXPECT_EQ(row.at("survivors"), row.at("members_run"));
      ++checked;
    }
  EXPECT_GT(checked, 20);
  // Each row's maxima are over its own T: a row that survived stayed within the criterion up to T.
  for (const auto& row : map)
    if (row.at("survived") == "1") {
      EXPECT_LE(std::stod(row.at("max_energy_rise")), o.criterion.energyRiseFraction) << row.at("dt");
      EXPECT_LE(std::stod(row.at("max_relative_stretch")), o.criterion.maxRelativeConstraintError) << row.at("dt");
    }
  // Table 2: one scan per integrator and table length, each survived dt below
  // its smallest failure with a whole decade of survival under that failure,
  // and the bound its runs support.
  const Table certified = readCsv(
      o.outDir + "/stability_certified.csv",
      {"integrator", "chain_length", "duration", "survived_dt", "runs_at_and_below", "failure_bound",
       "smallest_failure_dt", "smallest_failure", "grid_lo", "grid_hi", "resolution", "members", "points", "runs",
       "full_decades", "points_0.1_0.5", "failed_points_0.1_0.5", "runs_0.1_0.5", "failed_runs_0.1_0.5",
       "points_0.5_1", "failed_points_0.5_1", "runs_0.5_1", "failed_runs_0.5_1", "points_1_1.1",
       "failed_points_1_1.1", "runs_1_1.1", "failed_runs_1_1.1", "points_1.1_1.25", "failed_points_1.1_1.25",
       "runs_1.1_1.25", "failed_runs_1.1_1.25", "points_1.25_1.5", "failed_points_1.25_1.5", "runs_1.25_1.5",
       "failed_runs_1.25_1.5", "points_1.5_2", "failed_points_1.5_2", "runs_1.5_2", "failed_runs_1.5_2",
       "coarse_surviving_dt"});
  EXPECT_EQ(certified.size(), safe.size());  // the quick plan scans one chain length
  for (const auto& row : certified) {
    EXPECT_EQ(row.at("members"), "10");
    EXPECT_EQ(row.at("resolution"), "0.01");
    const double smallest = std::stod(row.at("smallest_failure_dt"));
    if (smallest == 0.0 || row.at("full_decades") != "1") continue;
    EXPECT_LT(std::stod(row.at("survived_dt")), smallest) << row.at("integrator");
    EXPECT_LE(std::stod(row.at("grid_lo")), smallest / 10.0 * (1 + 1e-9)) << row.at("integrator");
    // Every start ran at every grid dt (70 per octave) from the bottom up to the survived one,
    // and the bound is that of those runs, none failing.
    const long below = std::lround(70.0 * std::log2(std::stod(row.at("survived_dt")) / std::stod(row.at("grid_lo")))) + 1;
    EXPECT_EQ(std::stol(row.at("runs_at_and_below")), 10 * below) << row.at("integrator");
    EXPECT_NEAR(std::stod(row.at("failure_bound")), 1.0 - std::pow(0.05, 1.0 / (10.0 * below)), 1e-9);
    EXPECT_EQ(row.at("failed_runs_0.1_0.5"), "0");
    EXPECT_EQ(row.at("failed_runs_0.5_1"), "0");
  }
  EXPECT_TRUE(std::filesystem::exists(o.outDir + "/stability_certified.md"));
  EXPECT_TRUE(std::filesystem::exists(o.outDir + "/table1.md"));
  EXPECT_TRUE(std::filesystem::exists(o.outDir + "/table2.md"));
}

TEST(StabilityQuick, OneJobAndTwoJobsWriteIdenticalData) {
  LabOptions one = quickOptions("stability-jobs1"), two = quickOptions("stability-jobs2");
  one.jobs = 1;
  two.jobs = 2;
  one.integrators = two.integrators = {"symplectic-euler", "rk4"};
  StabilityOptions s;
  s.duration = 5.0;
  ASSERT_EQ(runStability(one, s), 0);
  ASSERT_EQ(runStability(two, s), 0);
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(one.outDir)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(fileText(entry.path().string()), fileText(two.outDir + "/" + name)) << name;
    ++files;
  }
  EXPECT_GE(files, 8);
}

// Energy drift on constrained scenes: with Baumgarte feedback symplectic
// Euler drifts at a rate proportional to dt and Verlet to dt²; RATTLE, which
// projects onto the constraints, drifts far less than either.
TEST(LongtimeQuick, DriftRatesOfTheSymplecticFamilies) {
  LabOptions o = quickOptions("longtime");
  // A value of an earlier longtime run in the same --out is gone; another experiment's is kept.
  std::filesystem::create_directories(o.outDir);
  writeValue(o.outDir, "longtime.drift.stale", "1");
  writeValue(o.outDir, "other.kept", "2");
  ASSERT_EQ(runLongtime(o), 0);
  EXPECT_EQ(readValues(o.outDir).count("longtime.drift.stale"), 0u);
  EXPECT_EQ(readValues(o.outDir).at("other.kept"), "2");
  EXPECT_EQ(readValues(o.outDir).count("longtime.horizon"), 1u);
  const Table rows = readCsv(o.outDir + "/longtime_drift.csv", {"problem", "integrator", "dt", "duration", "failed",
                                                                "time", "drift_per_100s", "max_abs_change"});
  std::map<std::string, std::map<std::string, std::map<double, double>>> rate;  // problem, integrator, dt
  for (const auto& row : rows) {
    ASSERT_EQ(row.at("failed"), "0") << row.at("problem") << " " << row.at("integrator") << " " << row.at("dt");
    rate[row.at("problem")][row.at("integrator")][std::stod(row.at("dt"))] = std::stod(row.at("drift_per_100s"));
  }
  ASSERT_EQ(rate.size(), 3u);
  for (auto& [problem, schemes] : rate) {
    const auto order = [&](const std::string& name) {
      // Between the smallest and the largest dt; a drift may be a loss, at both.
      const auto& r = schemes[name];
      const double first = r.begin()->second, last = r.rbegin()->second;
      EXPECT_GT(first * last, 0.0) << problem << " " << name << ": the drift changes sign with dt";
      return test_support::logLogSlope({r.begin()->first, r.rbegin()->first}, {std::abs(first), std::abs(last)});
    };
    EXPECT_NEAR(order("symplectic-euler"), 1.0, 0.2) << problem;
    const double h = schemes["rattle"].begin()->first;
    EXPECT_GT(schemes["symplectic-euler"][h], 0.0) << problem << ": symplectic Euler gains energy";
    EXPECT_LT(std::abs(schemes["rattle"][h]), 0.05 * std::abs(schemes["symplectic-euler"][h])) << problem;
    EXPECT_NEAR(order("verlet"), 2.0, 0.3) << problem;
  }
}

TEST(AccuracyQuick, OscillatorSlopesAreTheIntegratorsOrders) {
  LabOptions o = quickOptions("accuracy");
  ASSERT_EQ(runAccuracy(o), 0);
  const Table rows =
      readCsv(o.outDir + "/accuracy_slopes.csv", {"problem", "integrator", "slope", "points", "local_slopes"});
  std::map<std::string, double> slope;
  for (const auto& row : rows)
    if (row.at("problem") == "oscillator") {
      slope[row.at("integrator")] = std::stod(row.at("slope"));
      // The fit runs over the finest points whose local slopes agree: at least
      // two points, and no more than there are local slopes plus one.
      std::istringstream local(row.at("local_slopes"));
      std::vector<double> slopes;
      for (double s; local >> s;) slopes.push_back(s);
      const int points = std::stoi(row.at("points"));
      EXPECT_GE(points, 2) << row.at("integrator");
      EXPECT_LE(points, static_cast<int>(slopes.size()) + 1) << row.at("integrator");
      if (points == 2) {
        EXPECT_NEAR(slope[row.at("integrator")], slopes.front(), 0.006) << row.at("integrator");
      }
    }
  EXPECT_NEAR(slope["euler"], 1.0, 0.3);
  EXPECT_NEAR(slope["midpoint"], 2.0, 0.3);
  EXPECT_NEAR(slope["rk4"], 4.0, 0.3);
  const Table points = readCsv(o.outDir + "/accuracy.csv",
                               {"problem", "integrator", "dt", "tolerance", "error", "seconds_per_simulated_second",
                                "error_at_T", "energy_error", "constraint_drift", "cpu_min", "cpu_max", "survived",
                                "failure"});
  // Adaptive schemes are swept over their tolerance at a fixed output
  // interval: a tighter tolerance must give a smaller error, not the same one.
  std::map<std::string, std::map<double, double>> adaptiveErrors;
  for (const auto& row : points) {
    EXPECT_LE(std::stod(row.at("cpu_min")), std::stod(row.at("seconds_per_simulated_second")));
    EXPECT_LE(std::stod(row.at("seconds_per_simulated_second")), std::stod(row.at("cpu_max")));
    if (row.at("problem") == "oscillator" && std::stod(row.at("tolerance")) > 0)
      adaptiveErrors[row.at("integrator")][std::stod(row.at("tolerance"))] = std::stod(row.at("error"));
  }
  for (const auto& [name, errors] : adaptiveErrors) {
    ASSERT_GE(errors.size(), 2u) << name;
    EXPECT_LT(errors.begin()->second, 0.5 * errors.rbegin()->second) << name;
  }
}

// The cost against size: a pick per family, size and budget, each within its
// budget, and the slope in values.csv is the fit of log CPU time against log
// particle count over the CSV's rows.
TEST(CostQuick, CostAgainstSizeFitsItsOwnRows) {
  LabOptions o = quickOptions("cost");
  ASSERT_EQ(runCost(o), 0);
  const Table rows = readCsv(o.outDir + "/cost_vs_size.csv",
                             {"family", "scene", "particles", "horizon", "size", "budget_relative", "integrator", "dt",
                              "tolerance", "max_error", "worst_error", "cpu_per_simulated_second", "cpu_min",
                              "cpu_max", "reference_agreement", "certified_lo", "certified_hi", "margin_runs",
                              "failure_bound"});
  std::map<std::pair<std::string, std::string>, std::vector<std::pair<double, double>>> series;
  for (const auto& row : rows) {
    EXPECT_LE(std::stod(row.at("max_error")), std::stod(row.at("budget_relative")) * std::stod(row.at("size")));
    // Certified: the bound is that of the margin's runs, none failing, and every start is within budget.
    const long runs = std::stol(row.at("margin_runs"));
    EXPECT_GT(runs, 0);
    EXPECT_NEAR(std::stod(row.at("failure_bound")), 1.0 - std::pow(0.05, 1.0 / runs), 1e-9);
    EXPECT_LE(std::stod(row.at("max_error")), std::stod(row.at("worst_error")));
    EXPECT_LE(std::stod(row.at("worst_error")), std::stod(row.at("budget_relative")) * std::stod(row.at("size")));
    EXPECT_GT(std::stod(row.at("cpu_per_simulated_second")), 0.0);
    series[{row.at("family"), row.at("budget_relative")}].emplace_back(std::stod(row.at("particles")),
                                                                       std::stod(row.at("cpu_per_simulated_second")));
  }
  ASSERT_EQ(series.size(), 4u);  // chain and cloth × two budgets
  const Table values = readCsv(o.outDir + "/values.csv", {"key", "value"});
  std::map<std::string, std::string> value;
  for (const auto& row : values) value[row.at("key")] = row.at("value");
  for (const auto& [key, points] : series) {
    ASSERT_EQ(points.size(), 2u) << key.first << " " << key.second;
    const double slope =
        test_support::logLogSlope({points[0].first, points[1].first}, {points[0].second, points[1].second});
    const std::string name = "cost.size_slope." + key.first + "." + lab::general(std::stod(key.second));
    ASSERT_TRUE(value.count(name)) << name;
    EXPECT_NEAR(std::stod(value[name]), slope, 0.006) << name;
  }
  // Where each integrator is the cheapest pick, as the report's advice quotes it, agrees with the rows.
  std::map<std::string, std::string> quoted = readValues(o.outDir);
  for (const auto& row : rows)
    EXPECT_NE(quoted["cost.where_cheapest." + row.at("integrator")].find(row.at("particles") + "-particle " +
                                                                          row.at("family")),
              std::string::npos)
        << row.at("integrator") << ": " << quoted["cost.where_cheapest." + row.at("integrator")];
  for (const auto& info : particles::integratorTable())  // every scheme has its clause, picked or not
    EXPECT_EQ(quoted["cost.where_cheapest." + std::string(info.name)].rfind("is ", 0), 0u) << info.name;
  // The contact question of the quick plan: a reference by self-convergence and a pick, or a refusal saying why.
  const Table contacts = readCsv(o.outDir + "/cost_contacts.csv",
                                 {"scene", "particles", "horizon", "error", "contact", "reference", "refused",
                                  "certifiable_horizon", "integrator", "dt", "worst_error", "headroom", "certified_lo",
                                  "certified_hi", "margin_runs", "failure_bound", "cpu_per_simulated_second"});
  ASSERT_EQ(contacts.size(), 1u);
  const auto& contact = contacts[0];
  EXPECT_NE(contact.at("contact").find("touch"), std::string::npos) << contact.at("contact");
  if (contact.at("refused") == "0") {
    EXPECT_NE(contact.at("reference").find("self-convergence"), std::string::npos) << contact.at("reference");
    if (!contact.at("integrator").empty()) {
      EXPECT_LE(std::stod(contact.at("worst_error")), std::stod(contact.at("error")));
    }
  }
}

TEST(TimingQuick, WritesPositiveStepTimesForEveryIntegrator) {
  LabOptions o = quickOptions("timing");
  ASSERT_EQ(runTiming(o, {3, 3}), 0);
  const Table rows = readCsv(o.outDir + "/timing.csv",
                             {"scene", "integrator", "particles", "constraints", "springs", "dt", "step_seconds",
                              "step_seconds_min", "step_seconds_max", "cg_iterations_per_step"});
  std::map<std::string, int> perIntegrator;
  for (const auto& row : rows) {
    EXPECT_GT(std::stod(row.at("step_seconds_min")), 0.0) << row.at("integrator");
    // The median of the repeats lies within their spread.
    EXPECT_LE(std::stod(row.at("step_seconds_min")), std::stod(row.at("step_seconds"))) << row.at("integrator");
    EXPECT_LE(std::stod(row.at("step_seconds")), std::stod(row.at("step_seconds_max"))) << row.at("integrator");
    ++perIntegrator[row.at("integrator")];
  }
  std::size_t swept = 0;
  for (const auto& info : particles::integratorTable()) swept += inLabSweeps(info.name);
  EXPECT_EQ(perIntegrator.size(), swept);
  const Table table3 = readCsv(o.outDir + "/table3_step_cost.csv",
                               {"integrator", "dt", "step_ms", "step_ms_min", "step_ms_max", "cg_iterations_per_step"});
  EXPECT_EQ(table3.size(), 2 * swept);
}

TEST(ExtremesQuick, WritesEverySweep) {
  LabOptions o = quickOptions("extremes");
  o.integrators = {"midpoint", "rk4"};
  ASSERT_EQ(runExtremes(o), 0);
  EXPECT_FALSE(readCsv(o.outDir + "/extremes_stiffness.csv", {"integrator", "stiffness", "largest_surviving_dt", "first_failure_dt",
                                                              "first_failure", "grid_lo", "grid_hi"}).empty());
  EXPECT_FALSE(readCsv(o.outDir + "/extremes_mass_ratio.csv", {"integrator", "mass_ratio", "largest_surviving_dt", "first_failure_dt",
                                                               "first_failure", "cg_iterations_per_step"}).empty());
  EXPECT_FALSE(readCsv(o.outDir + "/extremes_feedback.csv", {"ks", "kd", "critical_kd", "survived", "failure",
                                                              "max_relative_stretch", "final_relative_stretch"}).empty());
  const Table budget = readCsv(o.outDir + "/extremes_cg_budget.csv", {"warm_start", "tolerance", "max_iterations", "survived",
                                                                      "failure", "max_relative_stretch",
                                                                      "cg_iterations_per_step"});
  EXPECT_FALSE(budget.empty());
  EXPECT_FALSE(readCsv(o.outDir + "/extremes_rod_form.csv", {"integrator", "rod", "largest_surviving_dt", "step_seconds",
                                                              "cg_iterations_per_step", "max_relative_stretch"}).empty());
  EXPECT_FALSE(readCsv(o.outDir + "/extremes_taut_chain.csv", {"integrator", "max_iterations", "survived", "reason",
                                                                "time", "max_relative_stretch",
                                                                "cg_iterations_per_step"}).empty());
}

TEST(ClaimsQuick, EveryClaimGetsAVerdict) {
  LabOptions o = quickOptions("claims");
  ASSERT_EQ(runClaims(o), 0);
  std::ifstream in(o.outDir + "/claims.md");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  int verdicts = 0;
  for (const char* word : {"| confirmed", "| refuted |", "| undecided |"})
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++verdicts;
  EXPECT_EQ(verdicts, 6);
  // The starved-CG verdict at each stretch threshold: looser thresholds never refute what a stricter one confirmed.
  const Table thresholds = readCsv(o.outDir + "/claims_starved_cg_verdict.csv",
                                   {"max_stretch_threshold", "cold", "warm", "cold_non_finite_only",
                                    "warm_non_finite_only"});
  ASSERT_EQ(thresholds.size(), 5u);
  for (const char* start : {"cold", "warm", "cold_non_finite_only", "warm_non_finite_only"})
    for (std::size_t k = 1; k < thresholds.size(); ++k)
      if (thresholds[k - 1].at(start) == "confirmed") {
        EXPECT_EQ(thresholds[k].at(start), "confirmed") << start;
      }
  // Counting energy growth as exploding can only refute more.
  for (const auto& row : thresholds)
    for (const char* start : {"cold", "warm"})
      if (row.at(start) == "confirmed") {
        EXPECT_EQ(row.at(std::string(start) + "_non_finite_only"), "confirmed");
      }
}
