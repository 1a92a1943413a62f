// `particle-lab timing`: cost per step against chain length and cloth size for
// each integrator, and the seed report's Table 3.
#include <chrono>
#include <cmath>
#include <iostream>

#include "lab/cells.h"
#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/lab_scene.h"
#include "lab/results.h"

namespace lab {

StepCost measureStepCost(scenes::Scene& scene, const std::string& integrator, double dt,
                         const TimingOptions& timing) {
  particles::ParticleSystem& system = *scene.system;
  auto stepper = particles::makeIntegrator(integrator);
  for (int k = 0; k < 3; ++k) system.step(*stepper, dt);
  const StepCost failed{std::nan(""), std::nan(""), std::nan("")};
  if (!system.finite()) return failed;
  const particles::Snapshot warm = system.snapshot();
  std::vector<double> perRepeat;
  double iterations = 0.0, solves = 0.0;
  long counted = 0;
  using Clock = std::chrono::steady_clock;
  for (int r = 0; r < timing.repeats; ++r) {
    double seconds = 0.0;
    int done = 0;
    for (int k = 0; k < timing.steps; ++k) {
      const auto start = Clock::now();
      const particles::StepStats stats = system.step(*stepper, dt);
      const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      if (!system.finite()) {
        system.restore(warm);
        continue;
      }
      seconds += elapsed;
      iterations += stats.cgIterations;
      solves += stats.solves;
      ++done, ++counted;
    }
    if (done > 0) perRepeat.push_back(seconds / done);
  }
  if (perRepeat.empty()) return failed;
  const double steps = static_cast<double>(std::max(1L, counted));
  return {median(perRepeat), iterations / steps, solves / steps};
}

double estimatedRunSeconds(scenes::Scene scene, const std::string& integrator, double dt, double duration) {
  const double seconds = measureStepCost(scene, integrator, dt, {1, 3}).seconds;
  return std::isfinite(seconds) ? seconds * duration / dt : 0.0;
}

namespace {

using Rows = std::vector<std::vector<std::string>>;

// What the experiment times.
struct TimingPlan {
  std::vector<int> chains;         // test-chain lengths, particles
  std::vector<int> cloths;         // 8-way cloth sides, particles per side
  int slopeFromSide = 0;           // the cloth growth slope is fitted from this side up
  std::vector<int> solverLengths;  // chains the constraint solvers are compared on
  double solverRunDuration = 0.0;  // s, the run whose max stretch each solver leaves
  std::string growthTitle;
};

// Small sizes: proves the code runs.
TimingPlan quickPlan() {
  TimingPlan plan;
  plan.chains = {10, 20, 40};
  plan.cloths = {4, 8};
  plan.slopeFromSide = 0;
  plan.solverLengths = {20};
  plan.solverRunDuration = 0.5;
  plan.growthTitle = "Cost growth: fitted log-log slope of step time against size";
  return plan;
}

// The growth slope is fitted from 32×32 up, past the sizes where fixed
// per-step overheads dominate.
TimingPlan fullPlan() {
  TimingPlan plan;
  plan.chains = {10, 20, 40, 80, 160, 320, 640, 1000};
  plan.cloths = {8, 16, 32, 64, 128, 256};
  plan.slopeFromSide = 32;
  plan.solverLengths = {80, 500};
  plan.solverRunDuration = 5.0;
  plan.growthTitle = "Cost growth: fitted log-log slope of step time against size (chain 10-1000, cloth 32x32-256x256)";
  return plan;
}

// One timed scene: its step cost and what it holds.
struct Timed {
  StepCost cost;
  long particles = 0, constraints = 0, forces = 0;
  double dt = 0.0;
};
template <class Io>
void fields(Io& io, Timed& t) {
  io("cost", t.cost), io("particles", t.particles), io("constraints", t.constraints), io("forces", t.forces);
  io("dt", t.dt);
}

Timed timeScene(scenes::Scene& scene, const std::string& integrator, const TimingOptions& timing) {
  Timed timed;
  timed.cost = measureStepCost(scene, integrator, scene.dt, timing);
  timed.particles = scene.system->size();
  timed.constraints = static_cast<long>(scene.system->constraints().size());
  timed.forces = static_cast<long>(scene.system->forceObjects().size());
  timed.dt = scene.dt;
  return timed;
}

// One size of one scene family under one integrator.
struct SizeCell {
  std::string integrator;
  bool cloth;  // the 8-way cloth of side `size`, else the test chain of `size` particles
  int size;
};

// Per integrator: every chain, then every cloth.
std::vector<SizeCell> sizeCells(const TimingPlan& plan, const std::vector<std::string>& integrators) {
  std::vector<SizeCell> cells;
  for (const auto& name : integrators) {
    for (int length : plan.chains) cells.push_back({name, false, length});
    for (int side : plan.cloths) cells.push_back({name, true, side});
  }
  return cells;
}

// The largest cloths are timed over fewer, shorter repeats.
TimingOptions clothTiming(int side, const TimingOptions& timing) {
  TimingOptions small = timing;
  if (side >= 128) small.repeats = std::min(timing.repeats, 3), small.steps = std::min(timing.steps, 4);
  return small;
}

Timed timeSizeCell(const SizeCell& cell, const TimingOptions& timing) {
  if (!cell.cloth) {
    scenes::Scene chain = buildChain({cell.size});
    return timeScene(chain, cell.integrator, timing);
  }
  const std::string side = std::to_string(cell.size);
  scenes::Scene cloth = buildLabScene("cloth", {{"width", side}, {"height", side}, {"links", "8"}});
  return timeScene(cloth, cell.integrator, clothTiming(cell.size, timing));
}

// Sizes and step times per integrator, the points of the growth fits.
struct Growth {
  std::map<std::string, std::vector<double>> chainN, chainT, clothN, clothT;
};

Growth writeSizeRows(const LabOptions& options, const TimingPlan& plan, const std::vector<SizeCell>& cells,
                     const Results<Timed>& results) {
  Csv csv(
      options, "timing.csv",
      {"scene", "integrator", "particles", "constraints", "springs", "dt", "step_seconds", "cg_iterations_per_step"});
  Growth growth;
  for (const auto& [k, timed] : results) {
    const SizeCell& cell = cells[k];
    const StepCost& cost = timed.cost;
    if (!cell.cloth) {
      csv << "test-chain" << cell.integrator << static_cast<long>(cell.size) << timed.constraints << timed.forces
          << timed.dt << cost.seconds << cost.cgIterations;
      csv.endRow();
      growth.chainN[cell.integrator].push_back(cell.size);
      growth.chainT[cell.integrator].push_back(cost.seconds);
      continue;
    }
    recordValue(options, "timing.cloth" + std::to_string(cell.size) + "." + cell.integrator + "_ms",
                general(cost.seconds * 1e3, 3));
    csv << "cloth-8" << cell.integrator << timed.particles << timed.constraints << timed.forces << timed.dt
        << cost.seconds << cost.cgIterations;
    csv.endRow();
    if (cell.size >= plan.slopeFromSide) {
      growth.clothN[cell.integrator].push_back(timed.particles);
      growth.clothT[cell.integrator].push_back(cost.seconds);
    }
  }
  return growth;
}

// Growth: fitted log–log slope of cost against size.
void writeGrowth(const LabOptions& options, const TimingPlan& plan, const std::vector<std::string>& integrators,
                 Growth& growth) {
  Rows rows;
  Csv slopes(options, "timing_slopes.csv", {"integrator", "chain_slope", "cloth_slope"});
  for (const auto& name : integrators) {
    const double chainSlope = logLogSlope(growth.chainN[name], growth.chainT[name]);
    const double clothSlope = logLogSlope(growth.clothN[name], growth.clothT[name]);
    slopes << name << chainSlope << clothSlope;
    slopes.endRow();
    rows.push_back({name, fixed(chainSlope, 2), fixed(clothSlope, 2)});
    recordValue(options, "timing.slope.cloth." + name, fixed(clothSlope, 2));
  }
  writeTable(options, "timing_growth", plan.growthTitle, {"integrator", "chain (particles)", "8-way cloth (particles)"},
             rows);
}

// Constraint solvers compared on the test chain under RK4: cost per step, CG
// iterations, and the rod stretch they leave after a short run.
struct SolverVariant {
  const char* name;
  particles::SolveMethod method;
  particles::Preconditioner preconditioner;
  bool warmStart;
};
const SolverVariant kSolverVariants[] = {
    {"plain CG, cold start", particles::SolveMethod::ConjugateGradient, particles::Preconditioner::None, false},
    {"Jacobi CG, warm start", particles::SolveMethod::ConjugateGradient, particles::Preconditioner::Jacobi, true},
    {"incomplete-Cholesky CG", particles::SolveMethod::ConjugateGradient,
     particles::Preconditioner::IncompleteCholesky, true},
    {"direct LDLT", particles::SolveMethod::Direct, particles::Preconditioner::None, false},
};
constexpr std::size_t kVariantCount = sizeof(kSolverVariants) / sizeof(kSolverVariants[0]);

scenes::Scene solverChain(const SolverVariant& variant, int length) {
  scenes::Scene chain = buildChain({length});
  auto& settings = chain.system->solver().settings;
  settings.method = variant.method;
  settings.preconditioner = variant.preconditioner;
  settings.warmStart = variant.warmStart;
  return chain;
}

// The step cost, and the max stretch of a short run (nullopt: cut short).
using SolverMeasure = std::pair<StepCost, double>;
std::optional<SolverMeasure> measureSolver(const SolverVariant& variant, int length, double duration,
                                           const TimingOptions& timing) {
  scenes::Scene timedChain = solverChain(variant, length);
  const StepCost cost = measureStepCost(timedChain, "rk4", timedChain.dt, timing);
  scenes::Scene runChain = solverChain(variant, length);
  auto rk4 = particles::makeIntegrator("rk4");
  const RunResult run = simulate(runChain, *rk4, runChain.dt, duration);
  if (run.cutShort) return std::nullopt;
  return std::pair{cost, run.maxRelativeStretch};
}

// Cell k is variant k / lengths, chain length k % lengths.
void writeSolvers(const LabOptions& options, const TimingPlan& plan, const Results<SolverMeasure>& results) {
  const std::vector<int>& lengths = plan.solverLengths;
  Csv solvers(options, "timing_solvers.csv",
              {"solver", "chain_length", "step_seconds", "cg_iterations_per_step", "max_relative_stretch"});
  Rows rows;
  std::map<std::string, std::map<int, double>> solverCost;
  for (std::size_t v = 0; v < kVariantCount; ++v) {
    const SolverVariant& variant = kSolverVariants[v];
    std::vector<std::string> row{variant.name};
    for (std::size_t l = 0; l < lengths.size(); ++l) {
      const auto found = results.find(v * lengths.size() + l);
      if (found == results.end()) continue;  // another shard's cell, or cut short
      const auto& [cost, stretch] = found->second;
      solvers << std::string(variant.name) << static_cast<long>(lengths[l]) << cost.seconds << cost.cgIterations
              << stretch;
      solvers.endRow();
      solverCost[variant.name][lengths[l]] = cost.seconds;
      row.push_back(general(cost.seconds * 1e6, 3) + " µs, " + general(cost.cgIterationsPerSolve(), 3) +
                    " it, stretch " + general(stretch, 2));
    }
    rows.push_back(row);
  }
  std::vector<std::string> header{"solver"};
  for (int length : lengths)
    header.push_back("chain " + std::to_string(length) + ": RK4 step, CG it/solve, max stretch");
  for (int length : lengths) {
    const std::string key = "timing.solvers.chain" + std::to_string(length);
    recordValue(options, key + ".direct_us", general(solverCost["direct LDLT"][length] * 1e6, 3));
    recordValue(options, key + ".plain_cg_us", general(solverCost["plain CG, cold start"][length] * 1e6, 3));
    recordValue(options, key + ".plain_cg_over_direct",
                general(solverCost["plain CG, cold start"][length] / solverCost["direct LDLT"][length], 3));
  }
  writeTable(options, "timing_solvers", "Constraint solvers on the test chain (RK4, tolerance 1e-8)", header, rows);
}

// Table 3: ms per step of the 80-particle chain at dt 0.1 and 0.2; cell k is
// integrator k / 2 at kTable3Steps[k % 2].
const double kTable3Steps[2] = {0.1, 0.2};

void writeTable3(const LabOptions& options, const std::vector<std::string>& integrators,
                 const Results<StepCost>& results) {
  const std::map<std::string, std::vector<std::string>> seedTable3 = {
      {"symplectic-euler", {"2", "2"}}, {"midpoint", {"5", "5"}}, {"rk4", {"10", "9"}}};
  Rows table3;
  Csv table3Csv(options, "table3_step_cost.csv", {"integrator", "dt", "step_ms", "cg_iterations_per_step"});
  for (std::size_t i = 0; i < integrators.size(); ++i) {
    const std::string& name = integrators[i];
    std::vector<std::string> row{name};
    for (std::size_t s = 0; s < 2; ++s) {
      const auto found = results.find(2 * i + s);
      if (found == results.end()) continue;  // another shard's cell
      const StepCost& cost = found->second;
      table3Csv << name << kTable3Steps[s] << cost.seconds * 1e3 << cost.cgIterations;
      table3Csv.endRow();
      row.push_back(std::isfinite(cost.seconds) ? general(cost.seconds * 1e3, 3) : "diverges");
    }
    const auto seed = seedTable3.find(name);
    for (int k = 0; k < 2; ++k) row.push_back(seed != seedTable3.end() ? seed->second[k] : "–");
    table3.push_back(row);
  }
  writeTable(options, "table3", "Table 3: milliseconds per step, 80-particle chain",
             {"integrator", "dt 0.1", "dt 0.2", "seed dt 0.1", "seed dt 0.2"}, table3);
}

}  // namespace

int runTiming(const LabOptions& options, const TimingOptions& timing) {
  prepareOutput(options);
  const auto integrators = selectedIntegrators(options);
  const TimingPlan plan = options.quick ? quickPlan() : fullPlan();
  Progress progress(options, "timing", static_cast<long>(integrators.size() * (plan.chains.size() + plan.cloths.size() + 2)));
  recordValue(options, "timing.adaptive_tolerance", general(particles::IntegratorSettings{}.tolerance));

  // Timed one cell at a time: a step's wall time is the measurement.
  const std::vector<SizeCell> sizes = sizeCells(plan, integrators);
  const auto timed = resultsInTurn<Timed>(
      options, sizes.size(), [&](std::size_t k) { return timeSizeCell(sizes[k], timing); }, true,
      [&](std::size_t) { progress.tick(); });
  Growth growth = writeSizeRows(options, plan, sizes, timed);

  const std::vector<int>& lengths = plan.solverLengths;
  const auto solvers = resultsInTurn<SolverMeasure>(
      options, kVariantCount * lengths.size(),
      [&](std::size_t k) {
        return measureSolver(kSolverVariants[k / lengths.size()], lengths[k % lengths.size()], plan.solverRunDuration,
                             timing);
      },
      true);
  writeSolvers(options, plan, solvers);
  writeGrowth(options, plan, integrators, growth);

  const auto table3 = resultsInTurn<StepCost>(
      options, 2 * integrators.size(),
      [&](std::size_t k) {
        scenes::Scene chain = buildChain({80});
        return measureStepCost(chain, integrators[k / 2], kTable3Steps[k % 2], timing);
      },
      false, [&](std::size_t k) { if (k % 2 == 1) progress.tick(2); });
  writeTable3(options, integrators, table3);
  return interrupted() ? 130 : 0;
}

}  // namespace lab
