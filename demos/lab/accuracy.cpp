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
#include "lab/results.h"
#include "output/format_number.h"

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

// What the experiment measures.
struct AccuracyPlan {
  int repeats = 0;                 // timed repeats per point; the median is reported
  std::vector<Problem> problems;
  // Adaptive schemes: swept over their tolerance, called every output
  // interval, long enough (2 Hz output) that the tolerance limits the internal
  // step over most of the sweep rather than the call.
  double outputInterval = 0.5;
  std::vector<double> tolerances;
};

// Periods: oscillator 2π (ω = 1); pendulum ≈ 20 s (scenes::pendulumPeriod);
// the chain's swing ≈ 12 s. The chain is chaotic: past about 20 s two
// references at nearby tolerances part, so its reference is held tighter.
AccuracyPlan fullPlan() {
  AccuracyPlan plan;
  plan.repeats = 5;
  plan.problems = {
      {"oscillator", "oscillator", {}, 32.0, logSpace(0.005, 0.5, 9), true},
      {"pendulum", "pendulum", {}, 100.0, logSpace(0.005, 0.3, 8)},
      {"6-chain", "test-chain", {{"cl", "6"}}, 60.0, logSpace(0.0025, 0.08, 7), false, 1e-13},
      {"cloth-10x10", "cloth", {{"width", "10"}, {"height", "10"}}, 10.0, logSpace(0.0025, 0.16, 7)},
  };
  plan.tolerances = logSpace(1e-12, 1e-3, 10);
  return plan;
}

// Short horizons and three steps at most: proves the code runs.
AccuracyPlan quickPlan() {
  AccuracyPlan plan;
  plan.repeats = 2;
  plan.problems = {
      {"oscillator", "oscillator", {}, 10.0, {0.1, 0.05, 0.025}, true},
      {"pendulum", "pendulum", {}, 20.0, {0.1, 0.05, 0.025}},
      {"6-chain", "test-chain", {{"cl", "6"}}, 4.0, {0.04, 0.02}, false, 1e-11},
      {"cloth-10x10", "cloth", {{"width", "10"}, {"height", "10"}}, 1.0, {0.04, 0.02}},
  };
  plan.tolerances = {1e-5, 1e-9};
  return plan;
}

bool adaptive(const std::string& integrator) { return particles::requireIntegrator(integrator).usesTolerance; }

// The knobs an integrator is swept over on a problem: its tolerances, or the problem's steps.
const std::vector<double>& knobsOf(const AccuracyPlan& plan, const Problem& problem, const std::string& integrator) {
  return adaptive(integrator) ? plan.tolerances : problem.steps;
}

// One point: an integrator at one knob; dt divides T, so the error at T is taken at T.
struct PointCell {
  std::string integrator;
  double knob;       // dt, or the tolerance of an adaptive scheme
  double dt;
  double tolerance;  // 0 for fixed-step schemes
};

PointCell pointCell(const AccuracyPlan& plan, const Problem& problem, const std::string& integrator, double knob) {
  const bool isAdaptive = adaptive(integrator);
  const double wanted = isAdaptive ? plan.outputInterval : knob;
  const double dt = problem.horizon / std::max(1.0, std::round(problem.horizon / wanted));
  return {integrator, knob, dt, isAdaptive ? knob : 0.0};
}

// A problem's scene and its reference, computed at most once, by whichever
// of the problem's cells needs it first.
class ProblemScene {
 public:
  explicit ProblemScene(const Problem& problem) : problem_(problem) {
    if (problem.closedForm)
      closedForm_ = [&p = problem_](double T, double h) {
        return oscillatorReference(p.params, T, h, scenes::kSeedPreset);
      };
    scenes::Scene first = build();
    particles = first.system->size();
    scale = releasableEnergy(*first.system);
    firstDt_ = first.dt;
  }
  scenes::Scene build() const { return buildLabScene(problem_.scene, problem_.params); }
  std::function<scenes::Scene()> builder() const { return [this] { return build(); }; }
  const Reference& reference() {
    if (!computed_)
      computed_ = makeReference(builder(), problem_.horizon, firstDt_, problem_.referenceTolerance, closedForm_);
    return *computed_;
  }
  int particles = 0;
  double scale = 0.0;  // E_s of the start

 private:
  const Problem& problem_;
  ClosedForm closedForm_;
  double firstDt_ = 0.0;
  std::optional<Reference> computed_;
};

// The run against the reference, then the timed repeats.
std::optional<Point> measurePoint(const AccuracyPlan& plan, const Problem& problem, ProblemScene& scene,
                                  const PointCell& cell, const FailureCriterion& failure) {
  Point point;
  point.candidate = measureRun(scene.builder(), scene.reference().trajectory, cell.integrator, cell.dt, cell.tolerance,
                             problem.horizon, failure, scene.scale);
  for (int repeat = 0; repeat < plan.repeats && point.candidate.survived && !interrupted(); ++repeat) {
    scenes::Scene run = scene.build();
    particles::IntegratorSettings settings;
    if (cell.tolerance > 0.0) settings.dopri5.tolerance = cell.tolerance;
    auto stepper = particles::makeIntegrator(cell.integrator, settings);
    point.perSecond.push_back(simulate(run, *stepper, cell.dt, problem.horizon, failure).seconds / problem.horizon);
  }
  if (interrupted()) return std::nullopt;
  if (point.perSecond.empty()) point.perSecond.push_back(point.candidate.seconds / problem.horizon);
  return point;
}

// One integrator's sweep on a problem: its points measured here, and whether the sweep ran to its end.
struct Sweep {
  std::string integrator;
  std::vector<std::pair<PointCell, Point>> points;
  bool complete = false;
};

// Everything measured on one problem.
struct ProblemRun {
  int particles = 0;
  ReferenceSummary summary;
  std::vector<Sweep> sweeps;
};

Sweep sweepIntegrator(const LabOptions& options, const AccuracyPlan& plan, const Problem& problem,
                      ProblemScene& scene, const std::string& integrator, Progress& progress) {
  Sweep sweep{integrator, {}, false};
  for (double knob : knobsOf(plan, problem, integrator)) {
    if (interrupted()) return sweep;
    const PointCell c = pointCell(plan, problem, integrator, knob);
    const auto point = cell<Point>(options, [&] { return measurePoint(plan, problem, scene, c, options.criterion); });
    if (interrupted()) return sweep;
    progress.tick();
    if (point) sweep.points.push_back({c, *point});  // else another shard's cell
  }
  sweep.complete = true;
  return sweep;
}

ProblemRun measureProblem(const LabOptions& options, const AccuracyPlan& plan, const Problem& problem,
                          const std::vector<std::string>& integrators, Progress& progress) {
  ProblemScene scene(problem);
  ProblemRun run;
  run.particles = scene.particles;
  run.summary = cell<ReferenceSummary>(options, [&]() -> std::optional<ReferenceSummary> {
                  const Reference& r = scene.reference();
                  if (interrupted()) return std::nullopt;
                  return ReferenceSummary{r.agreement, static_cast<double>(r.trajectory.size()), r.description};
                }).value_or(ReferenceSummary{});
  for (const auto& name : integrators) {
    run.sweeps.push_back(sweepIntegrator(options, plan, problem, scene, name, progress));
    if (!run.sweeps.back().complete) break;
  }
  return run;
}

// The order is read where the error is asymptotic (below a tenth of the
// scene) and above the reference's uncertainty, bounded by its distance from
// the check run at 100× its tolerance.
double observedOrder(const Problem& problem, const ProblemRun& run, const Sweep& sweep) {
  std::vector<double> knobs, errors;
  const double floor = problem.closedForm ? 1e-13 : run.summary.agreement;
  for (const auto& [cell, point] : sweep.points) {
    const Candidate& candidate = point.candidate;
    if (candidate.survived && candidate.maxError < 0.1 * run.summary.size && candidate.maxError > floor)
      knobs.push_back(cell.tolerance > 0.0 ? cell.knob : cell.dt), errors.push_back(candidate.maxError);
  }
  return logLogSlope(knobs, errors);
}

void writePointRows(Csv& csv, const Problem& problem, const Sweep& sweep) {
  for (const auto& [cell, point] : sweep.points) {
    const Candidate& candidate = point.candidate;
    const std::vector<double>& perSecond = point.perSecond;
    csv << problem.label << cell.integrator << cell.dt << cell.tolerance << candidate.maxError << median(perSecond)
        << candidate.errorAtT << candidate.energyError << candidate.constraintDrift
        << *std::min_element(perSecond.begin(), perSecond.end())
        << *std::max_element(perSecond.begin(), perSecond.end()) << (candidate.survived ? 1L : 0L)
        << (candidate.failure.empty() ? std::string("-") : candidate.failure);
    csv.endRow();
  }
}

using Rows = std::vector<std::vector<std::string>>;

// accuracy.csv and accuracy_slopes.csv; the slope table's rows and the
// references' (an interrupted sweep is missing points: no slope is derived from it).
void writeRuns(const LabOptions& options, const AccuracyPlan& plan, const std::vector<ProblemRun>& runs,
               Rows& table, Rows& references) {
  Csv csv(options, "accuracy.csv",
          {"problem", "integrator", "dt", "tolerance", "error", "seconds_per_simulated_second", "error_at_T",
           "energy_error", "constraint_drift", "cpu_min", "cpu_max", "survived", "failure"});
  Csv slopes(options, "accuracy_slopes.csv", {"problem", "integrator", "slope"});
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const Problem& problem = plan.problems[k];
    const ProblemRun& run = runs[k];
    references.push_back({problem.label, std::to_string(run.particles), general(problem.horizon),
                          general(run.summary.size), run.summary.description});
    recordValue(options, "accuracy.reference_agreement." + problem.label, general(run.summary.agreement, 2));
    recordValue(options, "accuracy.horizon." + problem.label, general(problem.horizon));
    std::vector<std::string> row{problem.label + " (" + output::plural(run.particles, "particle") +
                                 ", T = " + general(problem.horizon) + " s)"};
    for (const Sweep& sweep : run.sweeps) {
      writePointRows(csv, problem, sweep);
      if (!sweep.complete) break;
      const double slope = observedOrder(problem, run, sweep);
      slopes << problem.label << sweep.integrator << slope;
      slopes.endRow();
      row.push_back(std::isfinite(slope) ? fixed(slope, 2) : "–");
      recordValue(options, "accuracy.slope." + problem.label + "." + sweep.integrator, row.back());
    }
    table.push_back(row);
  }
}

void writeTables(const LabOptions& options, const AccuracyPlan& plan, const std::vector<std::string>& integrators,
                 const Rows& table, const Rows& references) {
  writeTable(options, "accuracy_references",
             "Work–precision problems and their references (agreement: largest particle distance from odeint "
             "at 100x the tolerance, at samples about 1 s apart)",
             {"problem", "particles", "T (s)", "size", "reference"}, references);
  std::vector<std::string> header{"problem"};
  for (const auto& name : integrators) header.push_back(name);
  writeTable(options, "accuracy_slopes",
             "Observed order: slope of log max position error over [0, T] against log dt (adaptive schemes: "
             "against log tolerance, called every " + general(plan.outputInterval) + " s)",
             header, table);
}

}  // namespace

int runAccuracy(const LabOptions& options) {
  prepareOutput(options, "accuracy.");
  const auto integrators = selectedIntegrators(options, true);
  const AccuracyPlan plan = options.quick ? quickPlan() : fullPlan();
  long total = 0;
  for (const auto& problem : plan.problems)
    for (const auto& name : integrators) total += static_cast<long>(knobsOf(plan, problem, name).size());
  Progress progress(options, "accuracy", total);
  recordValue(options, "accuracy.repeats", std::to_string(plan.repeats));
  recordValue(options, "accuracy.output_interval", general(plan.outputInterval));

  std::vector<ProblemRun> runs;
  for (const auto& problem : plan.problems) {
    if (interrupted()) break;
    runs.push_back(measureProblem(options, plan, problem, integrators, progress));
  }
  Rows table, references;
  writeRuns(options, plan, runs, table, references);
  if (interrupted()) return 130;  // rows already written stay; no table from missing data
  writeTables(options, plan, integrators, table, references);
  return 0;
}

}  // namespace lab
