// `particle-lab timing`: cost per step against chain length and cloth size for
// each integrator, and the seed report's Table 3.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>

#include "lab/cells.h"
#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/lab_scene.h"
#include "lab/results.h"

namespace lab {

namespace {

// One configuration during the measurement: its stepper, warmed-up state and tallies.
struct Timing {
  std::unique_ptr<particles::Integrator> stepper;
  particles::Snapshot warm;
  std::vector<double> perRepeat;
  double iterations = 0.0, solves = 0.0;
  long counted = 0;
  bool failed = false;
};

// `steps` timed steps of one configuration: the mean step time joins its repeats.
void timeRepeat(TimedStep& c, Timing& t, int steps) {
  using Clock = std::chrono::steady_clock;
  particles::ParticleSystem& system = *c.scene.system;
  double seconds = 0.0;
  int done = 0;
  for (int k = 0; k < steps; ++k) {
    const auto start = Clock::now();
    const particles::StepStats stats = system.step(*t.stepper, c.dt);
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    if (!system.finite()) {
      system.restore(t.warm);
      continue;
    }
    seconds += elapsed;
    t.iterations += stats.cgIterations;
    t.solves += stats.solves;
    ++done, ++t.counted;
  }
  if (done > 0) t.perRepeat.push_back(seconds / done);
}

StepCost costOf(const Timing& t) {
  if (t.failed || t.perRepeat.empty()) return {std::nan(""), std::nan(""), std::nan(""), std::nan(""), std::nan("")};
  const double steps = static_cast<double>(std::max(1L, t.counted));
  return {median(t.perRepeat), t.iterations / steps, t.solves / steps,
          *std::min_element(t.perRepeat.begin(), t.perRepeat.end()),
          *std::max_element(t.perRepeat.begin(), t.perRepeat.end())};
}

}  // namespace

std::vector<StepCost> measureInterleaved(std::vector<TimedStep>& configurations, const TimingOptions& timing) {
  std::vector<Timing> timings(configurations.size());
  for (std::size_t k = 0; k < configurations.size(); ++k) {
    TimedStep& c = configurations[k];
    Timing& t = timings[k];
    t.stepper = particles::makeIntegrator(c.integrator);
    for (int s = 0; s < 3; ++s) c.scene.system->step(*t.stepper, c.dt);
    t.failed = !c.scene.system->finite();
    if (!t.failed) t.warm = c.scene.system->snapshot();
  }
  for (int r = 0; r < timing.repeats; ++r)
    for (std::size_t k = 0; k < configurations.size(); ++k)
      if (!timings[k].failed) timeRepeat(configurations[k], timings[k], timing.steps);
  std::vector<StepCost> costs;
  for (const Timing& t : timings) costs.push_back(costOf(t));
  return costs;
}

StepCost measureStepCost(scenes::Scene& scene, const std::string& integrator, double dt,
                         const TimingOptions& timing) {
  std::vector<TimedStep> one(1);
  one[0] = {std::move(scene), integrator, dt};
  const StepCost cost = measureInterleaved(one, timing).front();
  scene = std::move(one[0].scene);
  return cost;
}

std::string costText(const StepCost& cost, double scale) {
  if (!std::isfinite(cost.seconds)) return "diverges";
  return general(cost.seconds * scale, 3) + " (" + general(cost.minSeconds * scale, 2) + "–" +
         general(cost.maxSeconds * scale, 2) + ")";
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


// One size of one scene family, timed under every integrator interleaved.
struct SizeCell {
  bool cloth;  // the 8-way cloth of side `size`, else the test chain of `size` particles
  int size;
};

// Every chain, then every cloth.
std::vector<SizeCell> sizeCells(const TimingPlan& plan) {
  std::vector<SizeCell> cells;
  for (int length : plan.chains) cells.push_back({false, length});
  for (int side : plan.cloths) cells.push_back({true, side});
  return cells;
}

// The largest cloths are timed over shorter repeats.
TimingOptions clothTiming(int side, const TimingOptions& timing) {
  TimingOptions small = timing;
  if (side >= 128) small.steps = std::min(timing.steps, 4);
  return small;
}

scenes::Scene sizeScene(const SizeCell& cell) {
  if (!cell.cloth) return buildChain({cell.size});
  const std::string side = std::to_string(cell.size);
  return buildLabScene("cloth", {{"width", side}, {"height", side}, {"links", "8"}});
}

// Timed per integrator (in the order given).
std::vector<Timed> timeSizeCell(const SizeCell& cell, const std::vector<std::string>& integrators,
                                const TimingOptions& timing) {
  std::vector<TimedStep> configurations;
  std::vector<Timed> out;
  for (const auto& name : integrators) {
    scenes::Scene scene = sizeScene(cell);
    Timed timed;
    timed.particles = scene.system->size();
    timed.constraints = static_cast<long>(scene.system->constraints().size());
    timed.forces = static_cast<long>(scene.system->forceObjects().size());
    timed.dt = scene.dt;
    out.push_back(timed);
    configurations.push_back({std::move(scene), name, timed.dt});
  }
  const std::vector<StepCost> costs =
      measureInterleaved(configurations, cell.cloth ? clothTiming(cell.size, timing) : timing);
  for (std::size_t k = 0; k < out.size(); ++k) out[k].cost = costs[k];
  return out;
}

// Sizes and step times per integrator, the points of the growth fits.
struct Growth {
  std::map<std::string, std::vector<double>> chainN, chainT, clothN, clothT;
};

Growth writeSizeRows(const LabOptions& options, const TimingPlan& plan, const std::vector<SizeCell>& cells,
                     const std::vector<std::string>& integrators, const Results<std::vector<Timed>>& results) {
  Csv csv(options, "timing.csv",
          {"scene", "integrator", "particles", "constraints", "springs", "dt", "step_seconds", "step_seconds_min",
           "step_seconds_max", "cg_iterations_per_step"});
  Growth growth;
  for (const auto& [k, timings] : results) {
    const SizeCell& cell = cells[k];
    for (std::size_t i = 0; i < timings.size() && i < integrators.size(); ++i) {
      const Timed& timed = timings[i];
      const StepCost& cost = timed.cost;
      const std::string& name = integrators[i];
      csv << (cell.cloth ? "cloth-8" : "test-chain") << name << timed.particles << timed.constraints << timed.forces
          << timed.dt << cost.seconds << cost.minSeconds << cost.maxSeconds << cost.cgIterations;
      csv.endRow();
      if (!cell.cloth) {
        growth.chainN[name].push_back(cell.size);
        growth.chainT[name].push_back(cost.seconds);
        continue;
      }
      recordValue(options, "timing.cloth" + std::to_string(cell.size) + "." + name + "_ms",
                  general(cost.seconds * 1e3, 3));
      if (cell.size >= plan.slopeFromSide) {
        growth.clothN[name].push_back(timed.particles);
        growth.clothT[name].push_back(cost.seconds);
      }
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

// Per variant: the step cost (the variants timed interleaved), and the max
// stretch of a short run (nullopt: cut short).
using SolverMeasure = std::pair<StepCost, double>;
std::optional<std::vector<SolverMeasure>> measureSolvers(int length, double duration, const TimingOptions& timing) {
  std::vector<TimedStep> configurations;
  for (const SolverVariant& variant : kSolverVariants) {
    scenes::Scene chain = solverChain(variant, length);
    const double dt = chain.dt;
    configurations.push_back({std::move(chain), "rk4", dt});
  }
  const std::vector<StepCost> costs = measureInterleaved(configurations, timing);
  std::vector<SolverMeasure> out;
  for (std::size_t v = 0; v < kVariantCount; ++v) {
    scenes::Scene runChain = solverChain(kSolverVariants[v], length);
    auto rk4 = particles::makeIntegrator("rk4");
    const RunResult run = simulate(runChain, *rk4, runChain.dt, duration);
    if (run.cutShort) return std::nullopt;
    out.push_back({costs[v], run.maxRelativeStretch});
  }
  return out;
}

// Cell l is chain length l, every variant.
void writeSolvers(const LabOptions& options, const TimingPlan& plan, const Results<std::vector<SolverMeasure>>& results) {
  const std::vector<int>& lengths = plan.solverLengths;
  Csv solvers(options, "timing_solvers.csv",
              {"solver", "chain_length", "step_seconds", "step_seconds_min", "step_seconds_max",
               "cg_iterations_per_step", "max_relative_stretch"});
  Rows rows;
  std::map<std::string, std::map<int, double>> solverCost;
  for (std::size_t v = 0; v < kVariantCount; ++v) {
    const SolverVariant& variant = kSolverVariants[v];
    std::vector<std::string> row{variant.name};
    for (std::size_t l = 0; l < lengths.size(); ++l) {
      const auto found = results.find(l);
      if (found == results.end()) continue;  // another shard's cell, or cut short
      const auto& [cost, stretch] = found->second[v];
      solvers << std::string(variant.name) << static_cast<long>(lengths[l]) << cost.seconds << cost.minSeconds
              << cost.maxSeconds << cost.cgIterations << stretch;
      solvers.endRow();
      solverCost[variant.name][lengths[l]] = cost.seconds;
      row.push_back(costText(cost, 1e6) + " µs, " + general(cost.cgIterationsPerSolve(), 3) + " it, stretch " +
                    general(stretch, 2));
    }
    rows.push_back(row);
  }
  std::vector<std::string> header{"solver"};
  for (int length : lengths)
    header.push_back("chain " + std::to_string(length) + ": RK4 step, median (min–max), CG it/solve, max stretch");
  for (int length : lengths) {
    const std::string key = "timing.solvers.chain" + std::to_string(length);
    recordValue(options, key + ".direct_us", general(solverCost["direct LDLT"][length] * 1e6, 3));
    recordValue(options, key + ".plain_cg_us", general(solverCost["plain CG, cold start"][length] * 1e6, 3));
    recordValue(options, key + ".plain_cg_over_direct",
                general(solverCost["plain CG, cold start"][length] / solverCost["direct LDLT"][length], 3));
  }
  writeTable(options, "timing_solvers",
             "Constraint solvers on the test chain (RK4, tolerance 1e-8), timed interleaved", header, rows);
}

// Table 3: ms per step of the 80-particle chain at dt 0.1 and 0.2, one cell
// timing every integrator at both interleaved: entry 2i + s is integrator i at kTable3Steps[s].
const double kTable3Steps[2] = {0.1, 0.2};

std::vector<StepCost> measureTable3(const std::vector<std::string>& integrators, const TimingOptions& timing) {
  std::vector<TimedStep> configurations;
  for (const auto& name : integrators)
    for (double dt : kTable3Steps) configurations.push_back({buildChain({80}), name, dt});
  return measureInterleaved(configurations, timing);
}

void writeTable3(const LabOptions& options, const std::vector<std::string>& integrators,
                 const Results<std::vector<StepCost>>& results) {
  const std::map<std::string, std::vector<std::string>> seedTable3 = {
      {"symplectic-euler", {"2", "2"}}, {"midpoint", {"5", "5"}}, {"rk4", {"10", "9"}}};
  Rows table3;
  Csv table3Csv(options, "table3_step_cost.csv",
                {"integrator", "dt", "step_ms", "step_ms_min", "step_ms_max", "cg_iterations_per_step"});
  const auto found = results.find(0);
  if (found == results.end()) return;  // another shard's cell, or cut short
  for (std::size_t i = 0; i < integrators.size(); ++i) {
    const std::string& name = integrators[i];
    std::vector<std::string> row{name};
    for (std::size_t s = 0; s < 2; ++s) {
      const StepCost& cost = found->second[2 * i + s];
      table3Csv << name << kTable3Steps[s] << cost.seconds * 1e3 << cost.minSeconds * 1e3 << cost.maxSeconds * 1e3
                << cost.cgIterations;
      table3Csv.endRow();
      row.push_back(costText(cost, 1e3));
    }
    const auto seed = seedTable3.find(name);
    for (int k = 0; k < 2; ++k) row.push_back(seed != seedTable3.end() ? seed->second[k] : "–");
    table3.push_back(row);
  }
  writeTable(options, "table3",
             "Table 3: milliseconds per step, 80-particle chain: median of repeats (min–max), every integrator and "
             "dt timed interleaved",
             {"integrator", "dt 0.1", "dt 0.2", "seed dt 0.1", "seed dt 0.2"}, table3);
}

}  // namespace

int runTiming(const LabOptions& options, const TimingOptions& timing) {
  prepareOutput(options, "timing.");
  const auto integrators = selectedIntegrators(options);
  const TimingPlan plan = options.quick ? quickPlan() : fullPlan();
  Progress progress(options, "timing", static_cast<long>(integrators.size() * (plan.chains.size() + plan.cloths.size() + 2)));
  recordValue(options, "timing.adaptive_tolerance", general(particles::IntegratorSettings{}.dopri5.tolerance));

  // Timed one cell at a time: a step's wall time is the measurement. Within
  // a cell the configurations compared are timed interleaved.
  const std::vector<SizeCell> sizes = sizeCells(plan);
  const auto timed = resultsInTurn<std::vector<Timed>>(
      options, sizes.size(), [&](std::size_t k) { return timeSizeCell(sizes[k], integrators, timing); }, true,
      [&](std::size_t) { progress.tick(static_cast<long>(integrators.size())); });
  Growth growth = writeSizeRows(options, plan, sizes, integrators, timed);

  const std::vector<int>& lengths = plan.solverLengths;
  const auto solvers = resultsInTurn<std::vector<SolverMeasure>>(
      options, lengths.size(),
      [&](std::size_t k) { return measureSolvers(lengths[k], plan.solverRunDuration, timing); }, true);
  writeSolvers(options, plan, solvers);
  writeGrowth(options, plan, integrators, growth);

  const auto table3 = resultsInTurn<std::vector<StepCost>>(
      options, 1, [&](std::size_t) { return measureTable3(integrators, timing); }, false,
      [&](std::size_t) { progress.tick(2 * static_cast<long>(integrators.size())); });
  writeTable3(options, integrators, table3);
  return interrupted() ? 130 : 0;
}

}  // namespace lab
