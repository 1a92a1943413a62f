// `particle-lab extremes`: stability at the extremes — stiff springs, heavy
// tips on light chains, the constraint feedback gains, a starved CG, the two
// rod forms, and the taut chain between two wires.
#include <cmath>
#include <iostream>
#include <limits>
#include <map>

#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/lab_scene.h"
#include "lab/cells.h"
#include "lab/results.h"
#include "output/format_number.h"

namespace lab {

namespace {

using Rows = std::vector<std::vector<std::string>>;

// 1. Spring stiffness: the safe dt of the 8-way cloth against k_s.
struct StiffnessSection {
  std::vector<double> stiffness;  // k_s swept
  double duration;                // T, s
  int clothSide;                  // particles per side
};
// 2. Mass ratio: a heavy tip on a light chain.
struct MassRatioSection {
  std::vector<double> ratios;  // tip mass / link mass
  double duration;
  int length;                  // chain particles
  double gridLo;               // the scanned grid's smallest dt (up to 0.5)
};
// 3. Constraint feedback gains k_s, k_d of the solver (RK4, test chain).
struct FeedbackSection {
  std::vector<double> stiffness, damping;
  double duration, dt;
  int length;
};
// 4. CG budget: tolerance × iteration cap (RK4, test chain).
struct BudgetSection {
  std::vector<double> tolerances;
  std::vector<int> caps;  // 0: uncapped
  double duration, dt;
  int length;
};
// 5. Squared against root rods.
struct RodFormSection {
  double duration;
  double gridLo;            // the scanned grid's smallest dt (up to 0.5)
  int scanLength;           // the chain whose safe dt is scanned
  int runLength;            // the chain whose step is timed
  TimingOptions timing;     // of that step
};
// 6. The taut chain under each integrator and solver budget.
struct TautSection {
  std::vector<int> caps;  // CG with an iteration cap (0: uncapped), and −1 for the direct solve
  double duration;
};

// What the experiment runs, section by section.
struct ExtremesPlan {
  StiffnessSection stiffness;
  MassRatioSection massRatio;
  FeedbackSection feedback;
  BudgetSection budget;
  RodFormSection rodForm;
  TautSection taut;
  long progressPerIntegrator, progressFixed;  // the progress estimate: cells per integrator, and others
};

// Small scenes, short runs: proves the code runs.
ExtremesPlan quickPlan() {
  return {{{1, 100}, 1.0, 4},
          {{1, 100}, 1.0, 6, 0.0125},
          {{0, 60}, {0, 10}, 1.0, 0.02, 6},
          {{1e-2, 1e-8}, {2, 0}, 1.0, 0.01, 12},
          {1.0, 0.0125, 6, 12, {1, 5}},
          {{0, -1}, 1.0},
          8,
          30};
}

ExtremesPlan fullPlan() {
  return {{logSpace(1, 1e5, 6), 5.0, 10},
          {logSpace(1, 1e4, 5), 10.0, 24, 0.05 / 32},
          {{0, 1, 10, 60, 100, 1000, 10000}, {0, 1, 3, 10, 30, 100, 300}, 20.0, 0.05, 24},
          {logSpace(1e-10, 1e-2, 5), {1, 2, 5, 10, 20, 50, 0}, 20.0, 0.01, 80},
          {20.0, 0.05 / 16, 24, 80, {5, 20}},
          {{5, 20, 0, -1}, 20.0},
          20,
          170};
}

// What every section shares.
struct Context {
  const LabOptions& options;
  const ExtremesPlan& plan;
  std::vector<std::string> integrators;
  std::vector<std::string> scanned;  // scanned sections leave out adaptive schemes: their dt is only a call interval
  // Safe steps by scanning a 5% log grid (scan.h) over the lab's ensemble of
  // starts (the scene as built and starts perturbed by 1e-6 of its size), as
  // every safe boundary of the report is.
  ScanSettings scan;
  std::string starts;  // "N starts"
  Progress& progress;
};

// A table's body: one row per integrator, its name and then its cells.
Rows integratorRows(const std::vector<std::string>& integrators,
                    std::map<std::string, std::vector<std::string>>& cells) {
  Rows table;
  for (const auto& name : integrators) {
    std::vector<std::string> row{name};
    row.insert(row.end(), cells[name].begin(), cells[name].end());
    table.push_back(row);
  }
  return table;
}

// A cell of a scanned section: an integrator at one value of the swept parameter.
struct SweptCell {
  std::string integrator;
  double value;
};

std::vector<SweptCell> sweptCells(const std::vector<std::string>& integrators, const std::vector<double>& values) {
  std::vector<SweptCell> cells;
  for (const auto& name : integrators)
    for (double value : values) cells.push_back({name, value});
  return cells;
}

// 1. Spring stiffness, scanned over the window 0.3/√k_s … 10/√k_s (capped at
//    0.5) around the spring's time scale, continued a decade lower when its
//    bottom fails.
scenes::Scene stiffCloth(const StiffnessSection& section, double ks) {
  const std::string side = std::to_string(section.clothSide);
  return buildLabScene("cloth", {{"width", side}, {"height", side}, {"links", "8"}, {"stiffness", general(ks, 6)}});
}

double windowBottom(double ks) { return 0.3 / std::sqrt(ks); }

std::optional<Boundary> scanStiffness(const Context& context, const SweptCell& cell) {
  const StiffnessSection& section = context.plan.stiffness;
  ScanSettings window = context.scan;
  window.grid = stepGrid(windowBottom(cell.value), std::min(0.5, 10.0 / std::sqrt(cell.value)));
  window.extendDecades = 1;
  return scanSafeStep([&] { return stiffCloth(section, cell.value); }, cell.integrator, section.duration, window,
                      context.options.criterion);
}

void writeStiffness(const Context& context, const std::vector<SweptCell>& cells, const Results<Boundary>& results) {
  const StiffnessSection& section = context.plan.stiffness;
  Csv csv(context.options, "extremes_stiffness.csv",
          {"integrator", "stiffness", "largest_surviving_dt", "first_failure_dt", "first_failure", "grid_lo", "grid_hi"});
  std::map<std::string, std::vector<std::string>> rows;
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> resolved;  // (k_s, dt) on the grid
  for (const auto& [k, boundary] : results) {
    csv << cells[k].integrator << cells[k].value << boundary.safeDt << boundary.firstFailureDt
        << failureName(boundary.firstFailure) << boundary.lowest << boundary.highest;
    csv.endRow();
    rows[cells[k].integrator].push_back(safeStepText(boundary));
    if (cells[k].value >= 10.0 && !boundary.belowGrid() && !boundary.aboveGrid()) {
      resolved[cells[k].integrator].first.push_back(cells[k].value);
      resolved[cells[k].integrator].second.push_back(boundary.safeDt);
    }
  }
  if (interrupted()) return;
  // How the largest surviving dt falls with k_s once the springs dominate (k_s ≥ 10): the fitted
  // slope of log dt against log k_s over the entries resolved on the grid (−½: the oscillation
  // limit ω h; −1: kept alive only by damping), which the report's discussion quotes.
  for (const auto& [name, points] : resolved)
    if (points.first.size() >= 2)
      recordValue(context.options, "extremes.stiffness_slope." + name, fixed(logLogSlope(points.first, points.second), 2));
  std::vector<std::string> header{"integrator"};
  for (double ks : section.stiffness) header.push_back("k_s " + general(ks));
  const std::string side = std::to_string(section.clothSide);
  writeTable(context.options, "extremes_stiffness",
             "Largest surviving dt (coarse scan) of the " + side + "×" + side + " 8-way cloth against spring stiffness, T = " +
                 general(section.duration) + " s, " + context.starts,
             header, integratorRows(context.scanned, rows));
}

void runStiffness(Context& context) {
  const std::vector<SweptCell> cells = sweptCells(context.scanned, context.plan.stiffness.stiffness);
  const auto results = sweepResults<Boundary>(
      context.options, cells.size(),
      [&](std::size_t k) {
        auto boundary = scanStiffness(context, cells[k]);
        context.progress.tick();
        return boundary;
      },
      [&](std::size_t k) {  // the scan's steps are dominated by its smallest dt
        const SweptCell& cell = cells[k];
        return estimatedRunSeconds(stiffCloth(context.plan.stiffness, cell.value), cell.integrator,
                                   windowBottom(cell.value), context.plan.stiffness.duration);
      });
  writeStiffness(context, cells, results);
}

// 2. Mass ratio: the safe dt, and the iterations of Jacobi CG, which show how
//    the mass ratio conditions J W Jᵀ.
ChainSpec heavyTipChain(const MassRatioSection& section, double ratio) {
  ChainSpec spec{section.length};
  spec.extra["tip-mass-ratio"] = general(ratio, 6);
  return spec;
}

ScanSettings massRatioWindow(const Context& context) {
  ScanSettings window = context.scan;
  window.grid = stepGrid(context.plan.massRatio.gridLo, 0.5);
  return window;
}

using MassRatioResult = std::pair<Boundary, double>;  // the boundary, CG iterations per step

std::optional<MassRatioResult> measureMassRatio(const Context& context, const SweptCell& cell) {
  const MassRatioSection& section = context.plan.massRatio;
  const ChainSpec spec = heavyTipChain(section, cell.value);
  auto boundary = scanSafeStep([&] { return buildChain(spec); }, cell.integrator, section.duration,
                               massRatioWindow(context), context.options.criterion);
  context.progress.tick();
  if (!boundary) return std::nullopt;
  scenes::Scene chain = buildChain(spec);
  chain.system->solver().settings.method = particles::SolveMethod::ConjugateGradient;
  const StepCost cost = measureStepCost(chain, cell.integrator, chain.dt, {1, 5});
  return MassRatioResult{*boundary, cost.cgIterations};
}

void writeMassRatio(const Context& context, const std::vector<SweptCell>& cells,
                    const Results<MassRatioResult>& results) {
  const MassRatioSection& section = context.plan.massRatio;
  Csv csv(context.options, "extremes_mass_ratio.csv",
          {"integrator", "mass_ratio", "largest_surviving_dt", "first_failure_dt", "first_failure", "cg_iterations_per_step"});
  std::map<std::string, std::vector<std::string>> rows;
  for (const auto& [k, result] : results) {
    const Boundary& boundary = result.first;
    csv << cells[k].integrator << cells[k].value << boundary.safeDt << boundary.firstFailureDt
        << failureName(boundary.firstFailure) << result.second;
    csv.endRow();
    rows[cells[k].integrator].push_back(safeStepText(boundary) + " (" + general(result.second, 3) + " it)");
  }
  if (interrupted()) return;
  std::vector<std::string> header{"integrator"};
  for (double ratio : section.ratios) header.push_back("tip/link mass " + general(ratio));
  writeTable(context.options, "extremes_mass_ratio",
             "Largest surviving dt (coarse scan) of the " + std::to_string(section.length) + "-chain, T = " + general(section.duration) + " s, " +
                 context.starts + " (and Jacobi-CG iterations per step at the default dt) against tip mass ratio",
             header, integratorRows(context.scanned, rows));
}

void runMassRatio(Context& context) {
  const MassRatioSection& section = context.plan.massRatio;
  const std::vector<SweptCell> cells = sweptCells(context.scanned, section.ratios);
  const double gridLo = massRatioWindow(context).grid.front();
  const auto results = sweepResults<MassRatioResult>(
      context.options, cells.size(), [&](std::size_t k) { return measureMassRatio(context, cells[k]); },
      [&](std::size_t k) {
        return estimatedRunSeconds(buildChain(heavyTipChain(section, cells[k].value)), cells[k].integrator, gridLo,
                                   section.duration);
      });
  writeMassRatio(context, cells, results);
}

// 3. Constraint feedback gains: cell k is stiffness k / dampings, damping k % dampings.
using FeedbackResult = std::pair<RunResult, double>;  // the run, its final max |C|/r

std::optional<FeedbackResult> runFeedback(const Context& context, double stiffness, double damping) {
  const FeedbackSection& section = context.plan.feedback;
  scenes::Scene chain = buildChain({section.length});
  chain.system->solver().settings.stiffness = stiffness;
  chain.system->solver().settings.damping = damping;
  auto stepper = particles::makeIntegrator("rk4");
  const RunResult run = simulate(chain, *stepper, section.dt, section.duration, context.options.criterion);
  context.progress.tick();
  if (run.cutShort) return std::nullopt;
  return std::pair{run, chain.system->maxRelativeConstraintError()};
}

void runFeedbackGains(Context& context) {
  const FeedbackSection& section = context.plan.feedback;
  const std::size_t dampings = section.damping.size();
  const auto results = resultsInTurn<FeedbackResult>(
      context.options, section.stiffness.size() * dampings,
      [&](std::size_t k) {
        return runFeedback(context, section.stiffness[k / dampings], section.damping[k % dampings]);
      },
      true);
  Csv csv(context.options, "extremes_feedback.csv",
          {"ks", "kd", "critical_kd", "survived", "failure", "max_relative_stretch", "final_relative_stretch"});
  for (const auto& [k, result] : results) {
    const double stiffness = section.stiffness[k / dampings], damping = section.damping[k % dampings];
    const RunResult& run = result.first;
    csv << stiffness << damping << 2.0 * std::sqrt(stiffness) << (run.failed ? 0L : 1L) << failureName(run.failure)
        << run.maxRelativeStretch << result.second;
    csv.endRow();
  }
  if (interrupted()) return;
  recordValue(context.options, "extremes.feedback.dt", general(section.dt));
  recordValue(context.options, "extremes.feedback.duration", general(section.duration));
}

// 4. CG budget: plain CG started cold (the cap really starves each solve) and warm.
struct BudgetCell {
  bool warm;
  double tolerance;
  int cap;
};

std::vector<BudgetCell> budgetCells(const BudgetSection& section) {
  std::vector<BudgetCell> cells;
  for (bool warm : {false, true})
    for (double tol : section.tolerances)
      for (int cap : section.caps) cells.push_back({warm, tol, cap});
  return cells;
}

std::optional<RunResult> runBudget(const Context& context, const BudgetCell& cell) {
  const BudgetSection& section = context.plan.budget;
  scenes::Scene chain = buildChain({section.length});
  auto& settings = chain.system->solver().settings;
  settings.tolerance = cell.tolerance;
  settings.method = particles::SolveMethod::ConjugateGradient;
  settings.maxIterations = cell.cap;
  settings.warmStart = cell.warm;
  settings.preconditioner = particles::Preconditioner::None;
  auto stepper = particles::makeIntegrator("rk4");
  RunResult run = simulate(chain, *stepper, section.dt, section.duration, context.options.criterion);
  context.progress.tick();
  if (run.cutShort) return std::nullopt;
  return run;
}

void runCgBudget(Context& context) {
  const BudgetSection& section = context.plan.budget;
  const std::vector<BudgetCell> cells = budgetCells(section);
  const auto results = sweepResults<RunResult>(context.options, cells.size(),
                                               [&](std::size_t k) { return runBudget(context, cells[k]); });
  Csv csv(context.options, "extremes_cg_budget.csv",
          {"warm_start", "tolerance", "max_iterations", "survived", "failure", "max_relative_stretch",
           "cg_iterations_per_step"});
  for (const auto& [k, run] : results) {
    const BudgetCell& cell = cells[k];
    csv << static_cast<long>(cell.warm) << cell.tolerance << static_cast<long>(cell.cap) << (run.failed ? 0L : 1L)
        << failureName(run.failure) << run.maxRelativeStretch
        << static_cast<double>(run.work.cgIterations) / std::max(1L, run.steps);
    csv.endRow();
  }
  if (interrupted()) return;
  recordValue(context.options, "extremes.cg_budget.duration", general(section.duration));
  recordValue(context.options, "extremes.cg_budget.length", std::to_string(section.length));
}

// 5. Squared against root rods: cost, stretch and safe step.
struct RodFormCell {
  std::string integrator;
  std::string form;  // "squared" | "root"
};

std::vector<RodFormCell> rodFormCells(const std::vector<std::string>& integrators) {
  std::vector<RodFormCell> cells;
  for (const auto& name : integrators)
    for (const std::string form : {"squared", "root"}) cells.push_back({name, form});
  return cells;
}

ScanSettings rodFormWindow(const Context& context) {
  ScanSettings window = context.scan;
  window.grid = stepGrid(context.plan.rodForm.gridLo, 0.5);
  return window;
}

using RodFormCost = std::pair<StepCost, double>;  // the step cost, the max stretch of a run

std::optional<RodFormCost> measureRodForm(const Context& context, const RodFormCell& cell) {
  const RodFormSection& section = context.plan.rodForm;
  ChainSpec big{section.runLength, cell.form};
  scenes::Scene chain = buildChain(big);
  const StepCost cost = measureStepCost(chain, cell.integrator, chain.dt, section.timing);
  scenes::Scene fresh = buildChain(big);
  auto stepper = particles::makeIntegrator(cell.integrator);
  const RunResult run = simulate(fresh, *stepper, fresh.dt, section.duration, context.options.criterion);
  if (run.cutShort) return std::nullopt;
  return std::pair{cost, run.maxRelativeStretch};
}

Results<Boundary> scanRodForms(Context& context, const std::vector<RodFormCell>& cells) {
  const RodFormSection& section = context.plan.rodForm;
  const ScanSettings window = rodFormWindow(context);
  return sweepResults<Boundary>(
      context.options, cells.size(),
      [&](std::size_t k) {
        const ChainSpec spec{section.scanLength, cells[k].form};
        auto boundary = scanSafeStep([&] { return buildChain(spec); }, cells[k].integrator, section.duration, window,
                              context.options.criterion);
        context.progress.tick();
        return boundary;
      },
      [&](std::size_t k) {
        return estimatedRunSeconds(buildChain(ChainSpec{section.scanLength, cells[k].form}), cells[k].integrator,
                                   window.grid.front(), section.duration);
      });
}

void writeRodForms(const Context& context, const std::vector<RodFormCell>& cells, const Results<Boundary>& boundaries,
                   const Results<RodFormCost>& costs) {
  const RodFormSection& section = context.plan.rodForm;
  Csv csv(context.options, "extremes_rod_form.csv",
          {"integrator", "rod", "largest_surviving_dt", "step_seconds", "cg_iterations_per_step", "max_relative_stretch"});
  std::map<std::string, std::vector<std::string>> rows;
  for (const auto& [k, result] : costs) {
    const auto found = boundaries.find(k);
    const Boundary boundary = found != boundaries.end() ? found->second : Boundary{};
    const auto& [cost, stretch] = result;
    csv << cells[k].integrator << cells[k].form << boundary.safeDt << cost.seconds << cost.cgIterations << stretch;
    csv.endRow();
    auto& row = rows[cells[k].integrator];
    row.push_back(safeStepText(boundary));
    row.push_back(general(cost.seconds * 1e6, 3));
    row.push_back(general(stretch, 2));
  }
  if (interrupted()) return;
  writeTable(context.options, "extremes_rod_form",
             "Squared against root rods: largest surviving dt (" + std::to_string(section.scanLength) +
                 "-chain, T = " + general(section.duration) + " s, " + context.starts +
                 "), µs per step and max stretch at the scene's dt (" + std::to_string(section.runLength) + "-chain)",
             {"integrator", "squared: surviving dt", "squared: µs/step", "squared: max stretch", "root: surviving dt",
              "root: µs/step", "root: max stretch"},
             integratorRows(context.scanned, rows));
}

void runRodForms(Context& context) {
  const std::vector<RodFormCell> cells = rodFormCells(context.scanned);
  const Results<Boundary> boundaries = scanRodForms(context, cells);
  if (interrupted()) return;
  // The step cost is timed on this thread after the scans, so the timings
  // never share the machine with another cell.
  const auto costs = resultsInTurn<RodFormCost>(context.options, cells.size(),
                                                [&](std::size_t k) { return measureRodForm(context, cells[k]); }, true);
  writeRodForms(context, cells, boundaries, costs);
}

// 6. The taut chain (the seed report's explosion case): cell k is integrator k / caps, cap k % caps.
std::optional<RunResult> runTaut(const Context& context, const std::string& integrator, int cap) {
  scenes::Scene taut = buildLabScene("taut-chain");
  auto& settings = taut.system->solver().settings;
  if (cap >= 0) {
    settings.method = particles::SolveMethod::ConjugateGradient;
    settings.maxIterations = cap;
  }
  auto stepper = particles::makeIntegrator(integrator);
  RunResult run = simulate(taut, *stepper, taut.dt, context.plan.taut.duration, context.options.criterion);
  context.progress.tick();
  if (run.cutShort) return std::nullopt;
  return run;
}

std::string capText(int cap) {
  if (cap > 0) return "CG cap " + std::to_string(cap);
  return cap == 0 ? "CG uncapped" : "direct LDLT";
}

void writeTaut(const Context& context, const Results<RunResult>& results) {
  const TautSection& section = context.plan.taut;
  Csv csv(context.options, "extremes_taut_chain.csv",
          {"integrator", "max_iterations", "survived", "reason", "time", "max_relative_stretch",
           "cg_iterations_per_step"});
  Rows table;
  for (std::size_t i = 0; i < context.integrators.size(); ++i) {
    std::vector<std::string> row{context.integrators[i]};
    for (std::size_t column = 0; column < section.caps.size(); ++column) {
      const auto found = results.find(i * section.caps.size() + column);
      if (found == results.end()) continue;  // another shard's cell, or cut short
      const RunResult& run = found->second;
      csv << context.integrators[i] << static_cast<long>(section.caps[column]) << (run.failed ? 0L : 1L)
          << failureName(run.failure) << run.time << run.maxRelativeStretch
          << static_cast<double>(run.work.cgIterations) / std::max(1L, run.steps);
      csv.endRow();
      row.push_back(run.failed ? run.reason + " at t = " + general(run.time, 3)
                               : "held (stretch " + general(run.maxRelativeStretch, 2) + ")");
    }
    table.push_back(row);
  }
  if (interrupted()) return;
  std::vector<std::string> header{"integrator"};
  for (int cap : section.caps) header.push_back(capText(cap));
  writeTable(context.options, "extremes_taut_chain",
             "Taut chain between two wires, T = " + general(section.duration) + " s", header, table);
}

void runTautChain(Context& context) {
  const std::vector<int>& caps = context.plan.taut.caps;
  const auto results = resultsInTurn<RunResult>(
      context.options, context.integrators.size() * caps.size(),
      [&](std::size_t k) { return runTaut(context, context.integrators[k / caps.size()], caps[k % caps.size()]); },
      true);
  writeTaut(context, results);
}

// The sections in the order they run.
const std::vector<void (*)(Context&)> kSections = {runStiffness, runMassRatio, runFeedbackGains,
                                                   runCgBudget,  runRodForms,  runTautChain};

}  // namespace

int runExtremes(const LabOptions& options) {
  prepareOutput(options, "extremes.");
  const ExtremesPlan plan = options.quick ? quickPlan() : fullPlan();
  const auto integrators = selectedIntegrators(options);
  std::vector<std::string> scanned;
  for (const auto& name : integrators)
    if (!particles::requireIntegrator(name).usesTolerance) scanned.push_back(name);
  std::cout << describe(options.criterion) << "\n";
  const ScanSettings scan;
  Progress progress(options, "extremes",
                    static_cast<long>(integrators.size()) * plan.progressPerIntegrator + plan.progressFixed);
  Context context{options, plan, integrators, scanned, scan, output::plural(scan.members, "start"), progress};
  for (const auto section : kSections) {
    section(context);
    if (interrupted()) return 130;
  }
  recordValue(options, "extremes.members", std::to_string(scan.members));
  return 0;
}

}  // namespace lab
