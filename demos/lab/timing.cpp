// `particle-lab timing`: cost per step against chain length and cloth size for
// each integrator, and the seed report's Table 3.
#include <chrono>
#include <cmath>
#include <iostream>

#include "lab/cells.h"
#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/lab_scene.h"

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
  Timed t;
  t.cost = measureStepCost(scene, integrator, scene.dt, timing);
  t.particles = scene.system->size();
  t.constraints = static_cast<long>(scene.system->constraints().size());
  t.forces = static_cast<long>(scene.system->forceObjects().size());
  t.dt = scene.dt;
  return t;
}

}  // namespace

int runTiming(const LabOptions& options, const TimingOptions& timing) {
  prepareOutput(options);
  const auto integrators = selectedIntegrators(options);
  const std::vector<int> chains = options.quick ? std::vector<int>{10, 20, 40}
                                                : std::vector<int>{10, 20, 40, 80, 160, 320, 640, 1000};
  const std::vector<int> cloths = options.quick ? std::vector<int>{4, 8}
                                                : std::vector<int>{8, 16, 32, 64, 128, 256};
  Progress progress(options, "timing", static_cast<long>(integrators.size() * (chains.size() + cloths.size() + 2)));
  recordValue(options, "timing.adaptive_tolerance", general(particles::IntegratorSettings{}.tolerance));

  Csv csv(options, "timing.csv",
          {"scene", "integrator", "particles", "constraints", "springs", "dt", "step_seconds", "cg_iterations_per_step"});
  std::map<std::string, std::vector<double>> chainN, chainT, clothN, clothT;
  for (const auto& name : integrators) {
    for (int cl : chains) {
      if (interrupted()) break;
      const auto timed = cell<Timed>(options, [&]() -> std::optional<Timed> {
        scenes::Scene chain = buildChain({cl});
        return timeScene(chain, name, timing);
      });
      progress.tick();
      if (!timed) continue;  // another shard's cell
      csv << "test-chain" << name << static_cast<long>(cl) << timed->constraints << timed->forces << timed->dt
          << timed->cost.seconds << timed->cost.cgIterations;
      csv.endRow();
      chainN[name].push_back(cl);
      chainT[name].push_back(timed->cost.seconds);
    }
    for (int side : cloths) {
      if (interrupted()) break;
      const auto timed = cell<Timed>(options, [&]() -> std::optional<Timed> {
        scenes::Scene cloth = buildLabScene(
            "cloth", {{"width", std::to_string(side)}, {"height", std::to_string(side)}, {"links", "8"}});
        TimingOptions small = timing;
        if (side >= 128) small.repeats = std::min(timing.repeats, 3), small.steps = std::min(timing.steps, 4);
        return timeScene(cloth, name, small);
      });
      progress.tick();
      if (!timed) continue;  // another shard's cell
      const StepCost& cost = timed->cost;
      recordValue(options, "timing.cloth" + std::to_string(side) + "." + name + "_ms", general(cost.seconds * 1e3, 3));
      csv << "cloth-8" << name << timed->particles << timed->constraints << timed->forces << timed->dt << cost.seconds
          << cost.cgIterations;
      csv.endRow();
      // The growth slope is fitted from 32×32 up, past the sizes where fixed
      // per-step overheads dominate.
      if (options.quick || side >= 32) {
        clothN[name].push_back(timed->particles);
        clothT[name].push_back(cost.seconds);
      }
    }
  }

  // Constraint solvers compared on the test chain under RK4: cost per step, CG
  // iterations, and the rod stretch they leave after a short run.
  {
    struct SolverVariant {
      const char* name;
      particles::SolveMethod method;
      particles::Preconditioner preconditioner;
      bool warmStart;
    };
    using particles::Preconditioner;
    using particles::SolveMethod;
    const SolverVariant variants[] = {
        {"plain CG, cold start", SolveMethod::ConjugateGradient, Preconditioner::None, false},
        {"Jacobi CG, warm start", SolveMethod::ConjugateGradient, Preconditioner::Jacobi, true},
        {"incomplete-Cholesky CG", SolveMethod::ConjugateGradient, Preconditioner::IncompleteCholesky, true},
        {"direct LDLT", SolveMethod::Direct, Preconditioner::None, false},
    };
    const std::vector<int> lengths = options.quick ? std::vector<int>{20} : std::vector<int>{80, 500};
    Csv solvers(options, "timing_solvers.csv",
                {"solver", "chain_length", "step_seconds", "cg_iterations_per_step", "max_relative_stretch"});
    std::vector<std::vector<std::string>> rows;
    std::map<std::string, std::map<int, double>> solverCost;
    for (const auto& variant : variants) {
      std::vector<std::string> row{variant.name};
      for (int cl : lengths) {
        if (interrupted()) break;
        auto configure = [&](scenes::Scene& scene) {
          auto& settings = scene.system->solver().settings;
          settings.method = variant.method;
          settings.preconditioner = variant.preconditioner;
          settings.warmStart = variant.warmStart;
        };
        // The step cost, and the max stretch of a short run.
        const auto measured = cell<std::pair<StepCost, double>>(options, [&]() -> std::optional<std::pair<StepCost, double>> {
          scenes::Scene timed = buildChain({cl});
          configure(timed);
          const StepCost cost = measureStepCost(timed, "rk4", timed.dt, timing);
          scenes::Scene run = buildChain({cl});
          configure(run);
          auto rk4 = particles::makeIntegrator("rk4");
          const RunResult r = simulate(run, *rk4, run.dt, options.quick ? 0.5 : 5.0);
          if (r.cutShort) return std::nullopt;
          return std::pair{cost, r.maxRelativeStretch};
        });
        if (!measured) continue;  // another shard's cell, or cut short (the check above ends the loop)
        const StepCost& cost = measured->first;
        const double stretch = measured->second;
        solvers << std::string(variant.name) << static_cast<long>(cl) << cost.seconds << cost.cgIterations << stretch;
        solvers.endRow();
        solverCost[variant.name][cl] = cost.seconds;
        row.push_back(general(cost.seconds * 1e6, 3) + " µs, " + general(cost.cgIterationsPerSolve(), 3) + " it, stretch " +
                      general(stretch, 2));
      }
      rows.push_back(row);
    }
    std::vector<std::string> header{"solver"};
    for (int cl : lengths) header.push_back("chain " + std::to_string(cl) + ": RK4 step, CG it/solve, max stretch");
    for (int cl : lengths) {
      const std::string key = "timing.solvers.chain" + std::to_string(cl);
      recordValue(options, key + ".direct_us", general(solverCost["direct LDLT"][cl] * 1e6, 3));
      recordValue(options, key + ".plain_cg_us", general(solverCost["plain CG, cold start"][cl] * 1e6, 3));
      recordValue(options, key + ".plain_cg_over_direct",
                  general(solverCost["plain CG, cold start"][cl] / solverCost["direct LDLT"][cl], 3));
    }
    writeTable(options, "timing_solvers", "Constraint solvers on the test chain (RK4, tolerance 1e-8)", header, rows);
  }

  // Growth: fitted log–log slope of cost against size.
  std::vector<std::vector<std::string>> growth;
  Csv slopes(options, "timing_slopes.csv", {"integrator", "chain_slope", "cloth_slope"});
  for (const auto& name : integrators) {
    const double chainSlope = logLogSlope(chainN[name], chainT[name]);
    const double clothSlope = logLogSlope(clothN[name], clothT[name]);
    slopes << name << chainSlope << clothSlope;
    slopes.endRow();
    growth.push_back({name, fixed(chainSlope, 2), fixed(clothSlope, 2)});
    recordValue(options, "timing.slope.cloth." + name, fixed(clothSlope, 2));
  }
  writeTable(options, "timing_growth", options.quick ? "Cost growth: fitted log-log slope of step time against size"
                                         : "Cost growth: fitted log-log slope of step time against size (chain 10-1000, cloth 32x32-256x256)",
             {"integrator", "chain (particles)", "8-way cloth (particles)"}, growth);

  // Table 3: ms per step of the 80-particle chain at dt 0.1 and 0.2.
  const std::map<std::string, std::vector<std::string>> seedTable3 = {
      {"symplectic-euler", {"2", "2"}}, {"midpoint", {"5", "5"}}, {"rk4", {"10", "9"}}};
  std::vector<std::vector<std::string>> table3;
  Csv table3Csv(options, "table3_step_cost.csv", {"integrator", "dt", "step_ms", "cg_iterations_per_step"});
  for (const auto& name : integrators) {
    std::vector<std::string> row{name};
    for (double dt : {0.1, 0.2}) {
      const auto measured = cell<StepCost>(options, [&]() -> std::optional<StepCost> {
        scenes::Scene chain = buildChain({80});
        return measureStepCost(chain, name, dt, timing);
      });
      if (!measured) continue;  // another shard's cell
      const StepCost& cost = *measured;
      table3Csv << name << dt << cost.seconds * 1e3 << cost.cgIterations;
      table3Csv.endRow();
      row.push_back(std::isfinite(cost.seconds) ? general(cost.seconds * 1e3, 3) : "diverges");
    }
    const auto seed = seedTable3.find(name);
    for (int k = 0; k < 2; ++k) row.push_back(seed != seedTable3.end() ? seed->second[k] : "–");
    table3.push_back(row);
    progress.tick(2);
  }
  writeTable(options, "table3", "Table 3: milliseconds per step, 80-particle chain",
             {"integrator", "dt 0.1", "dt 0.2", "seed dt 0.1", "seed dt 0.2"}, table3);
  return interrupted() ? 130 : 0;
}

}  // namespace lab
