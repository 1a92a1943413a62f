// `particle-lab extremes`: stability at the extremes — stiff springs, heavy
// tips on light chains, the constraint feedback gains, a starved CG, the two
// rod forms, and the taut chain between two wires.
#include <cmath>
#include <limits>

#include "lab/chain.h"
#include "lab/experiments.h"

namespace lab {

namespace {

std::string stepText(double dt, double lo, double hi) {
  return dt <= 0.0 ? "< " + general(lo) : dt >= hi ? "≥ " + general(hi) : general(dt, 2);
}

}  // namespace

int runExtremes(const LabOptions& options) {
  prepareOutput(options);
  const auto integrators = selectedIntegrators(options);
  const bool q = options.quick;
  const int rounds = q ? 3 : 7;
  const Explosion explosion;
  Progress progress("extremes", static_cast<long>(integrators.size()) * (q ? 40 : 200) + (q ? 30 : 150));

  // 1. Spring stiffness: the largest stable dt of the 8-way cloth against k_s.
  {
    const std::vector<double> stiffness = q ? std::vector<double>{1, 100} : logSpace(1, 1e5, 6);
    const double lo = 1e-5, hi = 0.5, duration = q ? 1.0 : 5.0;
    Csv csv(options.outDir + "/extremes_stiffness.csv", {"integrator", "stiffness", "max_dt"});
    std::vector<std::vector<std::string>> table;
    for (const auto& name : integrators) {
      std::vector<std::string> row{name};
      for (double ks : stiffness) {
        if (interrupted()) break;
        auto build = [&] {
          return scenes::buildScene("cloth", {{"width", q ? "4" : "10"}, {"height", q ? "4" : "10"},
                                              {"links", "8"}, {"stiffness", general(ks, 6)}},
                                    scenes::kSeedPreset);
        };
        const double dt = maxStableStep(build, name, duration, lo, hi, rounds, explosion, progress);
        if (interrupted()) break;  // a bisection cut short is not a measurement
        csv << name << ks << dt;
        csv.endRow();
        row.push_back(stepText(dt, lo, hi));
      }
      table.push_back(row);
    }
    std::vector<std::string> header{"integrator"};
    for (double ks : stiffness) header.push_back("k_s " + general(ks));
    writeTable(options, "extremes_stiffness", "Largest stable dt of the 8-way cloth against spring stiffness",
               header, table);
  }

  // 2. Mass ratio: a heavy tip on a light chain.
  {
    const std::vector<double> ratios = q ? std::vector<double>{1, 100} : logSpace(1, 1e4, 5);
    const double lo = 1e-4, hi = 0.5, duration = q ? 1.0 : 10.0;
    Csv csv(options.outDir + "/extremes_mass_ratio.csv",
            {"integrator", "mass_ratio", "max_dt", "cg_iterations_per_step"});
    std::vector<std::vector<std::string>> table;
    for (const auto& name : integrators) {
      std::vector<std::string> row{name};
      for (double ratio : ratios) {
        if (interrupted()) break;
        ChainSpec spec{q ? 6 : 24};
        spec.extra["tip-mass-ratio"] = general(ratio, 6);
        const double dt = maxStableStep([&] { return buildChain(spec); }, name, duration, lo, hi, rounds,
                                        explosion, progress);
        // Iterations of Jacobi CG show how the mass ratio conditions J W Jᵀ.
        scenes::Scene chain = buildChain(spec);
        chain.system->solver().settings.method = particles::SolveMethod::ConjugateGradient;
        const StepCost cost = measureStepCost(chain, name, chain.dt, {1, 5});
        csv << name << ratio << dt << cost.cgIterations;
        csv.endRow();
        row.push_back(stepText(dt, lo, hi) + " (" + general(cost.cgIterations, 3) + " it)");
      }
      table.push_back(row);
    }
    std::vector<std::string> header{"integrator"};
    for (double r : ratios) header.push_back("tip/link mass " + general(r));
    writeTable(options, "extremes_mass_ratio",
               "Largest stable dt (and Jacobi-CG iterations per step at the default dt) against tip mass ratio",
               header, table);
  }

  // 3. Constraint feedback gains k_s, k_d of the solver (RK4, test chain).
  {
    const std::vector<double> ks = q ? std::vector<double>{0, 60} : std::vector<double>{0, 1, 10, 60, 100, 1000, 10000};
    const std::vector<double> kd = q ? std::vector<double>{0, 10} : std::vector<double>{0, 1, 3, 10, 30, 100, 300};
    const double duration = q ? 1.0 : 20.0, dt = q ? 0.02 : 0.05;
    Csv csv(options.outDir + "/extremes_feedback.csv",
            {"ks", "kd", "critical_kd", "survived", "max_relative_stretch", "final_relative_stretch"});
    for (double s : ks)
      for (double d : kd) {
        if (interrupted()) break;
        scenes::Scene chain = buildChain({q ? 6 : 24});
        chain.system->solver().settings.stiffness = s;
        chain.system->solver().settings.damping = d;
        auto stepper = particles::makeIntegrator("rk4");
        const RunResult r = simulate(chain, *stepper, dt, duration, explosion);
        csv << s << d << 2.0 * std::sqrt(s) << (r.exploded ? 0L : 1L) << r.maxRelativeStretch
            << chain.system->maxRelativeConstraintError();
        csv.endRow();
        progress.tick();
      }
    recordValue(options, "extremes.feedback.dt", general(dt));
    recordValue(options, "extremes.feedback.duration", general(duration));
  }

  // 4. CG budget: tolerance × iteration cap (RK4, 80-particle chain), plain
  //    CG started cold (the cap really starves each solve) and warm.
  {
    const std::vector<double> tolerances = q ? std::vector<double>{1e-2, 1e-8} : logSpace(1e-10, 1e-2, 5);
    const std::vector<int> caps = q ? std::vector<int>{2, 0} : std::vector<int>{1, 2, 5, 10, 20, 50, 0};
    const double duration = q ? 1.0 : 20.0, dt = 0.01;
    Csv csv(options.outDir + "/extremes_cg_budget.csv",
            {"warm_start", "tolerance", "max_iterations", "survived", "max_relative_stretch", "cg_iterations_per_step"});
    for (bool warm : {false, true})
    for (double tol : tolerances)
      for (int cap : caps) {
        if (interrupted()) break;
        scenes::Scene chain = buildChain({q ? 12 : 80});
        auto& settings = chain.system->solver().settings;
        settings.tolerance = tol;
        settings.method = particles::SolveMethod::ConjugateGradient;
        settings.maxIterations = cap;
        settings.warmStart = warm;
        settings.preconditioner = particles::Preconditioner::None;
        auto stepper = particles::makeIntegrator("rk4");
        const RunResult r = simulate(chain, *stepper, dt, duration, explosion);
        csv << static_cast<long>(warm) << tol << static_cast<long>(cap) << (r.exploded ? 0L : 1L) << r.maxRelativeStretch
            << static_cast<double>(r.work.cgIterations) / std::max(1L, r.steps);
        csv.endRow();
        progress.tick();
      }
  }

  // 5. Squared against root rods: cost, stretch and largest stable step.
  {
    const double lo = 1e-3, hi = 0.5, duration = q ? 1.0 : 20.0;
    Csv csv(options.outDir + "/extremes_rod_form.csv",
            {"integrator", "rod", "max_dt", "step_seconds", "cg_iterations_per_step", "max_relative_stretch"});
    std::vector<std::vector<std::string>> table;
    for (const auto& name : integrators) {
      std::vector<std::string> row{name};
      for (const std::string form : {"squared", "root"}) {
        if (interrupted()) break;
        ChainSpec spec{q ? 6 : 24, form};
        const double dt = maxStableStep([&] { return buildChain(spec); }, name, duration, lo, hi, rounds,
                                        explosion, progress);
        if (interrupted()) break;
        ChainSpec big{q ? 12 : 80, form};
        scenes::Scene chain = buildChain(big);
        const StepCost cost = measureStepCost(chain, name, chain.dt, {q ? 1 : 5, q ? 5 : 20});
        scenes::Scene fresh = buildChain(big);
        auto stepper = particles::makeIntegrator(name);
        const RunResult r = simulate(fresh, *stepper, fresh.dt, duration, explosion);
        csv << name << form << dt << cost.seconds << cost.cgIterations << r.maxRelativeStretch;
        csv.endRow();
        row.push_back(stepText(dt, lo, hi));
        row.push_back(general(cost.seconds * 1e6, 3));
        row.push_back(general(r.maxRelativeStretch, 2));
      }
      table.push_back(row);
    }
    writeTable(options, "extremes_rod_form", "Squared against root rods",
               {"integrator", "squared: max dt", "squared: µs/step", "squared: max stretch", "root: max dt",
                "root: µs/step", "root: max stretch"},
               table);
  }

  // 6. The taut chain (the seed report's explosion case) under each integrator
  //    and solver budget.
  {
    // CG with an iteration cap (0: uncapped), and −1 for the direct solve.
    const std::vector<int> caps = q ? std::vector<int>{0, -1} : std::vector<int>{5, 20, 0, -1};
    const double duration = q ? 1.0 : 20.0;
    Csv csv(options.outDir + "/extremes_taut_chain.csv",
            {"integrator", "max_iterations", "survived", "reason", "time", "max_relative_stretch",
             "cg_iterations_per_step"});
    std::vector<std::vector<std::string>> table;
    for (const auto& name : integrators) {
      std::vector<std::string> row{name};
      for (int cap : caps) {
        if (interrupted()) break;
        scenes::Scene taut = scenes::buildScene("taut-chain", {}, scenes::kSeedPreset);
        auto& settings = taut.system->solver().settings;
        if (cap >= 0) {
          settings.method = particles::SolveMethod::ConjugateGradient;
          settings.maxIterations = cap;
        }
        auto stepper = particles::makeIntegrator(name);
        const RunResult r = simulate(taut, *stepper, taut.dt, duration, explosion);
        csv << name << static_cast<long>(cap) << (r.exploded ? 0L : 1L) << r.reason << r.time
            << r.maxRelativeStretch << static_cast<double>(r.work.cgIterations) / std::max(1L, r.steps);
        csv.endRow();
        row.push_back(r.exploded ? r.reason + " at t = " + general(r.time, 3)
                                 : "held (stretch " + general(r.maxRelativeStretch, 2) + ")");
        progress.tick();
      }
      table.push_back(row);
    }
    std::vector<std::string> header{"integrator"};
    for (int cap : caps)
      header.push_back(cap > 0 ? "CG cap " + std::to_string(cap) : cap == 0 ? "CG uncapped" : "direct LDLT");
    writeTable(options, "extremes_taut_chain", "Taut chain between two wires, T = " + general(duration) + " s",
               header, table);
  }
  return interrupted() ? 130 : 0;
}

}  // namespace lab
