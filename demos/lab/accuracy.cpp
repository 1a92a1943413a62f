// `particle-lab accuracy`: work–precision over horizons of at least five
// periods. For each problem, integrator and step (adaptive schemes: tolerance,
// at a fixed output interval), against a reference independent of every
// integrator under test (lab/reference.h): the maximum over the trajectory of
// the largest particle position error, the error at T, the energy error and
// the constraint drift; and the CPU time per simulated second as the median of
// repeats with its spread. The slope of log max error against log dt is the
// observed order.
#include <algorithm>
#include <cmath>

#include "lab/advise.h"
#include "lab/cells.h"
#include "lab/experiments.h"
#include "lab/lab_scene.h"
#include "format_number.h"

namespace lab {

namespace {

struct Problem {
  std::string label;
  std::string scene;
  std::map<std::string, std::string> params;
  double horizon;             // T, at least five periods of the slowest motion
  std::vector<double> steps;  // dt values swept
  bool closedForm = false;    // the oscillator: the closed form is the reference
  double referenceTolerance = 1e-11;
};

// What the tables need of a problem's reference (its trajectory stays in the
// processes that measure against it).
struct ReferenceSummary {
  double agreement = 0.0;
  double size = 0.0;
  std::string description;
};
template <class Io>
void fields(Io& io, ReferenceSummary& r) {
  io("agreement", r.agreement), io("size", r.size), io("description", r.description);
}

// One point of the work–precision sweep: the run against the reference and
// the CPU time per simulated second of its timed repeats.
struct Point {
  Candidate candidate;
  std::vector<double> perSecond;
};
template <class Io>
void fields(Io& io, Point& p) {
  io("candidate", p.candidate), io("per_second", p.perSecond);
}

}  // namespace

int runAccuracy(const LabOptions& options) {
  prepareOutput(options);
  const auto integrators = selectedIntegrators(options, true);
  const bool q = options.quick;
  const int repeats = q ? 2 : 5;
  // Periods: oscillator 2π (ω = 1); pendulum ≈ 20 s (scenes::pendulumPeriod);
  // the chain's swing ≈ 12 s. The chain is chaotic: past about 20 s two
  // references at nearby tolerances part, so its reference is held tighter.
  const std::vector<Problem> problems = {
      {"oscillator", "oscillator", {}, q ? 10.0 : 32.0, q ? std::vector<double>{0.1, 0.05, 0.025} : logSpace(0.005, 0.5, 9),
       true},
      {"pendulum", "pendulum", {}, q ? 20.0 : 100.0, q ? std::vector<double>{0.1, 0.05, 0.025} : logSpace(0.005, 0.3, 8)},
      {"6-chain", "test-chain", {{"cl", "6"}}, q ? 4.0 : 60.0, q ? std::vector<double>{0.04, 0.02} : logSpace(0.0025, 0.08, 7),
       false, q ? 1e-11 : 1e-13},
      {"cloth-10x10", "cloth", {{"width", "10"}, {"height", "10"}}, q ? 1.0 : 10.0,
       q ? std::vector<double>{0.04, 0.02} : logSpace(0.0025, 0.16, 7)},
  };
  // Adaptive schemes: swept over their tolerance, called every output
  // interval, long enough (2 Hz output) that the tolerance limits the internal
  // step over most of the sweep rather than the call.
  const double outputInterval = 0.5;
  const std::vector<double> tolerances = q ? std::vector<double>{1e-5, 1e-9} : logSpace(1e-12, 1e-3, 10);
  long total = 0;
  for (const auto& p : problems)
    for (const auto& name : integrators) total += particles::requireIntegrator(name).usesTolerance ? tolerances.size() : p.steps.size();
  Progress progress(options, "accuracy", total);
  recordValue(options, "accuracy.repeats", std::to_string(repeats));
  recordValue(options, "accuracy.output_interval", general(outputInterval));

  Csv csv(options, "accuracy.csv",
          {"problem", "integrator", "dt", "tolerance", "error", "seconds_per_simulated_second", "error_at_T",
           "energy_error", "constraint_drift", "cpu_min", "cpu_max", "survived", "failure"});
  Csv slopes(options, "accuracy_slopes.csv", {"problem", "integrator", "slope"});
  std::vector<std::vector<std::string>> table, references;
  const FailureCriterion& failure = options.criterion;
  for (const auto& p : problems) {
    if (interrupted()) break;
    const auto build = [&] { return buildLabScene(p.scene, p.params); };
    ClosedForm closedForm;
    if (p.closedForm) closedForm = [&](double T, double h) { return oscillatorReference(p.params, T, h, scenes::kSeedPreset); };
    scenes::Scene first = build();
    const int particles = first.system->size();
    const double scale = releasableEnergy(*first.system);
    // Computed at most once here, by whichever of the problem's cells needs it first.
    std::optional<Reference> computed;
    const auto reference = [&]() -> const Reference& {
      if (!computed) computed = makeReference(build, p.horizon, first.dt, p.referenceTolerance, closedForm);
      return *computed;
    };
    const ReferenceSummary summary = cell<ReferenceSummary>(options, [&]() -> std::optional<ReferenceSummary> {
                                       const Reference& r = reference();
                                       if (interrupted()) return std::nullopt;
                                       return ReferenceSummary{r.agreement, r.trajectory.size(), r.description};
                                     }).value_or(ReferenceSummary{});
    const double size = summary.size;
    references.push_back({p.label, std::to_string(particles), general(p.horizon), general(size),
                          summary.description});
    recordValue(options, "accuracy.reference_agreement." + p.label, general(summary.agreement, 2));
    recordValue(options, "accuracy.horizon." + p.label, general(p.horizon));

    std::vector<std::string> row{p.label + " (" + scenes::plural(particles, "particle") + ", T = " + general(p.horizon) +
                                 " s)"};
    for (const auto& name : integrators) {
      std::vector<double> knobs, errors;
      const bool adaptive = particles::requireIntegrator(name).usesTolerance;
      for (double knob : adaptive ? tolerances : p.steps) {
        if (interrupted()) break;
        // dt divides T, so the error at T is taken at T.
        const double wanted = adaptive ? outputInterval : knob;
        const double dt = p.horizon / std::max(1.0, std::round(p.horizon / wanted));
        const double tolerance = adaptive ? knob : 0.0;
        const auto point = cell<Point>(options, [&]() -> std::optional<Point> {
          Point out;
          out.candidate = measureRun(build, reference().trajectory, name, dt, tolerance, p.horizon, failure, scale);
          for (int r = 0; r < repeats && out.candidate.survived && !interrupted(); ++r) {
            scenes::Scene scene = build();
            particles::IntegratorSettings settings;
            if (adaptive) settings.tolerance = tolerance;
            auto stepper = particles::makeIntegrator(name, settings);
            out.perSecond.push_back(simulate(scene, *stepper, dt, p.horizon, failure).seconds / p.horizon);
          }
          if (interrupted()) return std::nullopt;
          if (out.perSecond.empty()) out.perSecond.push_back(out.candidate.seconds / p.horizon);
          return out;
        });
        if (interrupted()) break;
        progress.tick();
        if (!point) continue;  // another shard's cell
        const Candidate& c = point->candidate;
        const std::vector<double>& perSecond = point->perSecond;
        csv << p.label << name << dt << tolerance << c.maxError << median(perSecond) << c.errorAtT << c.energyError
            << c.constraintDrift << *std::min_element(perSecond.begin(), perSecond.end())
            << *std::max_element(perSecond.begin(), perSecond.end()) << (c.survived ? 1L : 0L)
            << (c.failure.empty() ? std::string("-") : c.failure);
        csv.endRow();
        // The order is read where the error is asymptotic (below a tenth of the
        // scene) and above the reference's uncertainty, bounded by its
        // distance from the check run at 100× its tolerance.
        const double floor = p.closedForm ? 1e-13 : summary.agreement;
        if (c.survived && c.maxError < 0.1 * size && c.maxError > floor)
          knobs.push_back(adaptive ? knob : dt), errors.push_back(c.maxError);
      }
      // An interrupted sweep is missing points: no slope is derived from it.
      if (interrupted()) break;
      const double slope = logLogSlope(knobs, errors);
      slopes << p.label << name << slope;
      slopes.endRow();
      row.push_back(std::isfinite(slope) ? fixed(slope, 2) : "–");
      recordValue(options, "accuracy.slope." + p.label + "." + name, std::isfinite(slope) ? fixed(slope, 2) : "–");
    }
    if (interrupted()) break;
    table.push_back(row);
  }
  if (interrupted()) return 130;  // rows already written stay; no table from missing data
  writeTable(options, "accuracy_references",
             "Work–precision problems and their references (agreement: largest particle distance from odeint "
             "at 100x the tolerance, at samples about 1 s apart)",
             {"problem", "particles", "T (s)", "size", "reference"}, references);
  std::vector<std::string> header{"problem"};
  for (const auto& name : integrators) header.push_back(name);
  writeTable(options, "accuracy_slopes",
             "Observed order: slope of log max position error over [0, T] against log dt (adaptive schemes: "
             "against log tolerance, called every " + general(outputInterval) + " s)",
             header, table);
  return interrupted() ? 130 : 0;
}

}  // namespace lab
