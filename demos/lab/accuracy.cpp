// `particle-lab accuracy`: work–precision. For each problem, integrator and
// step, the position error at time T against a reference solution, and the
// wall time per simulated second; the fitted slope of error against dt is the
// observed order.
#include <cmath>
#include <limits>

#include "lab/chain.h"
#include "lab/experiments.h"

namespace lab {

namespace {

struct Problem {
  std::string label;
  std::string scene;
  std::map<std::string, std::string> params;
  double duration;            // T
  std::vector<double> steps;  // dt values swept
};

// A run long enough to time, with no explosion test: the error says it all.
struct Sample {
  Eigen::VectorXd positions;
  double seconds = 0.0;
  double dt = 0.0;  // the step actually used: T divided into whole steps
};

// Runs a problem to T. For an adaptive integrator dt is only the interval it
// covers per call; its accuracy is set by `integratorTolerance`.
Sample runProblem(const Problem& p, const std::string& integrator, double dt, double solverTolerance,
                  double integratorTolerance = particles::IntegratorSettings{}.tolerance) {
  // Errors are compared at exactly T, so dt is adjusted to divide T.
  dt = p.duration / std::max(1.0, std::round(p.duration / dt));
  scenes::Scene scene = scenes::buildScene(p.scene, p.params, scenes::kSeedPreset);
  scene.system->solver().settings.tolerance = solverTolerance;
  particles::IntegratorSettings settings;
  settings.tolerance = integratorTolerance;
  auto stepper = particles::makeIntegrator(integrator, settings);
  Explosion none;
  none.maxRelativeStretch = std::numeric_limits<double>::infinity();
  none.energyGain = std::numeric_limits<double>::infinity();
  const RunResult r = simulate(scene, *stepper, dt, p.duration, none);
  return {scene.system->positions(), r.seconds, dt};
}

bool usesTolerance(const std::string& integrator) {
  for (const auto& info : particles::integratorTable())
    if (integrator == info.name) return info.usesTolerance;
  return false;
}

double maxError(const Eigen::VectorXd& x, const Eigen::VectorXd& reference) {
  double worst = 0.0;
  for (int i = 0; i < x.size() / 2; ++i) {
    const double e = (x.segment<2>(2 * i) - reference.segment<2>(2 * i)).norm();
    if (!std::isfinite(e)) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, e);
  }
  return worst;
}

}  // namespace

int runAccuracy(const LabOptions& options) {
  prepareOutput(options);
  const auto integrators = selectedIntegrators(options);
  const bool q = options.quick;
  // Tight solver tolerance, so the constraint solve does not floor the error of
  // the high-order schemes; the reference is RK4 at a tenth of the smallest dt.
  const double tolerance = 1e-12;
  const std::vector<Problem> problems = {
      {"oscillator", "oscillator", {}, q ? 2.0 : 5.0, q ? std::vector<double>{0.04, 0.02, 0.01, 0.005}
                                                        : logSpace(0.0025, 0.16, 7)},
      {"pendulum", "pendulum", {}, q ? 1.0 : 5.0, q ? std::vector<double>{0.04, 0.02, 0.01}
                                                     : logSpace(0.0025, 0.08, 6)},
      {"test-chain", "test-chain", {{"cl", q ? "4" : "10"}}, q ? 1.0 : 4.0,
       q ? std::vector<double>{0.02, 0.01} : logSpace(0.0025, 0.04, 5)},
      {"cloth", "cloth", {{"width", q ? "4" : "10"}, {"height", q ? "4" : "10"}},
       q ? 0.5 : 2.0, q ? std::vector<double>{0.02, 0.01} : logSpace(0.0025, 0.04, 5)},
  };
  // Adaptive schemes are swept over their tolerance instead of dt, covering the
  // largest dt per call; their "slope" is that of error against tolerance.
  const std::vector<double> tolerances = q ? std::vector<double>{1e-4, 1e-6, 1e-8} : logSpace(1e-10, 1e-3, 8);
  long total = 0;
  for (const auto& p : problems) total += 1 + static_cast<long>(std::max(p.steps.size(), tolerances.size()) * integrators.size());
  Progress progress("accuracy", total);

  Csv csv(options.outDir + "/accuracy.csv",
          {"problem", "integrator", "dt", "tolerance", "error", "seconds_per_simulated_second"});
  Csv slopes(options.outDir + "/accuracy_slopes.csv", {"problem", "integrator", "slope"});
  std::vector<std::vector<std::string>> table;
  for (const auto& p : problems) {
    if (interrupted()) break;
    const double referenceStep = p.steps.front() / 10.0;
    const Sample reference = runProblem(p, "rk4", referenceStep, tolerance);
    progress.tick();
    std::vector<std::string> row{p.label};
    for (const auto& name : integrators) {
      std::vector<double> dts, errors;
      const bool adaptive = usesTolerance(name);
      for (double knob : adaptive ? tolerances : p.steps) {
        if (interrupted()) break;
        const double dt = adaptive ? p.duration / 4.0 : knob;  // adaptive: the interval per call
        const Sample s = adaptive ? runProblem(p, name, dt, tolerance, knob) : runProblem(p, name, dt, tolerance);
        const double error = maxError(s.positions, reference.positions);
        csv << p.label << name << s.dt << (adaptive ? knob : 0.0) << error << s.seconds / p.duration;
        csv.endRow();
        // Errors of order one or more are outside the asymptotic range.
        if (std::isfinite(error) && error < 0.1) dts.push_back(adaptive ? knob : s.dt), errors.push_back(error);
        progress.tick();
      }
      const double slope = logLogSlope(dts, errors);
      slopes << p.label << name << slope;
      slopes.endRow();
      row.push_back(std::isfinite(slope) ? fixed(slope, 2) : "–");
      recordValue(options, "accuracy.slope." + p.label + "." + name, fixed(slope, 2));
    }
    table.push_back(row);
  }
  std::vector<std::string> header{"problem"};
  for (const auto& name : integrators) header.push_back(name);
  writeTable(options, "accuracy_slopes",
             "Observed order: slope of log error against log dt (adaptive schemes: against log tolerance)", header,
             table);
  return interrupted() ? 130 : 0;
}

}  // namespace lab
