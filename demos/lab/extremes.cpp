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
#include "format_number.h"

namespace lab {

namespace {

// A table's body: one row per integrator, its name and then its cells.
std::vector<std::vector<std::string>> integratorRows(const std::vector<std::string>& integrators,
                                                     std::map<std::string, std::vector<std::string>>& cells) {
  std::vector<std::vector<std::string>> table;
  for (const auto& name : integrators) {
    std::vector<std::string> row{name};
    row.insert(row.end(), cells[name].begin(), cells[name].end());
    table.push_back(row);
  }
  return table;
}

}  // namespace

int runExtremes(const LabOptions& options) {
  prepareOutput(options);
  const auto integrators = selectedIntegrators(options);
  // Scanned sections leave out adaptive schemes: their dt is only a call interval.
  std::vector<std::string> scanned;
  for (const auto& name : integrators)
    if (!particles::requireIntegrator(name).usesTolerance) scanned.push_back(name);
  const bool q = options.quick;
  const FailureCriterion& criterion = options.criterion;
  std::cout << describe(criterion) << "\n";
  // Safe steps by scanning a 5% log grid (scan.h) over the lab's ensemble of
  // starts (the scene as built and starts perturbed by 1e-6 of its size), as
  // every safe boundary of the report is.
  const ScanSettings scan;
  const std::string starts = scenes::plural(scan.members, "start");
  Progress progress(options, "extremes", static_cast<long>(integrators.size()) * (q ? 8 : 20) + (q ? 30 : 170));

  // 1. Spring stiffness: the safe dt of the 8-way cloth against k_s, scanned
  //    over the window 0.3/√k_s … 10/√k_s (capped at 0.5) around the
  //    spring's time scale, continued a decade lower when its bottom fails.
  {
    const std::vector<double> stiffness = q ? std::vector<double>{1, 100} : logSpace(1, 1e5, 6);
    const double duration = q ? 1.0 : 5.0;
    Csv csv(options, "extremes_stiffness.csv",
            {"integrator", "stiffness", "safe_dt", "first_failure_dt", "first_failure", "grid_lo", "grid_hi"});
    std::vector<std::pair<std::string, double>> cells;
    for (const auto& name : scanned)
      for (double ks : stiffness) cells.push_back({name, ks});
    auto cloth = [q](double ks) {
      return buildLabScene("cloth", {{"width", q ? "4" : "10"}, {"height", q ? "4" : "10"},
                                     {"links", "8"}, {"stiffness", general(ks, 6)}});
    };
    auto bottom = [](double ks) { return 0.3 / std::sqrt(ks); };  // the window's smallest dt
    std::map<std::string, std::vector<std::string>> rows;
    sweep<Boundary>(
        options, cells.size(),
        [&](std::size_t k) {
          const auto& [name, ks] = cells[k];
          ScanSettings window = scan;
          window.grid = stepGrid(bottom(ks), std::min(0.5, 10.0 / std::sqrt(ks)));
          window.extendDecades = 1;
          auto build = [&, ks = ks] { return cloth(ks); };
          auto b = scanSafeStep(build, name, duration, window, criterion);
          progress.tick();
          return b;
        },
        [&](std::size_t k, Boundary& b) {
          const auto& [name, ks] = cells[k];
          csv << name << ks << b.safeDt << b.firstFailureDt << failureName(b.firstFailure) << b.lowest << b.highest;
          csv.endRow();
          rows[name].push_back(safeStepText(b));
        },
        [&](std::size_t k) {  // the scan's steps are dominated by its smallest dt
          const auto& [name, ks] = cells[k];
          return estimatedRunSeconds(cloth(ks), name, bottom(ks), duration);
        });
    if (interrupted()) return 130;
    const std::vector<std::vector<std::string>> table = integratorRows(scanned, rows);
    std::vector<std::string> header{"integrator"};
    for (double ks : stiffness) header.push_back("k_s " + general(ks));
    writeTable(options, "extremes_stiffness",
               "Safe dt of the " + std::string(q ? "4×4" : "10×10") + " 8-way cloth against spring stiffness, T = " +
                   general(duration) + " s, " + starts,
               header, table);
  }

  // 2. Mass ratio: a heavy tip on a light chain.
  {
    const std::vector<double> ratios = q ? std::vector<double>{1, 100} : logSpace(1, 1e4, 5);
    const double duration = q ? 1.0 : 10.0;
    const int length = q ? 6 : 24;
    ScanSettings window = scan;
    window.grid = stepGrid(q ? 0.0125 : 0.05 / 32, 0.5);
    Csv csv(options, "extremes_mass_ratio.csv",
            {"integrator", "mass_ratio", "safe_dt", "first_failure_dt", "first_failure", "cg_iterations_per_step"});
    std::vector<std::pair<std::string, double>> cells;
    for (const auto& name : scanned)
      for (double ratio : ratios) cells.push_back({name, ratio});
    std::map<std::string, std::vector<std::string>> rows;
    auto cellChain = [&](std::size_t k) {  // the chain of cell k, for its scan and its cost estimate
      ChainSpec spec{length};
      spec.extra["tip-mass-ratio"] = general(cells[k].second, 6);
      return spec;
    };
    using Result = std::pair<Boundary, double>;
    sweep<Result>(
        options, cells.size(),
        [&](std::size_t k) -> std::optional<Result> {
          const std::string& name = cells[k].first;
          const ChainSpec spec = cellChain(k);
          auto b = scanSafeStep([&] { return buildChain(spec); }, name, duration, window, criterion);
          progress.tick();
          if (!b) return std::nullopt;
          // Iterations of Jacobi CG show how the mass ratio conditions J W Jᵀ.
          scenes::Scene chain = buildChain(spec);
          chain.system->solver().settings.method = particles::SolveMethod::ConjugateGradient;
          const StepCost cost = measureStepCost(chain, name, chain.dt, {1, 5});
          return Result{*b, cost.cgIterations};
        },
        [&](std::size_t k, Result& r) {
          const auto& [name, ratio] = cells[k];
          const Boundary& b = r.first;
          csv << name << ratio << b.safeDt << b.firstFailureDt << failureName(b.firstFailure) << r.second;
          csv.endRow();
          rows[name].push_back(safeStepText(b) + " (" + general(r.second, 3) + " it)");
        },
        [&](std::size_t k) {
          return estimatedRunSeconds(buildChain(cellChain(k)), cells[k].first, window.grid.front(), duration);
        });
    if (interrupted()) return 130;
    const std::vector<std::vector<std::string>> table = integratorRows(scanned, rows);
    std::vector<std::string> header{"integrator"};
    for (double r : ratios) header.push_back("tip/link mass " + general(r));
    writeTable(options, "extremes_mass_ratio",
               "Safe dt of the " + std::to_string(length) + "-chain, T = " + general(duration) + " s, " + starts +
                   " (and Jacobi-CG iterations per step at the default dt) against tip mass ratio",
               header, table);
  }

  // 3. Constraint feedback gains k_s, k_d of the solver (RK4, test chain).
  {
    const std::vector<double> ks = q ? std::vector<double>{0, 60} : std::vector<double>{0, 1, 10, 60, 100, 1000, 10000};
    const std::vector<double> kd = q ? std::vector<double>{0, 10} : std::vector<double>{0, 1, 3, 10, 30, 100, 300};
    const double duration = q ? 1.0 : 20.0, dt = q ? 0.02 : 0.05;
    Csv csv(options, "extremes_feedback.csv",
            {"ks", "kd", "critical_kd", "survived", "failure", "max_relative_stretch", "final_relative_stretch"});
    for (double s : ks)
      for (double d : kd) {
        if (interrupted()) break;
        // The run and its final max |C|/r.
        const auto result = cell<std::pair<RunResult, double>>(options, [&]() -> std::optional<std::pair<RunResult, double>> {
          scenes::Scene chain = buildChain({q ? 6 : 24});
          chain.system->solver().settings.stiffness = s;
          chain.system->solver().settings.damping = d;
          auto stepper = particles::makeIntegrator("rk4");
          const RunResult r = simulate(chain, *stepper, dt, duration, criterion);
          progress.tick();
          if (r.cutShort) return std::nullopt;
          return std::pair{r, chain.system->maxRelativeConstraintError()};
        });
        if (!result) continue;  // another shard's cell, or cut short (the check above ends the loop)
        const RunResult& r = result->first;
        csv << s << d << 2.0 * std::sqrt(s) << (r.failed ? 0L : 1L) << failureName(r.failure) << r.maxRelativeStretch
            << result->second;
        csv.endRow();
      }
    if (interrupted()) return 130;
    recordValue(options, "extremes.feedback.dt", general(dt));
    recordValue(options, "extremes.feedback.duration", general(duration));
  }

  // 4. CG budget: tolerance × iteration cap (RK4, 80-particle chain), plain
  //    CG started cold (the cap really starves each solve) and warm.
  {
    const std::vector<double> tolerances = q ? std::vector<double>{1e-2, 1e-8} : logSpace(1e-10, 1e-2, 5);
    const std::vector<int> caps = q ? std::vector<int>{2, 0} : std::vector<int>{1, 2, 5, 10, 20, 50, 0};
    const double duration = q ? 1.0 : 20.0, dt = 0.01;
    Csv csv(options, "extremes_cg_budget.csv",
            {"warm_start", "tolerance", "max_iterations", "survived", "failure", "max_relative_stretch",
             "cg_iterations_per_step"});
    struct Budget {
      bool warm;
      double tolerance;
      int cap;
    };
    std::vector<Budget> cells;
    for (bool warm : {false, true})
      for (double tol : tolerances)
        for (int cap : caps) cells.push_back({warm, tol, cap});
    sweep<RunResult>(
        options, cells.size(),
        [&](std::size_t k) -> std::optional<RunResult> {
          const Budget& c = cells[k];
          scenes::Scene chain = buildChain({q ? 12 : 80});
          auto& settings = chain.system->solver().settings;
          settings.tolerance = c.tolerance;
          settings.method = particles::SolveMethod::ConjugateGradient;
          settings.maxIterations = c.cap;
          settings.warmStart = c.warm;
          settings.preconditioner = particles::Preconditioner::None;
          auto stepper = particles::makeIntegrator("rk4");
          RunResult r = simulate(chain, *stepper, dt, duration, criterion);
          progress.tick();
          if (r.cutShort) return std::nullopt;
          return r;
        },
        [&](std::size_t k, RunResult& r) {
          const Budget& c = cells[k];
          csv << static_cast<long>(c.warm) << c.tolerance << static_cast<long>(c.cap) << (r.failed ? 0L : 1L)
              << failureName(r.failure) << r.maxRelativeStretch
              << static_cast<double>(r.work.cgIterations) / std::max(1L, r.steps);
          csv.endRow();
        });
    if (interrupted()) return 130;
    recordValue(options, "extremes.cg_budget.duration", general(duration));
    recordValue(options, "extremes.cg_budget.length", std::to_string(q ? 12 : 80));
  }

  // 5. Squared against root rods: cost, stretch and safe step.
  {
    const double duration = q ? 1.0 : 20.0;
    ScanSettings window = scan;
    window.grid = stepGrid(q ? 0.0125 : 0.05 / 16, 0.5);
    Csv csv(options, "extremes_rod_form.csv",
            {"integrator", "rod", "safe_dt", "step_seconds", "cg_iterations_per_step", "max_relative_stretch"});
    std::vector<std::pair<std::string, std::string>> cells;
    for (const auto& name : scanned)
      for (const std::string form : {"squared", "root"}) cells.push_back({name, form});
    struct Result {
      Boundary boundary;
      StepCost cost;
      double stretch;
    };
    std::map<std::string, std::vector<std::string>> rows;
    // The step cost is timed on this thread after the scans, so the timings
    // never share the machine with another cell.
    std::vector<Boundary> boundaries(cells.size());
    auto cellChain = [&](std::size_t k) { return ChainSpec{q ? 6 : 24, cells[k].second}; };
    sweep<Boundary>(
        options, cells.size(),
        [&](std::size_t k) {
          const ChainSpec spec = cellChain(k);
          auto b = scanSafeStep([&] { return buildChain(spec); }, cells[k].first, duration, window, criterion);
          progress.tick();
          return b;
        },
        [&](std::size_t k, Boundary& b) { boundaries[k] = b; },
        [&](std::size_t k) {
          return estimatedRunSeconds(buildChain(cellChain(k)), cells[k].first, window.grid.front(), duration);
        });
    if (interrupted()) return 130;
    for (std::size_t k = 0; k < cells.size(); ++k) {
      const auto& [name, form] = cells[k];
      // The step cost and the max stretch of a run.
      const auto result = cell<std::pair<StepCost, double>>(options, [&, &name = name, &form = form]()
                                                                -> std::optional<std::pair<StepCost, double>> {
        ChainSpec big{q ? 12 : 80, form};
        scenes::Scene chain = buildChain(big);
        const StepCost cost = measureStepCost(chain, name, chain.dt, {q ? 1 : 5, q ? 5 : 20});
        scenes::Scene fresh = buildChain(big);
        auto stepper = particles::makeIntegrator(name);
        const RunResult r = simulate(fresh, *stepper, fresh.dt, duration, criterion);
        if (r.cutShort) return std::nullopt;
        return std::pair{cost, r.maxRelativeStretch};
      });
      if (interrupted()) return 130;
      if (!result) continue;  // another shard's cell
      const auto& [cost, stretch] = *result;
      csv << name << form << boundaries[k].safeDt << cost.seconds << cost.cgIterations << stretch;
      csv.endRow();
      rows[name].push_back(safeStepText(boundaries[k]));
      rows[name].push_back(general(cost.seconds * 1e6, 3));
      rows[name].push_back(general(stretch, 2));
    }
    const std::vector<std::vector<std::string>> table = integratorRows(scanned, rows);
    writeTable(options, "extremes_rod_form",
               "Squared against root rods: safe dt (" + std::to_string(q ? 6 : 24) + "-chain, T = " +
                   general(duration) + " s, " + starts + "), µs per step and max stretch at the scene's dt (" +
                   std::to_string(q ? 12 : 80) + "-chain)",
               {"integrator", "squared: safe dt", "squared: µs/step", "squared: max stretch", "root: safe dt",
                "root: µs/step", "root: max stretch"},
               table);
  }

  // 6. The taut chain (the seed report's explosion case) under each integrator
  //    and solver budget.
  {
    // CG with an iteration cap (0: uncapped), and −1 for the direct solve.
    const std::vector<int> caps = q ? std::vector<int>{0, -1} : std::vector<int>{5, 20, 0, -1};
    const double duration = q ? 1.0 : 20.0;
    Csv csv(options, "extremes_taut_chain.csv",
            {"integrator", "max_iterations", "survived", "reason", "time", "max_relative_stretch",
             "cg_iterations_per_step"});
    std::vector<std::vector<std::string>> table;
    for (const auto& name : integrators) {
      std::vector<std::string> row{name};
      for (int cap : caps) {
        if (interrupted()) break;
        const auto result = cell<RunResult>(options, [&]() -> std::optional<RunResult> {
          scenes::Scene taut = buildLabScene("taut-chain");
          auto& settings = taut.system->solver().settings;
          if (cap >= 0) {
            settings.method = particles::SolveMethod::ConjugateGradient;
            settings.maxIterations = cap;
          }
          auto stepper = particles::makeIntegrator(name);
          RunResult r = simulate(taut, *stepper, taut.dt, duration, criterion);
          progress.tick();
          if (r.cutShort) return std::nullopt;
          return r;
        });
        if (!result) continue;  // another shard's cell, or cut short (the check above ends the loop)
        const RunResult& r = *result;
        csv << name << static_cast<long>(cap) << (r.failed ? 0L : 1L) << failureName(r.failure) << r.time
            << r.maxRelativeStretch << static_cast<double>(r.work.cgIterations) / std::max(1L, r.steps);
        csv.endRow();
        row.push_back(r.failed ? r.reason + " at t = " + general(r.time, 3)
                                 : "held (stretch " + general(r.maxRelativeStretch, 2) + ")");
      }
      table.push_back(row);
    }
    if (interrupted()) return 130;
    std::vector<std::string> header{"integrator"};
    for (int cap : caps)
      header.push_back(cap > 0 ? "CG cap " + std::to_string(cap) : cap == 0 ? "CG uncapped" : "direct LDLT");
    writeTable(options, "extremes_taut_chain", "Taut chain between two wires, T = " + general(duration) + " s",
               header, table);
  }
  if (interrupted()) return 130;
  recordValue(options, "extremes.members", std::to_string(scan.members));
  return 0;
}

}  // namespace lab
