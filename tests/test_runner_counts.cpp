// The runner's CSV counts what the step did: driven through the runner's own
// step loop (demos/cli/run_loop.h), each row's force_evaluations, solves,
// cg_iterations and internal_steps are compared with what a counting force
// (test_support::CountingForce: its evaluations and the CG iterations the
// solver reported at each) and a counting constraint saw during that step.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli/run_loop.h"
#include "cli/step_output.h"
#include "particles/constraints/rod.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "integrators/implicit_euler.h"
#include "particles/particle_system.h"
#include "oscillator_fixture.h"
#include "scene.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;
using test_support::CountingForce;

namespace {

// A rod that counts how often its rows are gathered (once per constraint solve).
class CountingRod : public RodConstraint {
 public:
  using RodConstraint::RodConstraint;
  void evaluate(const Phase& s, ConstraintRow& row) const override {
    ++gathers;
    RodConstraint::evaluate(s, row);
  }
  mutable int gathers = 0;
};

struct Row {
  int cgIterations, solves, forceEvaluations, internalSteps;
};

// The count columns of every CSV row, by the header's names.
std::vector<Row> countColumns(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::istringstream header(line); std::getline(header, line, ',');) names.push_back(line);
  EXPECT_EQ(names, cli::kDiagnosticsColumns);
  auto column = [&](const char* name) {
    for (std::size_t k = 0; k < names.size(); ++k)
      if (names[k] == name) return k;
    ADD_FAILURE() << "no column " << name;
    return std::size_t{0};
  };
  const std::size_t cg = column("cg_iterations"), solves = column("solves"),
                    evaluations = column("force_evaluations"), steps = column("internal_steps");
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    for (std::istringstream fields(line); std::getline(fields, line, ',');) cells.push_back(line);
    EXPECT_EQ(cells.size(), names.size());
    if (cells.size() != names.size()) break;
    rows.push_back({std::stoi(cells[cg]), std::stoi(cells[solves]), std::stoi(cells[evaluations]),
                    std::stoi(cells[steps])});
  }
  return rows;
}

// Four rods from a pinned particle, released sideways, one of them counting its
// gathers, plus the counting force; the solve by CG from a cold start, so that
// every solve iterates.
struct CountedChain {
  ParticleSystem system;
  const CountingForce* force = nullptr;
  const CountingRod* rod = nullptr;
};

CountedChain countedChain() {
  CountedChain c;
  ParticleSystem& s = c.system;
  for (int i = 0; i < 5; ++i) s.addParticle(Vector2d(0.1 * i, 0.0), 1.0);
  s.setPinned(0, true);
  c.rod = &static_cast<CountingRod&>(s.addConstraint(std::make_unique<CountingRod>(0, 1, 0.1)));
  for (int i = 1; i < 4; ++i) s.addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1));
  s.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  c.force = &static_cast<CountingForce&>(s.addForce(std::make_unique<CountingForce>(s.solver())));
  s.solver().settings.method = SolveMethod::ConjugateGradient;
  s.solver().settings.warmStart = false;
  return c;
}

// What the counting objects saw in each step, beside the step's own statistics.
struct Seen {
  int evaluations, gathers, iterations;
  StepStats stats;
};

// Runs `steps` steps through the runner's loop; returns the CSV rows (row 0 first) and what was seen.
std::vector<Row> runCounted(CountedChain& c, Integrator& integrator, double dt, int steps, std::vector<Seen>& seen) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            (std::string("particle-lab-runner-counts-") +
                             ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".csv"))
                               .string();
  output::CsvWriter csv(path, "the test's CSV", cli::kDiagnosticsColumns);
  cli::RunLoop loop(c.system, integrator, dt, {&csv, nullptr, 1}, 2.0);
  EXPECT_EQ(loop.start(), "");
  for (int k = 0; k < steps; ++k) {
    c.force->seen.clear();
    c.rod->gathers = 0;
    EXPECT_EQ(loop.step(), "") << "step " << k + 1;
    // Evaluation j + 1 saw solve j's iterations; the step's last solve is still the solver's.
    const std::vector<int>& iterations = c.force->seen;
    int sum = c.system.lastSolve().iterations;
    for (std::size_t j = 1; j < iterations.size(); ++j) sum += iterations[j];
    seen.push_back({static_cast<int>(iterations.size()), c.rod->gathers, sum, c.system.lastStepStats()});
  }
  csv.close();
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  std::filesystem::remove(path);
  return countColumns(text.str());
}

}  // namespace

TEST(RunnerCounts, FixedStepRowsCountEveryEvaluationSolveAndCgIteration) {
  CountedChain c = countedChain();
  auto rk4 = makeIntegrator("rk4");
  std::vector<Seen> seen;
  const std::vector<Row> rows = runCounted(c, *rk4, 0.005, 20, seen);
  ASSERT_EQ(rows.size(), seen.size() + 1);
  EXPECT_EQ(rows[0].solves + rows[0].forceEvaluations + rows[0].cgIterations + rows[0].internalSteps, 0);
  for (std::size_t k = 0; k < seen.size(); ++k) {
    const Row& row = rows[k + 1];
    EXPECT_EQ(row.forceEvaluations, seen[k].evaluations) << "step " << k + 1;
    EXPECT_EQ(row.forceEvaluations, 4) << "step " << k + 1;
    EXPECT_EQ(row.solves, seen[k].gathers) << "step " << k + 1;
    EXPECT_EQ(row.cgIterations, seen[k].iterations) << "step " << k + 1;
    EXPECT_GT(row.cgIterations, row.solves) << "step " << k + 1;  // cold CG iterates in every solve
    EXPECT_EQ(row.internalSteps, 1) << "step " << k + 1;
  }
}

// dopri5 at output intervals shorter than its internal step: some rows take
// no step (the output comes from the dense output) and count nothing; the
// others count six evaluations, six solves per accepted or rejected step
// (FSAL), and the first also k₁ and the starting-step probe.
TEST(RunnerCounts, Dopri5RowsCountItsInternalStepsAndTheirEvaluations) {
  CountedChain c = countedChain();
  IntegratorSettings settings;
  settings.dopri5.tolerance = 1e-5;
  auto dopri5 = makeIntegrator("dopri5", settings);
  std::vector<Seen> seen;
  const std::vector<Row> rows = runCounted(c, *dopri5, 0.002, 100, seen);
  ASSERT_EQ(rows.size(), seen.size() + 1);
  int emptyRows = 0, steppedRows = 0;
  for (std::size_t k = 0; k < seen.size(); ++k) {
    const Row& row = rows[k + 1];
    const int attempts = row.internalSteps + seen[k].stats.rejectedSteps;
    EXPECT_EQ(row.forceEvaluations, seen[k].evaluations) << "step " << k + 1;
    EXPECT_EQ(row.forceEvaluations, 6 * attempts + (k == 0 ? 2 : 0)) << "step " << k + 1;
    EXPECT_EQ(row.solves, seen[k].gathers) << "step " << k + 1;
    EXPECT_EQ(row.cgIterations, row.solves ? seen[k].iterations : 0) << "step " << k + 1;
    (row.internalSteps == 0 ? emptyRows : steppedRows) += 1;
  }
  EXPECT_GT(emptyRows, 0);
  EXPECT_GT(steppedRows, 0);
}

// Implicit Euler evaluates the forces at the start of the step and, with
// constraints, once more at each Newton iterate (after every solve), and
// solves its own systems (Newton passes on the constraints; CG on the
// cloth-like spring net): the CSV carries the step's solves and CG iterations.
TEST(RunnerCounts, ImplicitEulerRowsCountItsEvaluationAndSolves) {
  {
    CountedChain c = countedChain();
    auto implicit = makeIntegrator("implicit-euler");
    std::vector<Seen> seen;
    const std::vector<Row> rows = runCounted(c, *implicit, 0.05, 20, seen);
    ASSERT_EQ(rows.size(), seen.size() + 1);
    for (std::size_t k = 0; k < seen.size(); ++k) {
      const Row& row = rows[k + 1];
      EXPECT_EQ(row.forceEvaluations, seen[k].evaluations) << "step " << k + 1;
      EXPECT_EQ(row.forceEvaluations, 1 + row.solves) << "step " << k + 1;
      EXPECT_EQ(row.solves, seen[k].stats.solves) << "step " << k + 1;
      EXPECT_GE(row.solves, 1) << "step " << k + 1;
      EXPECT_EQ(row.cgIterations, seen[k].stats.cgIterations) << "step " << k + 1;
      EXPECT_EQ(row.internalSteps, 1) << "step " << k + 1;
    }
  }
  {
    // Springs only: the CG solve, whose iterations the row sums.
    CountedChain c;
    ParticleSystem& s = c.system;
    for (int i = 0; i < 6; ++i) s.addParticle(Vector2d(0.1 * i, 0.0), 1.0);
    s.setPinned(0, true);
    for (int i = 0; i < 5; ++i) s.addForce(std::make_unique<SpringForce>(i, i + 1, 0.1, 200.0, 0.5));
    s.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
    c.force = &static_cast<CountingForce&>(s.addForce(std::make_unique<CountingForce>(s.solver())));
    CountingRod unused(0, 1, 0.1);
    c.rod = &unused;
    ImplicitEulerIntegrator implicit;
    IntegratorSettings settings;
    settings.implicitEuler.solver = ImplicitLinearSolver::ConjugateGradient;
    implicit.configure(settings);
    std::vector<Seen> seen;
    const std::vector<Row> rows = runCounted(c, implicit, 0.02, 20, seen);
    ASSERT_EQ(rows.size(), seen.size() + 1);
    for (std::size_t k = 0; k < seen.size(); ++k) {
      const Row& row = rows[k + 1];
      EXPECT_EQ(row.forceEvaluations, seen[k].evaluations) << "step " << k + 1;
      EXPECT_EQ(row.solves, 1) << "step " << k + 1;
      EXPECT_EQ(row.cgIterations, seen[k].stats.cgIterations) << "step " << k + 1;
      EXPECT_GT(row.cgIterations, 0) << "step " << k + 1;
    }
  }
}

namespace {
// A spring that counts how often its potential energy is evaluated.
class PotentialCountingSpring : public SpringForce {
 public:
  using SpringForce::SpringForce;
  double potential(const Phase& s) const override {
    ++potentials;
    return SpringForce::potential(s);
  }
  mutable int potentials = 0;
};
}  // namespace

// The runner measures the energies once per measured step (the divergence
// check reuses the diagnostics' total energy), and with diagnosticsEvery 3
// only at steps 3, 6, ... and writes only their rows.
TEST(RunnerCounts, DiagnosticsMeasureThePotentialOncePerMeasuredStep) {
  for (long long every : {1LL, 3LL}) {
    ParticleSystem system;
    system.addParticle(Vector2d(0.0, 0.0), 1.0);
    system.addParticle(Vector2d(1.5, 0.0), 1.0);
    auto& spring = static_cast<PotentialCountingSpring&>(
        system.addForce(std::make_unique<PotentialCountingSpring>(0, 1, 1.0, 10.0, 0.1)));
    const std::string path =
        (std::filesystem::temp_directory_path() / ("particle-lab-runner-potential-" + std::to_string(every) + ".csv"))
            .string();
    auto integrator = makeIntegrator("rk4");
    {
      output::CsvWriter csv(path, "the test's CSV", cli::kDiagnosticsColumns);
      cli::RunLoop loop(system, *integrator, 0.01, {&csv, nullptr, 1, every}, 2.0);
      EXPECT_EQ(loop.start(), "");
      const int before = spring.potentials;
      for (int k = 1; k <= 6; ++k) {
        const int at = spring.potentials;
        EXPECT_EQ(loop.step(), "");
        EXPECT_EQ(spring.potentials - at, k % every == 0 ? 1 : 0) << "step " << k << " every " << every;
      }
      EXPECT_EQ(spring.potentials - before, every == 1 ? 6 : 2);
      csv.close();
    }
    std::ifstream in(path);
    int lines = 0;
    for (std::string line; std::getline(in, line);) ++lines;
    EXPECT_EQ(lines, 1 + 1 + (every == 1 ? 6 : 2)) << "header, row 0 and the measured steps";
    std::filesystem::remove(path);
  }
}

// --- the runner's energy bound ---------------------------------------------------

// Every built-in scene at its own integrator and dt for 3 s of simulated time
// stays inside the runner's energy bound (E − E₀ ≤ 100 E_ref), with room to
// spare: the largest rise is printed as a fraction of E_ref.
TEST(RunnerDivergence, BuiltInScenesStayInsideTheEnergyBoundAtTheirDefaults) {
  for (const scenes::SceneInfo& info : scenes::sceneTable()) {
    scenes::Scene scene = scenes::buildScene(info.name);
    particles::ParticleSystem& system = *scene.system;
    auto integrator = makeIntegrator(scene.integrator, scene.integratorSettings);
    const double length = cli::sceneLength(scene);
    const double scale = particles::blowUpEnergyScale(system, length), e0 = system.totalEnergy();
    cli::RunLoop loop(system, *integrator, scene.dt, {nullptr, nullptr, 1}, length);
    ASSERT_EQ(loop.start(), "") << info.name;
    double rise = 0.0;
    const int steps = static_cast<int>(std::lround(3.0 / scene.dt));
    for (int k = 1; k <= steps; ++k) {
      ASSERT_EQ(loop.step(), "") << info.name << " step " << k;
      rise = std::max(rise, system.totalEnergy() - e0);
    }
    std::cout << info.name << " (" << scene.integrator << ", dt " << scene.dt << "): largest energy rise " << rise
              << " J = " << rise / scale << " E_ref\n";
    EXPECT_LT(rise, 0.01 * cli::kEnergyBoundFactor * scale) << info.name;
  }
}

// Explicit Euler on a spring of ω = 100 rad/s at dt 0.01 multiplies the
// energy by 1 + ω²h² = 2 each step: the run ends at the energy bound within
// 20 steps, with the state still finite (it overflows only after ~1000).
TEST(RunnerDivergence, ExplicitEulerOnAStiffSpringEndsAtTheEnergyBound) {
  test_support::Oscillator oscillator;  // unit mass, undamped
  oscillator.params.stiffness = 1e4;
  oscillator.params.rest = 0.5;
  oscillator.params.stretch = 0.01;
  ParticleSystem system = oscillator.build();
  auto euler = makeIntegrator("euler");
  cli::RunLoop loop(system, *euler, 0.01, {nullptr, nullptr, 1}, 2.0);
  ASSERT_EQ(loop.start(), "");
  std::string reason;
  int step = 0;
  while (reason.empty() && step < 200) reason = loop.step(), ++step;
  EXPECT_EQ(reason.rfind("the energy rose by ", 0), 0u) << reason;
  EXPECT_LE(step, 20) << "stopped at step " << step << ": " << reason;
  EXPECT_TRUE(system.finite());
}
