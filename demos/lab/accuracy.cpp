// `particle-lab accuracy`: work–precision over horizons of at least five
// measured periods (a chaotic problem: its predictability). For each problem, integrator and step (adaptive schemes: tolerance,
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
  // A chaotic problem, whose horizon is its predictability and not five
  // periods: its references are also run over this longer horizon (0: none),
  // to measure the periods in it and when the two references part.
  double chaosProbe = 0.0;
};

// The partings of references more than this (m) leave no error to measure orders on.
constexpr double kPartingThreshold = 1e-4;

// What the tables need of a problem's reference (its trajectory stays in the
// processes that measure against it).
struct ReferenceSummary {
  double agreement = 0.0;
  double size = 0.0;
  double period = 0.0;  // Trajectory::slowestPeriod
  std::string description;
  // Over Problem::chaosProbe: the slowest period, the references' agreement,
  // and the time they first part by more than kPartingThreshold.
  double probePeriod = 0.0, probeAgreement = 0.0, probePredictable = 0.0;
};
template <class Io>
void fields(Io& io, ReferenceSummary& r) {
  io("agreement", r.agreement), io("size", r.size), io("period", r.period), io("description", r.description);
  io("probe_period", r.probePeriod), io("probe_agreement", r.probeAgreement);
  io("probe_predictable", r.probePredictable);
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

// Horizons of at least five periods of the slowest motion, as measured on
// the references (accuracy_references.md): oscillator 6.3 s, pendulum 21.3 s,
// cloth 18.2 s (its vertical bounce). The 6-chain (period 18.3 s) is chaotic:
// its references part by more than kPartingThreshold after about 66 s, so its
// horizon is 60 s, its reference held tighter, and the probe over 100 s says so.
AccuracyPlan fullPlan() {
  AccuracyPlan plan;
  plan.repeats = 5;
  plan.problems = {
      {"oscillator", "oscillator", {}, 32.0, logSpace(0.005, 0.5, 9), true},
      {"pendulum", "pendulum", {}, 110.0, logSpace(0.005, 0.3, 8)},
      {"6-chain", "test-chain", {{"cl", "6"}}, 60.0, logSpace(0.0025, 0.08, 7), false, 1e-13, 100.0},
      {"cloth-10x10", "cloth", {{"width", "10"}, {"height", "10"}}, 100.0, logSpace(0.0025, 0.16, 7)},
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
      {"6-chain", "test-chain", {{"cl", "6"}}, 4.0, {0.04, 0.02}, false, 1e-11, 8.0},
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
  // The reference over another horizon, computed afresh.
  Reference longerReference(double horizon) const {
    return makeReference(builder(), horizon, firstDt_, problem_.referenceTolerance, closedForm_);
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
                  ReferenceSummary summary{r.agreement, r.trajectory.size(), r.trajectory.slowestPeriod(),
                                           r.description};
                  if (problem.chaosProbe > 0.0) {
                    const Reference probe = scene.longerReference(problem.chaosProbe);
                    summary.probePeriod = probe.trajectory.slowestPeriod();
                    summary.probeAgreement = probe.agreement;
                    summary.probePredictable = predictableUntil(probe, kPartingThreshold, problem.chaosProbe);
                  }
                  return summary;
                }).value_or(ReferenceSummary{});
  for (const auto& name : integrators) {
    run.sweeps.push_back(sweepIntegrator(options, plan, problem, scene, name, progress));
    if (!run.sweeps.back().complete) break;
  }
  return run;
}

// The observed order on a sweep: local slopes between neighbouring points
// (finest first) and the least-squares slope over the asymptotic range, the
// finest points whose local slopes lie within kAsymptoticSpread of each other.
struct Order {
  double slope = std::nan("");  // over the asymptotic range; NaN with fewer than two points
  int points = 0;               // in the asymptotic range
  std::vector<double> local;    // finest pair first
};
constexpr double kAsymptoticSpread = 0.2;

// The points that count are where the error is below a tenth of the scene and
// above the reference's uncertainty (its distance from the check run at 100×
// its tolerance).
Order observedOrder(const Problem& problem, const ProblemRun& run, const Sweep& sweep) {
  std::vector<std::pair<double, double>> points;  // (knob, error)
  const double floor = problem.closedForm ? 1e-13 : run.summary.agreement;
  for (const auto& [cell, point] : sweep.points) {
    const Candidate& candidate = point.candidate;
    if (candidate.survived && candidate.maxError < 0.1 * run.summary.size && candidate.maxError > floor)
      points.emplace_back(cell.tolerance > 0.0 ? cell.knob : cell.dt, candidate.maxError);
  }
  std::sort(points.begin(), points.end());
  Order order;
  for (std::size_t k = 0; k + 1 < points.size(); ++k)
    order.local.push_back(std::log(points[k + 1].second / points[k].second) /
                          std::log(points[k + 1].first / points[k].first));
  if (order.local.empty()) return order;
  // The asymptotic range grows from the finest pair while the spread of its local slopes stays small.
  std::size_t slopes = 1;
  double lo = order.local[0], hi = order.local[0];
  while (slopes < order.local.size()) {
    const double next = order.local[slopes];
    if (std::max(hi, next) - std::min(lo, next) > kAsymptoticSpread) break;
    lo = std::min(lo, next), hi = std::max(hi, next), ++slopes;
  }
  std::vector<double> knobs, errors;
  for (std::size_t k = 0; k <= slopes; ++k) knobs.push_back(points[k].first), errors.push_back(points[k].second);
  order.slope = logLogSlope(knobs, errors);
  order.points = static_cast<int>(knobs.size());
  return order;
}

std::string localSlopesText(const Order& order) {
  std::string text;
  for (double s : order.local) text += (text.empty() ? "" : " ") + fixed(s, 2);
  return text.empty() ? "–" : text;
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

// The rows of the experiment's tables.
struct AccuracyTables {
  Rows slopes;      // per problem, the order of every integrator
  Rows local;       // per problem and integrator, the order with its range and local slopes
  Rows references;  // per problem, its reference and horizon
};

// A problem's reference row: its horizon against the slowest period measured on the reference.
void addReferenceRow(const LabOptions& options, const Problem& problem, const ProblemRun& run,
                     AccuracyTables& tables) {
  const double period = run.summary.period;
  const std::string periods = period > 0.0 ? fixed(problem.horizon / period, 1) : "< 2";
  tables.references.push_back({problem.label, std::to_string(run.particles), general(problem.horizon),
                               period > 0.0 ? general(period, 3) : "–", periods, general(run.summary.size),
                               run.summary.description});
  recordValue(options, "accuracy.reference_agreement." + problem.label, general(run.summary.agreement, 2));
  recordValue(options, "accuracy.horizon." + problem.label, general(problem.horizon));
  recordValue(options, "accuracy.period." + problem.label, period > 0.0 ? general(period, 3) : "–");
  recordValue(options, "accuracy.periods." + problem.label, periods);
  if (problem.chaosProbe > 0.0) {
    const std::string key = "accuracy.chaos." + problem.label;
    recordValue(options, key + ".probe", general(problem.chaosProbe));
    recordValue(options, key + ".probe_periods",
                run.summary.probePeriod > 0.0 ? fixed(problem.chaosProbe / run.summary.probePeriod, 1) : "< 2");
    recordValue(options, key + ".probe_agreement", general(run.summary.probeAgreement, 2));
    recordValue(options, key + ".predictable", general(run.summary.probePredictable, 3));
    recordValue(options, key + ".threshold", general(kPartingThreshold));
  }
}

// accuracy.csv and accuracy_slopes.csv, and the tables' rows (an interrupted
// sweep is missing points: no slope is derived from it).
AccuracyTables writeRuns(const LabOptions& options, const AccuracyPlan& plan, const std::vector<ProblemRun>& runs) {
  AccuracyTables tables;
  Csv csv(options, "accuracy.csv",
          {"problem", "integrator", "dt", "tolerance", "error", "seconds_per_simulated_second", "error_at_T",
           "energy_error", "constraint_drift", "cpu_min", "cpu_max", "survived", "failure"});
  Csv slopes(options, "accuracy_slopes.csv", {"problem", "integrator", "slope", "points", "local_slopes"});
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const Problem& problem = plan.problems[k];
    const ProblemRun& run = runs[k];
    addReferenceRow(options, problem, run, tables);
    std::vector<std::string> row{problem.label + " (" + output::plural(run.particles, "particle") +
                                 ", T = " + general(problem.horizon) + " s)"};
    for (const Sweep& sweep : run.sweeps) {
      writePointRows(csv, problem, sweep);
      if (!sweep.complete) break;
      const Order order = observedOrder(problem, run, sweep);
      slopes << problem.label << sweep.integrator << order.slope << static_cast<long>(order.points)
             << localSlopesText(order);
      slopes.endRow();
      row.push_back(std::isfinite(order.slope) ? fixed(order.slope, 2) : "–");
      tables.local.push_back(
          {problem.label, sweep.integrator, row.back(), std::to_string(order.points), localSlopesText(order)});
      recordValue(options, "accuracy.slope." + problem.label + "." + sweep.integrator, row.back());
      recordValue(options, "accuracy.local_slopes." + problem.label + "." + sweep.integrator,
                  localSlopesText(order));
    }
    tables.slopes.push_back(row);
  }
  return tables;
}

void writeTables(const LabOptions& options, const AccuracyPlan& plan, const std::vector<std::string>& integrators,
                 const AccuracyTables& tables) {
  writeTable(options, "accuracy_references",
             "Work–precision problems and their references (slowest period: measured on the reference, the mean "
             "spacing of its centre's crossings; agreement: largest particle distance from odeint at 100x the "
             "tolerance, at samples about 1 s apart)",
             {"problem", "particles", "T (s)", "slowest period (s)", "periods in T", "size", "reference"},
             tables.references);
  std::vector<std::string> header{"problem"};
  for (const auto& name : integrators) header.push_back(name);
  const std::string against =
      "against log dt (adaptive schemes: against log tolerance, called every " + general(plan.outputInterval) + " s)";
  writeTable(options, "accuracy_slopes",
             "Observed order: slope of log max position error over [0, T] " + against +
                 ", fitted over the asymptotic range (the finest points whose local slopes agree within " +
                 fixed(kAsymptoticSpread, 1) + ")",
             header, tables.slopes);
  writeTable(options, "accuracy_local_slopes",
             "Local slopes of log max position error " + against +
                 " between neighbouring points, finest first, and the points of the asymptotic range",
             {"problem", "integrator", "order", "points fitted", "local slopes (finest first)"}, tables.local);
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
  const AccuracyTables tables = writeRuns(options, plan, runs);
  if (interrupted()) return 130;  // rows already written stay; no table from missing data
  writeTables(options, plan, integrators, tables);
  return 0;
}

}  // namespace lab
