// `particle-lab small-steps`: Macklin et al. 2019 ("Small Steps in Physics
// Simulation") on our scenes. XPBD at a fixed budget n = substeps × iterations
// split three ways (1×n, √n×√n, n×1), beside implicit Euler and RK4 over dt,
// on conservative versions of the 80-chain, the stiff cloth and the hair
// (every spring and angle damper k_d = 0), each against a converged reference
// (RK4 at a small dt). Per run: CPU time per simulated second, constraint
// error, numerical damping and position error at T; a run stops at its first
// failure by the lab's criterion (failure.h), which is printed and recorded. Then the stiff 128² cloth
// at 60 Hz: frame time against substeps beside one RK4 step, in the same run.
#include <time.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

#include "lab/cells.h"
#include "lab/experiments.h"
#include "lab/failure.h"
#include "lab/lab_scene.h"
#include "particles/forces/spring.h"
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

}  // namespace

int runSmallSteps(const LabOptions& options) {
  prepareOutput(options);
  std::cout << describe(options.criterion) << "\n";
  recordValue(options, "small_steps.failure", describe(options.criterion));
  const bool q = options.quick;
  const double frame = 1.0 / 60.0;
  std::map<std::string, std::string> undampedCloth;
  const int clothSize = q ? 8 : 24;
  const std::vector<Problem> problems = {
      {"chain80", [] { return buildLabScene("test-chain", {{"cl", "80"}}); }, q ? 1.0 : 5.0, 1e-3,
       q ? std::vector<double>{frame, frame / 8} : std::vector<double>{frame, frame / 2, frame / 4, frame / 8, frame / 16},
       q ? std::vector<double>{frame} : std::vector<double>{frame, frame / 2, frame / 4, frame / 8}},
      {"stiff-cloth",
       [clothSize] {
         scenes::ClothParams p = scenes::stiffClothParams(clothSize);
         p.damping = 0.0;
         return scenes::buildCloth(p);
       },
       q ? 0.25 : 1.0, 1e-4,
       q ? std::vector<double>{frame / 64} : std::vector<double>{frame / 16, frame / 32, frame / 64, frame / 128},
       q ? std::vector<double>{frame} : std::vector<double>{frame, frame / 2, frame / 4, frame / 8}},
      {"hair", [] { return buildLabScene("hair", {{"damping", "0"}, {"bend-damping", "0"}}); }, q ? 1.0 : 4.0,
       2e-4, q ? std::vector<double>{frame / 8} : std::vector<double>{frame, frame / 2, frame / 4, frame / 8, frame / 16},
       q ? std::vector<double>{frame} : std::vector<double>{frame, frame / 2, frame / 4, frame / 8}},
  };
  // 20 is xpbd's default (20 × 1), the equal-cost yardstick below.
  const std::vector<int> budgets = q ? std::vector<int>{1, 4, 20} : std::vector<int>{1, 2, 4, 8, 16, 20, 32, 64};

  Csv csv(options, "small_steps.csv",
          {"scene", "family", "split", "budget", "substeps", "iterations", "dt", "cpu_per_simulated_second",
           "constraint_error", "energy_loss_per_second", "position_error", "failure"});
  auto write = [&](const std::string& scene, const std::string& family, const std::string& split, int budget,
                   int substeps, int iterations, double dt, const Outcome& o) {
    csv << scene << family << split << budget << substeps << iterations << dt << o.cpuPerSecond
        << o.constraintError << o.energyLoss << o.positionError << std::string(failureName(o.failure));
    csv.endRow();
  };
  long total = 0;
  for (const Problem& p : problems) total += 1 + static_cast<long>(p.rk4Steps.size() + p.implicitSteps.size()) + 3 * static_cast<long>(budgets.size());
  Progress progress(options, "small-steps", total);

  std::vector<std::vector<std::string>> claimRows, familyRows;
  bool substepsWinEverywhere = true, xpbdBeatsImplicitEverywhere = true;
  for (const Problem& p : problems) {
    const particles::IntegratorSettings defaults;
    // The converged reference: its outcome is a cell; its positions at T are
    // computed at most once here, by the first of the problem's cells that needs them.
    std::optional<Outcome> computed;
    const auto referenceX = [&]() -> const Eigen::VectorXd* {
      if (!computed) computed = runOne(p, "rk4", defaults, p.referenceDt, nullptr, options.criterion);
      return &computed->x;
    };
    const auto referenceCell = cell<Outcome>(options, [&]() -> std::optional<Outcome> {
      referenceX();
      progress.tick();
      if (interrupted()) return std::nullopt;
      return *computed;
    });
    if (interrupted()) return 130;
    const Outcome reference = referenceCell.value_or(Outcome{});
    if (referenceCell) write(p.name, "reference", "-", 0, 1, 1, p.referenceDt, reference);
    // One run against the reference, as a cell.
    const auto measure = [&](const std::string& integrator, const particles::IntegratorSettings& settings, double dt) {
      return cell<Outcome>(options, [&]() -> std::optional<Outcome> {
        const Outcome o = runOne(p, integrator, settings, dt, referenceX(), options.criterion);
        progress.tick();
        if (interrupted()) return std::nullopt;
        return o;
      });
    };
    std::map<std::string, Outcome> atLargest;
    Outcome xpbdDefault;
    const int largest = budgets.back();
    for (int n : budgets)
      for (const auto& [split, si] : splits(n)) {
        particles::IntegratorSettings settings;
        settings.substeps = si.first;
        settings.iterations = si.second;
        const auto run = measure("xpbd", settings, frame);
        if (interrupted()) return 130;
        if (!run) continue;  // another shard's cell
        const Outcome& o = *run;
        write(p.name, "xpbd", split, n, si.first, si.second, frame, o);
        if (n == largest) atLargest[split] = o;
        if (si.first == defaults.substeps && si.second == defaults.iterations) xpbdDefault = o;
      }
    // Fixed budget: do many substeps beat many iterations (constraint error and damping)?
    const Outcome& many = atLargest["nx1"];
    const Outcome& iterated = atLargest["1xn"];
    // Damping compares |energy change|: an unconverged solve can also gain energy.
    const bool wins = many.constraintError <= iterated.constraintError &&
                      std::abs(many.energyLoss) <= std::abs(iterated.energyLoss) &&
                      many.positionError <= iterated.positionError;
    substepsWinEverywhere &= wins;
    claimRows.push_back({p.name, std::to_string(largest), general(many.constraintError), general(iterated.constraintError),
                         general(many.energyLoss), general(iterated.energyLoss), general(many.positionError),
                         general(iterated.positionError), wins ? "yes" : "no"});
    recordValue(options, "small_steps." + p.name + ".nx1_constraint_error", general(many.constraintError));
    recordValue(options, "small_steps." + p.name + ".1xn_constraint_error", general(iterated.constraintError));

    // Equal CPU time per simulated second: the force-based run with the
    // smallest dt whose cost is at most xpbd's default (20 × 1), else the cheapest.
    familyRows.push_back(row(p.name, "reference: rk4 at dt " + general(p.referenceDt, 2), reference));
    familyRows.push_back(row(p.name, "xpbd 20x1 at 1/60", xpbdDefault));
    recordRow(options, p.name, "xpbd", xpbdDefault);
    recordRow(options, p.name, "reference", reference);
    const double budget = xpbdDefault.cpuPerSecond;
    for (const auto& [family, stepsList] : {std::pair{std::string("implicit-euler"), p.implicitSteps},
                                           std::pair{std::string("rk4"), p.rk4Steps}}) {
      Outcome chosen;
      double chosenDt = 0.0;
      bool any = false;
      for (double dt : stepsList) {
        const auto run = measure(family, defaults, dt);
        if (interrupted()) return 130;
        if (!run) continue;  // another shard's cell
        const Outcome& o = *run;
        write(p.name, family, "-", 0, 1, 1, dt, o);
        const bool affordable = o.cpuPerSecond <= budget;
        if (!any || (affordable && (chosen.cpuPerSecond > budget || dt < chosenDt)) ||
            (!affordable && chosen.cpuPerSecond > budget && o.cpuPerSecond < chosen.cpuPerSecond)) {
          chosen = o;
          chosenDt = dt;
          any = true;
        }
      }
      familyRows.push_back(row(p.name,
                               family + " at dt " + general(chosenDt, 3) +
                                   (chosen.failed() ? std::string(" (failed: ") + failureName(chosen.failure) + ")" : ""),
                               chosen));
      recordRow(options, p.name, family, chosen);
      if (family == "implicit-euler")
        xpbdBeatsImplicitEverywhere &= xpbdDefault.constraintError <= chosen.constraintError &&
                                       std::abs(xpbdDefault.energyLoss) <= std::abs(chosen.energyLoss);
    }
    recordValue(options, "small_steps." + p.name + ".xpbd_cpu_per_second", general(budget));
  }
  writeTable(options, "small_steps_budget",
             "Fixed budget n = substeps × iterations at 1/60 s: n substeps of one pass (nx1) against one substep of n "
             "passes (1xn); constraint error = worst relative violation over the run, damping = energy lost per "
             "simulated second over the energy scale, position error at T over the scene's diagonal",
             {"scene", "n", "error nx1", "error 1xn", "damping nx1", "damping 1xn", "position nx1", "position 1xn",
              "nx1 wins all three"},
             claimRows);
  writeTable(options, "small_steps_families",
             "Equal CPU time per simulated second: xpbd 20 × 1 at 1/60 s against the force-based run with the "
             "smallest dt that costs no more (else the cheapest run); columns as above (negative damping: energy "
             "gained), CPU in s per simulated s; the reference's violation is the physical stretch of the springs",
             {"scene", "method", "CPU/s", "constraint error", "damping /s", "position error"}, familyRows);
  recordValue(options, "small_steps.claim_substeps",
              substepsWinEverywhere ? "holds on every scene" : "does not hold on every scene");
  recordValue(options, "small_steps.claim_implicit",
              xpbdBeatsImplicitEverywhere ? "holds on every scene" : "does not hold on every scene");

  // --- the stiff cloth at 60 Hz ---------------------------------------------
  const int n = q ? 32 : 128;
  const int repeats = q ? 3 : 5;
  Csv cloth(options, "small_steps_cloth.csv",
            {"method", "substeps", "frame_ms_median", "frame_ms_min", "frame_ms_max", "max_strain"});
  auto medianFrames = [&](scenes::Scene& scene, particles::Integrator& stepper, double dt, int frames) {
    std::vector<double> ms;
    for (int k = 0; k < frames; ++k) {
      const double start = cpuSeconds();
      scene.system->step(stepper, dt);
      ms.push_back(1e3 * (cpuSeconds() - start));
    }
    return ms;
  };
  if (const auto frames = cell<Frames>(options, [&]() -> std::optional<Frames> {
        scenes::Scene scene = scenes::buildCloth(scenes::stiffClothParams(n));
        auto rk4 = particles::makeIntegrator("rk4");
        // The cost of a step does not depend on its size; 5e-5 s is within RK4's
        // stable step on this cloth (about 1e-4 s), so the state stays finite.
        Frames out;
        out.ms = medianFrames(scene, *rk4, 5e-5, 2 * repeats);
        out.worst = worstViolation(*scene.system);
        return out;
      })) {
    const std::vector<double>& ms = frames->ms;
    cloth << std::string("rk4-step") << 0 << median(ms) << *std::min_element(ms.begin(), ms.end())
          << *std::max_element(ms.begin(), ms.end()) << frames->worst;
    cloth.endRow();
    recordValue(options, "small_steps.cloth.rk4_step_ms", fixed(median(ms), 2));
  }
  // The target: a frame in at most 16 ms with every spring within 3 %,
  // by the fewest substeps that keep the strain.
  const double targetMs = 16.0, targetStrain = 0.03;
  std::string target;
  for (int substeps : q ? std::vector<int>{10, 30} : std::vector<int>{10, 20, 30, 40, 60}) {
    const auto frames = cell<Frames>(options, [&]() -> std::optional<Frames> {
      scenes::Scene scene = scenes::buildCloth(scenes::stiffClothParams(n));
      particles::IntegratorSettings settings;
      settings.substeps = substeps;
      auto xpbd = particles::makeIntegrator("xpbd", settings);
      Frames out;
      for (int k = 0; k < (q ? 10 : 60) && !interrupted(); ++k) {  // one simulated second: the cloth hangs loaded
        scene.system->step(*xpbd, frame);
        out.worst = std::max(out.worst, worstViolation(*scene.system));
      }
      out.ms = medianFrames(scene, *xpbd, frame, repeats);
      out.worst = std::max(out.worst, worstViolation(*scene.system));
      if (interrupted()) return std::nullopt;
      return out;
    });
    if (interrupted()) return 130;
    if (!frames) continue;  // another shard's cell
    const std::vector<double>& ms = frames->ms;
    const double worst = frames->worst;
    cloth << std::string("xpbd") << substeps << median(ms) << *std::min_element(ms.begin(), ms.end())
          << *std::max_element(ms.begin(), ms.end()) << worst;
    cloth.endRow();
    recordValue(options, "small_steps.cloth.xpbd" + std::to_string(substeps) + "_ms", fixed(median(ms), 2));
    recordValue(options, "small_steps.cloth.xpbd" + std::to_string(substeps) + "_strain_percent", fixed(100 * worst, 2));
    if (target.empty() && worst <= targetStrain)
      target = (median(ms) <= targetMs ? "is met by " : "is not met on this machine: the fewest substeps within 3 %, ") +
               std::to_string(substeps) + " of one pass, take " + fixed(median(ms), 2) + " ms with the worst spring at " +
               fixed(100 * worst, 2) + " %";
  }
  if (target.empty()) target = "is not met: no substep count measured keeps every spring within 3 %";
  recordValue(options, "small_steps.cloth.target", target);
  recordValue(options, "small_steps.cloth.size", std::to_string(n));
  return 0;
}

}  // namespace lab
