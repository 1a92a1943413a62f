// The laboratory: the explosion detector, the report renderer, and each
// experiment's --quick mode producing CSVs with the expected columns and
// sane values.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/render.h"

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

TEST(Explosion, FlagsADivergingRunAndPassesAStableOne) {
  scenes::Scene unstable = buildChain({12});
  auto euler = particles::makeIntegrator("euler");
  const RunResult bad = simulate(unstable, *euler, 0.2, 20.0);
  EXPECT_TRUE(bad.exploded);
  EXPECT_FALSE(bad.reason.empty());
  EXPECT_LT(bad.time, 20.0);

  scenes::Scene stable = buildChain({12});
  auto rk4 = particles::makeIntegrator("rk4");
  const RunResult good = simulate(stable, *rk4, 0.01, 2.0);
  EXPECT_FALSE(good.exploded) << good.reason;
  EXPECT_EQ(good.steps, 200);
  EXPECT_LT(good.maxRelativeStretch, 0.01);
}

TEST(Explosion, EachCriterionTriggersOnItsOwn) {
  scenes::Scene chain = buildChain({6});
  chain.system->velocities()[chain.system->velocities().size() - 1] = std::nan("");
  auto rk4 = particles::makeIntegrator("rk4");
  EXPECT_EQ(simulate(chain, *rk4, 0.01, 0.1).reason, "non-finite");

  scenes::Scene stretched = buildChain({6});
  stretched.system->positions()[stretched.system->positions().size() - 2] += 1.0;  // pull the tip off
  Explosion strict;
  EXPECT_EQ(simulate(stretched, *rk4, 0.01, 0.1, strict).reason, "constraint");

  // Explicit Euler pumps energy into an undamped oscillator: (1 + ω²h²) per step.
  scenes::Scene oscillator = scenes::buildScene("oscillator", {{"damping", "0"}});
  Explosion energyOnly;
  energyOnly.energyGain = 0.01;
  auto euler = particles::makeIntegrator("euler");
  EXPECT_EQ(simulate(oscillator, *euler, 0.05, 100.0, energyOnly).reason, "energy");
  scenes::Scene calm = scenes::buildScene("oscillator", {{"damping", "0"}});
  auto rk4Again = particles::makeIntegrator("rk4");
  EXPECT_FALSE(simulate(calm, *rk4Again, 0.01, 10.0, energyOnly).exploded);
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

TEST(StabilityQuick, WritesTheBoundaryAndRk4StableRegionContainsEulers) {
  LabOptions o = quickOptions("stability");
  StabilityOptions s;
  s.duration = 10.0;
  ASSERT_EQ(runStability(o, s), 0);
  const Table rows = readCsv(o.outDir + "/stability_boundary.csv",
                             {"integrator", "chain_length", "duration", "max_dt", "max_dt_dimensionless"});
  std::map<std::string, std::map<std::string, double>> maxDt;
  for (const auto& row : rows) maxDt[row.at("integrator")][row.at("chain_length")] = std::stod(row.at("max_dt"));
  ASSERT_FALSE(maxDt["rk4"].empty());
  for (const auto& [cl, dt] : maxDt["euler"]) EXPECT_GE(maxDt["rk4"][cl], dt) << "chain " << cl;
  readCsv(o.outDir + "/stability_map.csv", {"integrator", "chain_length", "dt", "dt_dimensionless", "survived"});
  EXPECT_TRUE(std::filesystem::exists(o.outDir + "/table1.md"));
  EXPECT_TRUE(std::filesystem::exists(o.outDir + "/table2.md"));
}

TEST(AccuracyQuick, OscillatorSlopesAreTheIntegratorsOrders) {
  LabOptions o = quickOptions("accuracy");
  ASSERT_EQ(runAccuracy(o), 0);
  const Table rows = readCsv(o.outDir + "/accuracy_slopes.csv", {"problem", "integrator", "slope"});
  std::map<std::string, double> slope;
  for (const auto& row : rows)
    if (row.at("problem") == "oscillator") slope[row.at("integrator")] = std::stod(row.at("slope"));
  EXPECT_NEAR(slope["euler"], 1.0, 0.3);
  EXPECT_NEAR(slope["midpoint"], 2.0, 0.3);
  EXPECT_NEAR(slope["rk4"], 4.0, 0.3);
  readCsv(o.outDir + "/accuracy.csv", {"problem", "integrator", "dt", "tolerance", "error", "seconds_per_simulated_second"});
}

TEST(TimingQuick, WritesPositiveStepTimesForEveryIntegrator) {
  LabOptions o = quickOptions("timing");
  ASSERT_EQ(runTiming(o, {1, 3}), 0);
  const Table rows = readCsv(o.outDir + "/timing.csv", {"scene", "integrator", "particles", "constraints", "springs",
                                                        "dt", "step_seconds", "cg_iterations_per_step"});
  std::map<std::string, int> perIntegrator;
  for (const auto& row : rows) {
    EXPECT_GT(std::stod(row.at("step_seconds")), 0.0) << row.at("integrator");
    ++perIntegrator[row.at("integrator")];
  }
  EXPECT_EQ(perIntegrator.size(), particles::integratorTable().size());
  readCsv(o.outDir + "/table3_step_cost.csv", {"integrator", "dt", "step_ms", "cg_iterations_per_step"});
}

TEST(ExtremesQuick, WritesEverySweep) {
  LabOptions o = quickOptions("extremes");
  o.integrators = {"midpoint", "rk4"};
  ASSERT_EQ(runExtremes(o), 0);
  EXPECT_FALSE(readCsv(o.outDir + "/extremes_stiffness.csv", {"integrator", "stiffness", "max_dt"}).empty());
  EXPECT_FALSE(readCsv(o.outDir + "/extremes_mass_ratio.csv",
                       {"integrator", "mass_ratio", "max_dt", "cg_iterations_per_step"}).empty());
  EXPECT_FALSE(readCsv(o.outDir + "/extremes_feedback.csv", {"ks", "kd", "critical_kd", "survived",
                                                              "max_relative_stretch", "final_relative_stretch"}).empty());
  const Table budget = readCsv(o.outDir + "/extremes_cg_budget.csv", {"warm_start", "tolerance", "max_iterations", "survived",
                                                                      "max_relative_stretch", "cg_iterations_per_step"});
  EXPECT_FALSE(budget.empty());
  EXPECT_FALSE(readCsv(o.outDir + "/extremes_rod_form.csv", {"integrator", "rod", "max_dt", "step_seconds",
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
  for (const char* word : {"| confirmed", "| refuted |"})
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++verdicts;
  EXPECT_EQ(verdicts, 6);
}
