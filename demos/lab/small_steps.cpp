// `particle-lab small-steps`: Macklin et al. 2019 ("Small Steps in Physics
// Simulation") on our scenes. XPBD at a fixed budget n = substeps × iterations
// split three ways (1×n, √n×√n, n×1), beside implicit Euler and RK4 over dt,
// on conservative versions of the 80-chain, the stiff cloth and the hair
// (every spring and angle damper k_d = 0), each against a converged reference
// (RK4 at a small dt). Per run: CPU time per simulated second, constraint
// error, numerical damping and position error at T; a run stops at its first
// failure by the lab's criterion (failure.h), which is printed and recorded. Then the stiff 128² cloth
// at 60 Hz: frame time against substeps beside one RK4 step, in the same run,
// and one frame's wall time on one thread against two.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <utility>

#include "lab/cells.h"
#include "lab/experiments.h"
#include "lab/failure.h"
#include "lab/lab_scene.h"
#include "lab/results.h"
#include "particles/forces/spring.h"
#include "particles/threads.h"
#include "scenes/cloth.h"

namespace lab {

namespace {

// CPU time of this thread, seconds: the machine is shared, so wall time
// would count the other processes' turns.
double cpuSeconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Largest relative violation: hard constraints max |C|/r and springs | |d|/r − 1 |.
double worstViolation(const particles::ParticleSystem& s) {
  double worst = s.maxRelativeConstraintError();
  for (const auto& force : s.forceObjects())
    if (const auto* spring = dynamic_cast<const particles::SpringForce*>(force.get())) {
      worst = std::max(worst, std::abs(spring->strain(s.positions())));
    }
  return worst;
}

struct Problem {
  std::string name;
  std::function<scenes::Scene()> build;
  double duration;     // T, simulated seconds
  double referenceDt;  // RK4's converged reference
  std::vector<double> rk4Steps, implicitSteps;
};

struct Outcome {
  Failure failure = Failure::None;  // the lab's criterion (failure.h), first step that meets it
  bool failed() const { return failure != Failure::None; }
  double cpuPerSecond = 0.0;     // CPU seconds per simulated second
  double constraintError = 0.0;  // worst relative violation over the run
  double energyLoss = 0.0;       // (E(0) − E(T)) / (T · E_s), per second (E_s: releasable energy)
  double positionError = 0.0;    // max_i |x_i(T) − x_ref,i(T)| / D
  Eigen::VectorXd x;
};
// The fields a cell's result keeps (lab/cell_json.h): x only feeds the runs
// measured against a reference, in the process that computed it.
template <class Io>
void fields(Io& io, Outcome& o) {
  io("failure", o.failure), io("cpu_per_second", o.cpuPerSecond), io("constraint_error", o.constraintError);
  io("energy_loss", o.energyLoss), io("position_error", o.positionError);
}

// Frame times (ms) of the stiff cloth and the worst strain over the run.
struct Frames {
  std::vector<double> ms;
  double worst = 0.0;
};
template <class Io>
void fields(Io& io, Frames& f) {
  io("ms", f.ms), io("worst", f.worst);
}

// Wall times (ms) of the same frames on one thread and on two, in turn.
struct ThreadedFrames {
  std::vector<double> oneMs, twoMs;
};
template <class Io>
void fields(Io& io, ThreadedFrames& f) {
  io("one_ms", f.oneMs), io("two_ms", f.twoMs);
}

// A run stops at its first failure by the lab's criterion; its damping and
// position error are then infinite.
Outcome runOne(const Problem& p, const std::string& integrator, const particles::IntegratorSettings& settings,
               double dt, const Eigen::VectorXd* reference, const FailureCriterion& criterion) {
  scenes::Scene scene = p.build();
  particles::ParticleSystem& s = *scene.system;
  auto stepper = particles::makeIntegrator(integrator, settings);
  const double scale = std::max(releasableEnergy(s), 1e-300), e0 = s.totalEnergy();
  const particles::DivergenceLimits limits = divergenceLimits(criterion, scale);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (int i = 0; i < s.size(); ++i) lo = lo.cwiseMin(s.position(i)), hi = hi.cwiseMax(s.position(i));
  const double diagonal = std::max((hi - lo).norm(), 1e-12);
  Outcome o;
  const long steps = std::lround(p.duration / dt);
  double cpu = 0.0;
  for (long k = 0; k < steps && !interrupted(); ++k) {
    const double start = cpuSeconds();
    const particles::StepStats stats = s.step(*stepper, dt);
    cpu += cpuSeconds() - start;
    const double violation = s.finite() ? worstViolation(s) : std::numeric_limits<double>::infinity();
    o.constraintError = std::max(o.constraintError, violation);
    o.failure = checkFailure(s, limits, e0, stats);
    if (o.failed()) break;
  }
  o.cpuPerSecond = cpu / p.duration;
  o.energyLoss = (e0 - s.totalEnergy()) / (p.duration * scale);
  o.x = s.positions();
  if (reference != nullptr) {
    for (int i = 0; i < s.size(); ++i)
      o.positionError = std::max(o.positionError, (o.x.segment<2>(2 * i) - reference->segment<2>(2 * i)).norm());
    o.positionError /= diagonal;
  }
  if (o.failed()) o.positionError = o.energyLoss = std::numeric_limits<double>::infinity();
  return o;
}

// The three splits of a budget n: (substeps, iterations).
std::vector<std::pair<std::string, std::pair<int, int>>> splits(int n) {
  int root = 1;
  while (root * root < n) ++root;
  while (n % root != 0) --root;  // the divisor nearest √n from below
  std::vector<std::pair<std::string, std::pair<int, int>>> out = {{"1xn", {1, n}}};
  if (root != 1 && root != n) out.push_back({"sqrt", {root, n / root}});
  if (n != 1) out.push_back({"nx1", {n, 1}});
  return out;
}

// The report quotes each family's row: small_steps.<scene>.<family>.<measure>.
void recordRow(const LabOptions& options, const std::string& scene, const std::string& family, const Outcome& o) {
  const std::string key = "small_steps." + scene + "." + family + ".";
  recordValue(options, key + "cpu", general(o.cpuPerSecond, 2));
  recordValue(options, key + "constraint_error", general(o.constraintError, 2));
  recordValue(options, key + "damping", general(o.energyLoss, 2));
  recordValue(options, key + "position_error", general(o.positionError, 2));
}

std::vector<std::string> row(const std::string& a, const std::string& b, const Outcome& o) {
  return {a, b, general(o.cpuPerSecond, 3), general(o.constraintError, 3), general(o.energyLoss, 3),
          general(o.positionError, 3)};
}

using Rows = std::vector<std::vector<std::string>>;

constexpr double kFrame = 1.0 / 60.0;  // s

// What the experiment runs.
struct SmallStepsPlan {
  std::vector<Problem> problems;
  std::vector<int> budgets;          // n = substeps × iterations; 20 is xpbd's default (20 × 1), the yardstick
  int clothSize = 0;                 // the 60 Hz stiff cloth: n × n particles
  int frameRepeats = 0;              // timed frames (RK4: twice as many steps)
  std::vector<int> clothSubsteps;    // xpbd's substeps per frame on it
  std::vector<int> lineSubsteps;     // the same with its hanging lines solved (XpbdSettings::lines)
  int threadedSubsteps = 0;          // the substeps timed on one thread against two
  int loadFrames = 0;                // frames run before timing: one simulated second, the cloth hangs loaded
};

std::function<scenes::Scene()> chain80() {
  return [] { return buildLabScene("test-chain", {{"cl", "80"}}); };
}

std::function<scenes::Scene()> undampedStiffCloth(int size) {
  return [size] {
    scenes::ClothParams p = scenes::stiffClothParams(size);
    p.damping = 0.0;
    return scenes::buildCloth(p);
  };
}

std::function<scenes::Scene()> undampedHair() {
  return [] { return buildLabScene("hair", {{"damping", "0"}, {"bend-damping", "0"}}); };
}

// Small scenes, short runs: proves the code runs.
SmallStepsPlan quickPlan() {
  const double f = kFrame;
  SmallStepsPlan plan;
  plan.problems = {{"chain80", chain80(), 1.0, 1e-3, {f, f / 8}, {f}},
                   {"stiff-cloth", undampedStiffCloth(8), 0.25, 1e-4, {f / 64}, {f}},
                   {"hair", undampedHair(), 1.0, 2e-4, {f / 8}, {f}}};
  plan.budgets = {1, 4, 20};
  plan.clothSize = 32;
  plan.frameRepeats = 3;
  plan.clothSubsteps = {10, 30};
  plan.lineSubsteps = {3};
  plan.threadedSubsteps = 30;
  plan.loadFrames = 10;
  return plan;
}

SmallStepsPlan fullPlan() {
  const double f = kFrame;
  SmallStepsPlan plan;
  plan.problems = {
      {"chain80", chain80(), 5.0, 1e-3, {f, f / 2, f / 4, f / 8, f / 16}, {f, f / 2, f / 4, f / 8}},
      {"stiff-cloth", undampedStiffCloth(24), 1.0, 1e-4, {f / 16, f / 32, f / 64, f / 128}, {f, f / 2, f / 4, f / 8}},
      {"hair", undampedHair(), 4.0, 2e-4, {f, f / 2, f / 4, f / 8, f / 16}, {f, f / 2, f / 4, f / 8}}};
  plan.budgets = {1, 2, 4, 8, 16, 20, 32, 64};
  plan.clothSize = 128;
  plan.frameRepeats = 5;
  plan.clothSubsteps = {10, 20, 30, 40, 60};
  plan.lineSubsteps = {2, 3, 4, 6};
  plan.threadedSubsteps = 30;
  plan.loadFrames = 60;
  return plan;
}

// One run on a problem: xpbd at one split of a budget, or a force-based scheme at one dt.
struct RunCell {
  std::string family;  // "xpbd", "implicit-euler", "rk4"
  std::string split;   // xpbd: "1xn", "sqrt", "nx1"; else "-"
  int budget = 0;      // xpbd: n; else 0
  particles::IntegratorSettings settings;
  double dt = 0.0;
  int substeps() const { return family == "xpbd" ? settings.xpbd.substeps : 1; }
  int iterations() const { return family == "xpbd" ? settings.xpbd.iterations : 1; }
};

// Every budget's splits at 1/60 s, then implicit Euler's steps, then RK4's.
std::vector<RunCell> runCells(const SmallStepsPlan& plan, const Problem& problem) {
  std::vector<RunCell> cells;
  for (int n : plan.budgets)
    for (const auto& [split, si] : splits(n)) {
      RunCell cell{"xpbd", split, n, {}, kFrame};
      cell.settings.xpbd.substeps = si.first;
      cell.settings.xpbd.iterations = si.second;
      cells.push_back(cell);
    }
  for (double dt : problem.implicitSteps) cells.push_back({"implicit-euler", "-", 0, {}, dt});
  for (double dt : problem.rk4Steps) cells.push_back({"rk4", "-", 0, {}, dt});
  return cells;
}

// The converged reference of a problem: its positions at T computed at most
// once, by the first of the problem's cells that needs them.
class ProblemReference {
 public:
  ProblemReference(const Problem& problem, const FailureCriterion& criterion)
      : problem_(problem), criterion_(criterion) {}
  const Outcome& outcome() {
    if (!computed_) computed_ = runOne(problem_, "rk4", {}, problem_.referenceDt, nullptr, criterion_);
    return *computed_;
  }
  const Eigen::VectorXd* positions() { return &outcome().x; }

 private:
  const Problem& problem_;
  const FailureCriterion& criterion_;
  std::optional<Outcome> computed_;
};

// Everything measured on one problem (in a shard: its own cells).
struct ProblemRun {
  std::optional<Outcome> reference;
  std::vector<RunCell> cells;
  Results<Outcome> runs;  // by index into cells
};

ProblemRun measureProblem(const LabOptions& options, const Problem& problem, const SmallStepsPlan& plan,
                          Progress& progress) {
  ProblemReference reference(problem, options.criterion);
  ProblemRun run;
  run.reference = cell<Outcome>(options, [&]() -> std::optional<Outcome> {
    const Outcome outcome = reference.outcome();
    progress.tick();
    if (interrupted()) return std::nullopt;
    return outcome;
  });
  if (interrupted()) return run;
  run.cells = runCells(plan, problem);
  run.runs = resultsInTurn<Outcome>(
      options, run.cells.size(),
      [&](std::size_t k) -> std::optional<Outcome> {
        const RunCell& cell = run.cells[k];
        const Outcome outcome =
            runOne(problem, cell.family, cell.settings, cell.dt, reference.positions(), options.criterion);
        progress.tick();
        if (interrupted()) return std::nullopt;
        return outcome;
      },
      true);
  return run;
}

void writeRunRows(Csv& csv, const Problem& problem, const ProblemRun& run) {
  auto write = [&](const std::string& family, const std::string& split, int budget, int substeps, int iterations,
                   double dt, const Outcome& outcome) {
    csv << problem.name << family << split << budget << substeps << iterations << dt << outcome.cpuPerSecond
        << outcome.constraintError << outcome.energyLoss << outcome.positionError
        << std::string(failureName(outcome.failure));
    csv.endRow();
  };
  if (run.reference) write("reference", "-", 0, 1, 1, problem.referenceDt, *run.reference);
  for (const auto& [k, outcome] : run.runs) {
    const RunCell& cell = run.cells[k];
    write(cell.family, cell.split, cell.budget, cell.substeps(), cell.iterations(), cell.dt, outcome);
  }
}

// xpbd's runs at the largest budget by split, and at its default settings (20 × 1).
struct XpbdRuns {
  std::map<std::string, Outcome> atLargest;
  Outcome atDefault;
};

XpbdRuns xpbdRuns(const SmallStepsPlan& plan, const ProblemRun& run) {
  const particles::IntegratorSettings defaults;
  XpbdRuns xpbd;
  for (const auto& [k, outcome] : run.runs) {
    const RunCell& cell = run.cells[k];
    if (cell.family != "xpbd") continue;
    if (cell.budget == plan.budgets.back()) xpbd.atLargest[cell.split] = outcome;
    if (cell.settings.xpbd.substeps == defaults.xpbd.substeps && cell.settings.xpbd.iterations == defaults.xpbd.iterations)
      xpbd.atDefault = outcome;
  }
  return xpbd;
}

// Fixed budget: do many substeps beat many iterations (constraint error and
// damping)? Damping compares |energy change|: an unconverged solve can also gain energy.
bool substepsWin(const Outcome& many, const Outcome& iterated) {
  return many.constraintError <= iterated.constraintError &&
         std::abs(many.energyLoss) <= std::abs(iterated.energyLoss) && many.positionError <= iterated.positionError;
}

std::vector<std::string> budgetRow(const SmallStepsPlan& plan, const Problem& problem, XpbdRuns& xpbd) {
  const Outcome& many = xpbd.atLargest["nx1"];
  const Outcome& iterated = xpbd.atLargest["1xn"];
  return {problem.name, std::to_string(plan.budgets.back()), general(many.constraintError),
          general(iterated.constraintError), general(many.energyLoss), general(iterated.energyLoss),
          general(many.positionError), general(iterated.positionError), substepsWin(many, iterated) ? "yes" : "no"};
}

// Equal CPU time per simulated second: the force-based run with the smallest
// dt whose cost is at most `budget` (xpbd's default), else the cheapest.
struct Chosen {
  Outcome outcome;
  double dt = 0.0;
};

Chosen chooseAtBudget(const ProblemRun& run, const std::string& family, double budget) {
  Chosen chosen;
  bool any = false;
  for (const auto& [k, outcome] : run.runs) {
    const RunCell& cell = run.cells[k];
    if (cell.family != family) continue;
    const bool affordable = outcome.cpuPerSecond <= budget;
    const bool chosenOver = chosen.outcome.cpuPerSecond > budget;
    if (!any || (affordable && (chosenOver || cell.dt < chosen.dt)) ||
        (!affordable && chosenOver && outcome.cpuPerSecond < chosen.outcome.cpuPerSecond)) {
      chosen = {outcome, cell.dt};
      any = true;
    }
  }
  return chosen;
}

std::string chosenText(const std::string& family, const Chosen& chosen) {
  const Outcome& outcome = chosen.outcome;
  return family + " at dt " + general(chosen.dt, 3) +
         (outcome.failed() ? std::string(" (failed: ") + failureName(outcome.failure) + ")" : "");
}

// The tables' rows, and whether each claim holds on every scene.
struct Tabulated {
  Rows claimRows, familyRows;
  bool substepsWinEverywhere = true, xpbdBeatsImplicitEverywhere = true;
};

void tabulateProblem(const LabOptions& options, const SmallStepsPlan& plan, const Problem& problem,
                     const ProblemRun& run, Tabulated& out) {
  XpbdRuns xpbd = xpbdRuns(plan, run);
  out.claimRows.push_back(budgetRow(plan, problem, xpbd));
  out.substepsWinEverywhere &= substepsWin(xpbd.atLargest["nx1"], xpbd.atLargest["1xn"]);
  recordValue(options, "small_steps." + problem.name + ".nx1_constraint_error",
              general(xpbd.atLargest["nx1"].constraintError));
  recordValue(options, "small_steps." + problem.name + ".1xn_constraint_error",
              general(xpbd.atLargest["1xn"].constraintError));
  const Outcome reference = run.reference.value_or(Outcome{});
  out.familyRows.push_back(row(problem.name, "reference: rk4 at dt " + general(problem.referenceDt, 2), reference));
  out.familyRows.push_back(row(problem.name, "xpbd 20x1 at 1/60", xpbd.atDefault));
  recordRow(options, problem.name, "xpbd", xpbd.atDefault);
  recordRow(options, problem.name, "reference", reference);
  const double budget = xpbd.atDefault.cpuPerSecond;
  for (const std::string family : {"implicit-euler", "rk4"}) {
    const Chosen chosen = chooseAtBudget(run, family, budget);
    out.familyRows.push_back(row(problem.name, chosenText(family, chosen), chosen.outcome));
    recordRow(options, problem.name, family, chosen.outcome);
    if (family == "implicit-euler")
      out.xpbdBeatsImplicitEverywhere &= xpbd.atDefault.constraintError <= chosen.outcome.constraintError &&
                                         std::abs(xpbd.atDefault.energyLoss) <= std::abs(chosen.outcome.energyLoss);
  }
  recordValue(options, "small_steps." + problem.name + ".xpbd_cpu_per_second", general(budget));
}

void writeFamilyTables(const LabOptions& options, const Tabulated& t) {
  writeTable(options, "small_steps_budget",
             "Fixed budget n = substeps × iterations at 1/60 s: n substeps of one pass (nx1) against one substep of n "
             "passes (1xn); constraint error = worst relative violation over the run, damping = energy lost per "
             "simulated second over the energy scale, position error at T over the scene's diagonal",
             {"scene", "n", "error nx1", "error 1xn", "damping nx1", "damping 1xn", "position nx1", "position 1xn",
              "nx1 wins all three"},
             t.claimRows);
  writeTable(options, "small_steps_families",
             "Equal CPU time per simulated second: xpbd 20 × 1 at 1/60 s against the force-based run with the "
             "smallest dt that costs no more (else the cheapest run); columns as above (negative damping: energy "
             "gained), CPU in s per simulated s; the reference's violation is the physical stretch of the springs",
             {"scene", "method", "CPU/s", "constraint error", "damping /s", "position error"}, t.familyRows);
  recordValue(options, "small_steps.claim_substeps",
              t.substepsWinEverywhere ? "holds on every scene" : "does not hold on every scene");
  recordValue(options, "small_steps.claim_implicit",
              t.xpbdBeatsImplicitEverywhere ? "holds on every scene" : "does not hold on every scene");
}

// --- the stiff cloth at 60 Hz ---------------------------------------------

double wallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::vector<double> frameTimes(scenes::Scene& scene, particles::Integrator& stepper, double dt, int frames) {
  std::vector<double> ms;
  for (int k = 0; k < frames; ++k) {
    const double start = cpuSeconds();
    scene.system->step(stepper, dt);
    ms.push_back(1e3 * (cpuSeconds() - start));
  }
  return ms;
}

// The cost of a step does not depend on its size; 5e-5 s is within RK4's
// stable step on this cloth (about 1e-4 s), so the state stays finite.
Frames timeRk4Step(const SmallStepsPlan& plan) {
  scenes::Scene scene = scenes::buildCloth(scenes::stiffClothParams(plan.clothSize));
  auto rk4 = particles::makeIntegrator("rk4");
  Frames out;
  out.ms = frameTimes(scene, *rk4, 5e-5, 2 * plan.frameRepeats);
  out.worst = worstViolation(*scene.system);
  return out;
}

std::optional<Frames> timeXpbdFrames(const SmallStepsPlan& plan, int substeps, bool lines) {
  scenes::Scene scene = scenes::buildCloth(scenes::stiffClothParams(plan.clothSize));
  particles::IntegratorSettings settings;
  settings.xpbd.substeps = substeps;
  settings.xpbd.lines = lines;
  auto xpbd = particles::makeIntegrator("xpbd", settings);
  Frames out;
  for (int k = 0; k < plan.loadFrames && !interrupted(); ++k) {
    scene.system->step(*xpbd, kFrame);
    out.worst = std::max(out.worst, worstViolation(*scene.system));
  }
  out.ms = frameTimes(scene, *xpbd, kFrame, plan.frameRepeats);
  out.worst = std::max(out.worst, worstViolation(*scene.system));
  if (interrupted()) return std::nullopt;
  return out;
}

// One thread against two on the loaded cloth: two copies stepped in turn,
// in blocks of frames on one count and then the other, so that both counts
// meet the same load of the machine. A block's first frame is not timed: it
// wakes the threads and brings its cloth back into the caches, as
// consecutive frames of one cloth find it. Wall time: two threads share a
// frame. The copies stay the same bits (the engine's threads never change a
// result), which the run checks.
std::optional<ThreadedFrames> timeThreadedXpbdFrames(const SmallStepsPlan& plan, int substeps) {
  scenes::Scene one = scenes::buildCloth(scenes::stiffClothParams(plan.clothSize));
  scenes::Scene two = scenes::buildCloth(scenes::stiffClothParams(plan.clothSize));
  // Two threads on every frame, not the engine's choice (src/thread_use.h):
  // this compares the counts themselves.
  two.system->threadUse().adaptive = false;
  particles::IntegratorSettings settings;
  settings.xpbd.substeps = substeps;
  auto xpbdOne = particles::makeIntegrator("xpbd", settings);
  auto xpbdTwo = particles::makeIntegrator("xpbd", settings);
  for (int k = 0; k < plan.loadFrames && !interrupted(); ++k) {
    one.system->step(*xpbdOne, kFrame);
    two.system->step(*xpbdTwo, kFrame);
  }
  ThreadedFrames out;
  const int previous = particles::threadCount();
  auto timed = [previous](scenes::Scene& scene, particles::Integrator& xpbd, int threads) {
    particles::setThreadCount(threads);
    const double start = wallSeconds();
    scene.system->step(xpbd, kFrame);
    const double ms = 1e3 * (wallSeconds() - start);
    particles::setThreadCount(previous);
    return ms;
  };
  constexpr int kTimedPerBlock = 2;
  for (int block = 0; block < plan.frameRepeats && !interrupted(); ++block) {
    timed(one, *xpbdOne, 1);
    for (int k = 0; k < kTimedPerBlock; ++k) out.oneMs.push_back(timed(one, *xpbdOne, 1));
    timed(two, *xpbdTwo, 2);
    for (int k = 0; k < kTimedPerBlock; ++k) out.twoMs.push_back(timed(two, *xpbdTwo, 2));
  }
  if (interrupted()) return std::nullopt;
  if (one.system->positions() != two.system->positions() || one.system->velocities() != two.system->velocities())
    throw std::runtime_error("small-steps: the stiff cloth on two threads left the one-thread trajectory");
  return out;
}

void writeFrames(Csv& csv, const std::string& method, int substeps, const Frames& frames) {
  const std::vector<double>& ms = frames.ms;
  csv << method << substeps << median(ms) << *std::min_element(ms.begin(), ms.end())
      << *std::max_element(ms.begin(), ms.end()) << frames.worst;
  csv.endRow();
}

// The target: a frame in at most 16 ms with every spring within 3 %, by the
// fewest substeps that keep the strain, and that frame in RK4 steps.
std::string targetText(const std::vector<int>& substeps, const Results<Frames>& xpbd, const std::string& how,
                       const std::optional<Frames>& rk4) {
  const double targetMs = 16.0, targetStrain = 0.03;
  for (const auto& [k, frames] : xpbd) {
    if (frames.worst > targetStrain) continue;
    const double ms = median(frames.ms);
    return (ms <= targetMs ? "is met by " : "is not met on this machine: the fewest substeps within 3 %, ") +
           std::to_string(substeps[k]) + " substeps of one pass" + how + ", take " + fixed(ms, 2) + " ms" +
           (rk4 ? " (" + fixed(ms / median(rk4->ms), 2) + " RK4 steps)" : std::string()) +
           " with the worst spring at " + fixed(100 * frames.worst, 2) + " %";
  }
  return "is not met: no substep count measured keeps every spring within 3 %";
}

// One series of xpbd frames: a CSV row and two values per substep count.
void writeSeries(const LabOptions& options, Csv& cloth, const std::string& method, const std::string& key,
                 const std::vector<int>& substeps, const Results<Frames>& frames) {
  for (const auto& [k, f] : frames) {
    const std::string name = "small_steps.cloth." + key + std::to_string(substeps[k]);
    writeFrames(cloth, method, substeps[k], f);
    recordValue(options, name + "_ms", fixed(median(f.ms), 2));
    recordValue(options, name + "_strain_percent", fixed(100 * f.worst, 2));
  }
}

// The frame at plan.threadedSubsteps on one thread and on two (a CSV row per
// count, wall time), when the process may use two CPUs. Nothing is written
// without the cell's result: another shard's cell, or an interrupt.
void writeThreadedFrames(const LabOptions& options, const SmallStepsPlan& plan) {
  const std::string key = "small_steps.cloth.threads";
  recordValue(options, "small_steps.cloth.cpus", std::to_string(particles::affinityCpuCount()));
  if (particles::affinityCpuCount() < 2) {
    recordValue(options, key + ".text", "were not compared: this process may use one CPU only");
    return;
  }
  const auto frames = cell<ThreadedFrames>(
      options, [&]() -> std::optional<ThreadedFrames> { return timeThreadedXpbdFrames(plan, plan.threadedSubsteps); });
  if (!frames) return;
  Csv csv(options, "small_steps_cloth_threads.csv",
          {"threads", "substeps", "frame_wall_ms_median", "frame_wall_ms_min", "frame_wall_ms_max"});
  for (const auto& [threads, ms] : {std::pair<int, const std::vector<double>&>{1, frames->oneMs}, {2, frames->twoMs}}) {
    csv << threads << plan.threadedSubsteps << median(ms) << *std::min_element(ms.begin(), ms.end())
        << *std::max_element(ms.begin(), ms.end());
    csv.endRow();
  }
  const double one = median(frames->oneMs), two = median(frames->twoMs);
  recordValue(options, key + ".substeps", std::to_string(plan.threadedSubsteps));
  recordValue(options, key + ".one_ms", fixed(one, 2));
  recordValue(options, key + ".two_ms", fixed(two, 2));
  recordValue(options, key + ".speedup", fixed(one / two, 2));
  recordValue(options, key + ".text",
              "take " + fixed(one, 2) + " ms on one thread and " + fixed(two, 2) + " ms on two (wall time, medians of " +
                  std::to_string(frames->oneMs.size()) + " frames, in blocks in turn): " + fixed(one / two, 2) + "×");
}

// Frame time against substeps beside one RK4 step, one at a time on this
// thread, Gauss–Seidel alone and with the hanging lines solved; then one
// thread against two.
void runStiffCloth(const LabOptions& options, const SmallStepsPlan& plan) {
  const auto rk4 = cell<Frames>(options, [&]() -> std::optional<Frames> { return timeRk4Step(plan); });
  auto series = [&](const std::vector<int>& substeps, bool lines) {
    return resultsInTurn<Frames>(
        options, substeps.size(), [&](std::size_t k) { return timeXpbdFrames(plan, substeps[k], lines); }, true);
  };
  const auto xpbd = series(plan.clothSubsteps, false);
  const auto lines = series(plan.lineSubsteps, true);
  Csv cloth(options, "small_steps_cloth.csv",
            {"method", "substeps", "frame_ms_median", "frame_ms_min", "frame_ms_max", "max_strain"});
  if (rk4) {
    writeFrames(cloth, "rk4-step", 0, *rk4);
    recordValue(options, "small_steps.cloth.rk4_step_ms", fixed(median(rk4->ms), 2));
  }
  writeSeries(options, cloth, "xpbd", "xpbd", plan.clothSubsteps, xpbd);
  writeSeries(options, cloth, "xpbd-lines", "lines", plan.lineSubsteps, lines);
  if (interrupted()) return;
  recordValue(options, "small_steps.cloth.target", targetText(plan.clothSubsteps, xpbd, "", rk4));
  recordValue(options, "small_steps.cloth.lines_target",
              targetText(plan.lineSubsteps, lines, " with the hanging lines solved", rk4));
  writeThreadedFrames(options, plan);
  if (interrupted()) return;
  recordValue(options, "small_steps.cloth.size", std::to_string(plan.clothSize));
}

}  // namespace

int runSmallSteps(const LabOptions& options) {
  prepareOutput(options, "small_steps.");
  std::cout << describe(options.criterion) << "\n";
  recordValue(options, "small_steps.failure", describe(options.criterion));
  const SmallStepsPlan plan = options.quick ? quickPlan() : fullPlan();
  long total = 0;
  for (const Problem& p : plan.problems)
    total +=
        1 + static_cast<long>(p.rk4Steps.size() + p.implicitSteps.size()) + 3 * static_cast<long>(plan.budgets.size());
  Progress progress(options, "small-steps", total);

  std::vector<ProblemRun> runs;
  for (const Problem& problem : plan.problems) {
    runs.push_back(measureProblem(options, problem, plan, progress));
    if (interrupted()) break;
  }
  Csv csv(options, "small_steps.csv",
          {"scene", "family", "split", "budget", "substeps", "iterations", "dt", "cpu_per_simulated_second",
           "constraint_error", "energy_loss_per_second", "position_error", "failure"});
  for (std::size_t k = 0; k < runs.size(); ++k) writeRunRows(csv, plan.problems[k], runs[k]);
  if (interrupted()) return 130;
  Tabulated tabulated;
  for (std::size_t k = 0; k < runs.size(); ++k) tabulateProblem(options, plan, plan.problems[k], runs[k], tabulated);
  writeFamilyTables(options, tabulated);
  runStiffCloth(options, plan);
  // 130 means an interrupt and nothing else: a cell without a result here
  // (another shard's) is no reason to stop.
  return interrupted() ? 130 : 0;
}

}  // namespace lab
