// `particle-lab claims`: the seed report's claims, each confirmed or refuted by
// a measurement.
#include <cmath>
#include <iostream>
#include <limits>

#include "particles/constants.h"
#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/lab_scene.h"
#include "lab/cells.h"
#include "lab/results.h"
#include "particles/forces/mouse_spring.h"
#include "output/format_number.h"

namespace lab {

namespace {

// Mean and largest |corner angle − 90°| (degrees) over the cells of a cloth
// whose particles are laid out row by row, `width` per row.
std::pair<double, double> cellShear(const particles::ParticleSystem& s, int width, int height) {
  double sum = 0.0, worst = 0.0;
  int cells = 0;
  for (int r = 0; r + 1 < height; ++r)
    for (int c = 0; c + 1 < width; ++c) {
      const int i = r * width + c;
      const Eigen::Vector2d a = s.position(i + 1) - s.position(i), b = s.position(i + width) - s.position(i);
      const double cosine = a.dot(b) / (a.norm() * b.norm());
      const double shear = std::abs(std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / particles::kPi - 90.0);
      sum += shear, worst = std::max(worst, shear), ++cells;
    }
  return {cells ? sum / cells : 0.0, worst};
}

std::string verdict(bool confirmed) { return confirmed ? "confirmed" : "refuted"; }

using Rows = std::vector<std::vector<std::string>>;

// What the experiment measures.
struct ClaimsPlan {
  double duration = 0.0;          // T of every run, s
  TimingOptions timing;           // of the step costs
  int chainLength = 0;            // the chain timed (claims 1, 2) and starved (claim 4)
  int scanLength = 0;             // the chain whose safe dt is scanned (claim 2)
  double scanGridLo = 0.0;        // the scanned grid's smallest dt (up to 0.5)
  int scanMembers = 0;            // starts per scanned dt
  std::vector<int> cgLengths;     // chains whose CG iterations are counted (claim 3)
  int clothSide = 0;              // particles per side of the pulled cloths (claim 5)
  long progressTotal = 0;         // the progress estimate
};

// Small scenes, short runs: proves the code runs.
ClaimsPlan quickPlan() { return {2.0, {1, 5}, 12, 6, 0.025, 1, {5, 10, 20}, 5, 30}; }

// Runs last as long as the stability tables' T (StabilityOptions).
ClaimsPlan fullPlan() {
  return {StabilityOptions{}.duration, {5, 20}, 80, 24, 0.05 / 8, 3, {10, 20, 40, 80, 160, 320, 500}, 10, 80};
}

// What every claim shares: the claims table grows by one or two rows per claim.
struct Context {
  const LabOptions& options;
  const ClaimsPlan& plan;
  Progress& progress;
  Rows table;
};

// 1. "Changing the time step size has virtually no effect on the duration of the time step."
const std::vector<std::string> kCostIntegrators = {"midpoint", "rk4"};
const std::vector<double> kCostSteps = {0.005, 0.01, 0.02, 0.05, 0.1};

void claimCostVsDt(Context& context) {
  const ClaimsPlan& plan = context.plan;
  const std::size_t steps = kCostSteps.size();
  const auto results = resultsInTurn<StepCost>(
      context.options, kCostIntegrators.size() * steps,
      [&](std::size_t k) {
        scenes::Scene chain = buildChain({plan.chainLength});
        return measureStepCost(chain, kCostIntegrators[k / steps], kCostSteps[k % steps], plan.timing);
      },
      false, [&](std::size_t) { context.progress.tick(); });
  Csv csv(context.options, "claims_cost_vs_dt.csv", {"integrator", "dt", "step_seconds", "cg_iterations_per_step"});
  std::vector<double> lo(kCostIntegrators.size(), std::numeric_limits<double>::infinity());
  std::vector<double> hi(kCostIntegrators.size(), 0.0);
  for (const auto& [k, cost] : results) {
    csv << kCostIntegrators[k / steps] << kCostSteps[k % steps] << cost.seconds << cost.cgIterations;
    csv.endRow();
    const std::size_t i = k / steps;
    if (std::isfinite(cost.seconds)) lo[i] = std::min(lo[i], cost.seconds), hi[i] = std::max(hi[i], cost.seconds);
  }
  if (interrupted()) return;  // never a verdict from a cut-short measurement
  double worstRatio = 0.0;
  for (std::size_t i = 0; i < kCostIntegrators.size(); ++i) worstRatio = std::max(worstRatio, hi[i] / lo[i]);
  recordValue(context.options, "claims.cost_vs_dt_ratio", fixed(worstRatio, 2));
  context.table.push_back({"cost per step hardly depends on dt",
                           "slowest/fastest step over dt 0.005–0.1 (midpoint, RK4, " +
                               std::to_string(plan.chainLength) + "-chain): " + fixed(worstRatio, 2),
                           verdict(worstRatio < 1.5)});
}

// 2. "RK4 is about twice as slow as midpoint, but allows more than twice the step."
//    Both step times measured in one cell, so their ratio is taken in one run.
std::pair<double, double> rk4AndMidpointSeconds(const ClaimsPlan& plan) {
  scenes::Scene a = buildChain({plan.chainLength}), b = buildChain({plan.chainLength});
  return std::pair{measureStepCost(a, "rk4", a.dt, plan.timing).seconds,
                   measureStepCost(b, "midpoint", b.dt, plan.timing).seconds};
}

ScanSettings rk4MidpointScan(const ClaimsPlan& plan) {
  ScanSettings scan;
  scan.grid = stepGrid(plan.scanGridLo, 0.5);
  scan.members = plan.scanMembers;
  return scan;
}

void claimRk4AgainstMidpoint(Context& context) {
  const ClaimsPlan& plan = context.plan;
  const auto times = cell<std::pair<double, double>>(
      context.options, [&]() -> std::optional<std::pair<double, double>> { return rk4AndMidpointSeconds(plan); });
  const double rk4 = times ? times->first : std::nan(""), mid = times ? times->second : std::nan("");
  const ScanSettings scan = rk4MidpointScan(plan);
  const std::vector<std::string> pair = {"rk4", "midpoint"};
  const auto scanned = sweepResults<Boundary>(context.options, 2, [&](std::size_t k) {
    auto boundary = scanSafeStep([&] { return buildChain({plan.scanLength}); }, pair[k], plan.duration, scan,
                          context.options.criterion);
    context.progress.tick();
    return boundary;
  });
  if (interrupted()) return;
  std::vector<Boundary> boundaries(2);
  for (const auto& [k, boundary] : scanned) boundaries[k] = boundary;
  const double dtRk4 = boundaries[0].safeDt, dtMid = boundaries[1].safeDt;
  recordValue(context.options, "claims.rk4_midpoint_cost_ratio", fixed(rk4 / mid, 2));
  recordValue(context.options, "claims.rk4_midpoint_step_ratio", fixed(dtRk4 / dtMid, 2));
  context.table.push_back({"RK4 costs about twice midpoint per step", "RK4/midpoint step time: " + fixed(rk4 / mid, 2),
                           verdict(rk4 / mid > 1.5 && rk4 / mid < 2.5)});
  context.table.push_back(
      {"RK4 allows more than twice midpoint's step",
       "largest surviving dt (coarse scan, " + output::plural(scan.members, "start") + "), " + std::to_string(plan.scanLength) +
           "-chain, T = " + general(plan.duration) + " s: RK4 " + safeStepText(boundaries[0]) + ", midpoint " +
           safeStepText(boundaries[1]) + " (ratio " + fixed(dtRk4 / dtMid, 2) + ")",
       dtMid > 0.0 && !boundaries[0].aboveGrid() ? verdict(dtRk4 > 2.0 * dtMid) : "undecided"});
}

// 3. "The number of CG steps is about linear in the number of constraints."
//    (constraints, plain CG iterations per solve, Jacobi warm-started CG iterations per solve)
using Counts = std::pair<double, std::pair<double, double>>;

Counts countCgIterations(int length) {
  scenes::Scene chain = buildChain({length});
  auto& settings = chain.system->solver().settings;
  settings.method = particles::SolveMethod::ConjugateGradient;
  settings.warmStart = false;
  settings.preconditioner = particles::Preconditioner::None;
  const StepCost plainCost = measureStepCost(chain, "rk4", chain.dt, {1, 5});
  scenes::Scene tuned = buildChain({length});
  tuned.system->solver().settings.method = particles::SolveMethod::ConjugateGradient;
  const StepCost defaultCost = measureStepCost(tuned, "rk4", tuned.dt, {1, 5});
  return Counts{static_cast<double>(chain.system->constraints().size()),
                {plainCost.cgIterationsPerSolve(), defaultCost.cgIterationsPerSolve()}};
}

void claimCgIterations(Context& context) {
  const std::vector<int>& lengths = context.plan.cgLengths;
  const auto results = resultsInTurn<Counts>(
      context.options, lengths.size(),
      [&](std::size_t k) {
        const Counts counts = countCgIterations(lengths[k]);
        context.progress.tick();
        return counts;
      },
      false);
  Csv csv(context.options, "claims_cg_iterations.csv",
          {"constraints", "plain_cg_iterations_per_solve", "jacobi_warm_cg_iterations_per_solve"});
  std::vector<double> m, plain;
  for (const auto& [k, counts] : results) {
    const auto& [constraints, perSolve] = counts;
    csv << constraints << perSolve.first << perSolve.second;
    csv.endRow();
    m.push_back(constraints), plain.push_back(perSolve.first);
  }
  if (interrupted()) return;
  const double slope = logLogSlope(m, plain);
  recordValue(context.options, "claims.cg_iterations_slope", fixed(slope, 2));
  context.table.push_back({"CG iterations grow about linearly with the number of constraints",
                           "plain CG iterations per solve ∝ m^" + fixed(slope, 2) + " (chains of " +
                               std::to_string(lengths.front()) + "–" + std::to_string(lengths.back()) + ")",
                           verdict(slope > 0.8 && slope < 1.2)});
}

// 4. "A solver limited below the desired number of steps stretches rods but does not explode."
//    Jacobi CG capped at a few iterations, started cold and warm (from the
//    previous λ, which lets a capped solve keep converging across steps).
//    The runs stop only at a non-finite state or a failed step (the
//    stretch and energy thresholds are lifted and their extremes recorded),
//    so the verdict can be read at every threshold: the claim holds at
//    stretch threshold τ when every capped run stayed finite with max |C|/r ≤ τ
//    and — unless only a non-finite state counts as exploding — with its
//    energy rise within the criterion's fraction of E_s.
const std::vector<int> kStarvedCaps = {1, 2, 5, 0};
const std::vector<double> kStretchThresholds = {0.01, 0.03, 0.1, 0.3, 1.0};

struct Starved {
  bool warm;
  int cap;  // 0: uncapped
};

std::vector<Starved> starvedCells() {
  std::vector<Starved> cells;
  for (bool warm : {false, true})
    for (int cap : kStarvedCaps) cells.push_back({warm, cap});
  return cells;
}

std::optional<RunResult> runStarved(const Context& context, const Starved& cell) {
  FailureCriterion finiteOnly = context.options.criterion;
  finiteOnly.maxRelativeConstraintError = std::numeric_limits<double>::infinity();
  finiteOnly.energyRiseFraction = std::numeric_limits<double>::infinity();
  scenes::Scene chain = buildChain({context.plan.chainLength});
  auto& settings = chain.system->solver().settings;
  settings.method = particles::SolveMethod::ConjugateGradient;
  settings.maxIterations = cell.cap;
  settings.warmStart = cell.warm;
  auto stepper = particles::makeIntegrator("rk4");
  RunResult run = simulate(chain, *stepper, 0.01, context.plan.duration, finiteOnly);
  context.progress.tick();
  if (run.cutShort) return std::nullopt;
  return run;
}

// Every run in words: "cold: cap 1 …; warm: …".
std::string starvedDetail(const std::vector<Starved>& cells, const std::vector<RunResult>& results) {
  std::string detail;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (k % kStarvedCaps.size() == 0)
      detail += std::string(detail.empty() ? "" : "; ") + (cells[k].warm ? "warm:" : "cold:");
    const RunResult& run = results[k];
    detail += std::string(" ") + (cells[k].cap ? "cap " + std::to_string(cells[k].cap) : std::string("uncapped")) +
              " " +
              (run.failed ? run.reason + " at t = " + general(run.time, 3)
                          : "stretch " + general(run.maxRelativeStretch, 2) + ", energy rise " +
                                general(run.maxEnergyRise, 2) + " E_s");
  }
  return detail;
}

// Whether the claim holds at stretch threshold τ: [energy counted][warm].
struct Holds {
  bool at[2][2] = {{true, true}, {true, true}};
};

Holds holdsAt(double tau, const std::vector<Starved>& cells, const std::vector<RunResult>& results, double rise) {
  Holds holds;
  for (int countEnergy = 0; countEnergy < 2; ++countEnergy)
    for (std::size_t k = 0; k < cells.size(); ++k) {
      if (cells[k].cap <= 0) continue;
      const RunResult& run = results[k];
      const bool exploded = run.failed || (countEnergy && run.maxEnergyRise > rise);
      bool& holdsHere = holds.at[countEnergy][cells[k].warm];
      holdsHere = holdsHere && !exploded && run.maxRelativeStretch <= tau;
    }
  return holds;
}

std::string verdictAtCriterion(const Holds& holds) {
  const bool cold = holds.at[1][0], warm = holds.at[1][1];
  if (cold && warm) return "confirmed";
  if (warm) return "confirmed only with warm start";
  return cold ? "confirmed only with cold start" : "refuted";
}

// The verdict at each stretch threshold, with and without the energy test; the verdict at the criterion's.
std::string writeStarvedVerdicts(const Context& context, const std::vector<Starved>& cells,
                                 const std::vector<RunResult>& results) {
  const FailureCriterion& criterion = context.options.criterion;
  Csv verdicts(context.options, "claims_starved_cg_verdict.csv",
               {"max_stretch_threshold", "cold", "warm", "cold_non_finite_only", "warm_non_finite_only"});
  Rows rows;
  std::string atCriterion;
  for (double tau : kStretchThresholds) {
    const Holds h = holdsAt(tau, cells, results, criterion.energyRiseFraction);
    verdicts << tau << verdict(h.at[1][0]) << verdict(h.at[1][1]) << verdict(h.at[0][0]) << verdict(h.at[0][1]);
    verdicts.endRow();
    rows.push_back({general(tau), verdict(h.at[1][0]), verdict(h.at[1][1]), verdict(h.at[0][0]), verdict(h.at[0][1])});
    if (tau == criterion.maxRelativeConstraintError) atCriterion = verdictAtCriterion(h);
  }
  writeTable(context.options, "claims_starved_cg",
             "A starved solver (Jacobi CG capped at 1, 2, 5 iterations, RK4, dt 0.01, " +
                 std::to_string(context.plan.chainLength) + "-chain, T = " + general(context.plan.duration) +
                 " s): the claim's verdict against the stretch threshold max |C|/r, counting an energy rise above " +
                 general(criterion.energyRiseFraction) + " E_s as exploding or only a non-finite state",
             {"stretch threshold", "cold start", "warm start", "cold, non-finite only", "warm, non-finite only"}, rows);
  return atCriterion.empty() ? "see the threshold table" : atCriterion;
}

void claimStarvedSolver(Context& context) {
  const std::vector<Starved> cells = starvedCells();
  const auto measured = sweepResults<RunResult>(context.options, cells.size(),
                                                [&](std::size_t k) { return runStarved(context, cells[k]); });
  Csv csv(context.options, "claims_starved_cg.csv",
          {"warm_start", "max_iterations", "failure", "time", "max_relative_stretch", "max_energy_rise"});
  std::vector<RunResult> results(cells.size());
  for (const auto& [k, run] : measured) {
    csv << static_cast<long>(cells[k].warm) << static_cast<long>(cells[k].cap) << failureName(run.failure) << run.time
        << run.maxRelativeStretch << run.maxEnergyRise;
    csv.endRow();
    results[k] = run;
  }
  if (interrupted()) return;
  const std::string detail = starvedDetail(cells, results);
  const std::string atCriterion = writeStarvedVerdicts(context, cells, results);
  context.table.push_back({"a starved solver stretches rods but does not explode",
                           detail + " (verdict at the criterion's max |C|/r = " +
                               general(context.options.criterion.maxRelativeConstraintError) +
                               "; other thresholds in the table below)",
                           atCriterion});
}

// 5. "The 4-way cloth under gravity or pulling is less cloth-like than the 8-way one": cell shear.
const std::vector<std::string> kClothLinks = {"4", "8"};

// (mean, largest) cell shear over a run of the cloth with its bottom-left
// corner pulled sideways, as a user dragging it would.
std::optional<std::pair<double, double>> measureShear(const Context& context, const std::string& links) {
  const int side = context.plan.clothSide;
  scenes::Scene cloth =
      buildLabScene("cloth", {{"width", std::to_string(side)}, {"height", std::to_string(side)}, {"links", links}});
  const int corner = (side - 1) * side;
  cloth.system->addForce(std::make_unique<particles::MouseSpringForce>(
      corner, cloth.system->position(corner) + Eigen::Vector2d(-0.3, 0.0), 1.0, 0.5));
  auto stepper = particles::makeIntegrator("rk4");
  double sum = 0.0, worst = 0.0;
  int samples = 0;
  const RunResult run =
      simulate(cloth, *stepper, cloth.dt, context.plan.duration, context.options.criterion,
               [&](const particles::ParticleSystem& s) {
                 const auto [meanShear, worstShear] = cellShear(s, side, side);
                 sum += meanShear, worst = std::max(worst, worstShear), ++samples;
                 return true;
               });
  context.progress.tick();
  if (run.cutShort) return std::nullopt;
  return std::pair{samples ? sum / samples : 0.0, worst};
}

void claimClothShear(Context& context) {
  const auto shears = resultsInTurn<std::pair<double, double>>(
      context.options, kClothLinks.size(), [&](std::size_t k) { return measureShear(context, kClothLinks[k]); }, true);
  Csv csv(context.options, "claims_cloth_shear.csv", {"links", "mean_shear_degrees", "max_shear_degrees"});
  double mean[2] = {0, 0};
  for (const auto& [k, shear] : shears) {
    mean[k] = shear.first;
    csv << kClothLinks[k] << mean[k] << shear.second;
    csv.endRow();
  }
  if (interrupted()) return;
  recordValue(context.options, "claims.shear_4way", fixed(mean[0], 2));
  recordValue(context.options, "claims.shear_8way", fixed(mean[1], 2));
  context.table.push_back({"4-way cloth deforms less cloth-like than 8-way",
                           "mean cell shear while pulled: 4-way " + fixed(mean[0], 1) + "°, 8-way " +
                               fixed(mean[1], 1) + "°",
                           verdict(mean[0] > mean[1])});
}

// The claims in the order they are measured.
const std::vector<void (*)(Context&)> kClaims = {claimCostVsDt, claimRk4AgainstMidpoint, claimCgIterations,
                                                 claimStarvedSolver, claimClothShear};

}  // namespace

int runClaims(const LabOptions& options) {
  prepareOutput(options, "claims.");
  const ClaimsPlan plan = options.quick ? quickPlan() : fullPlan();
  std::cout << describe(options.criterion) << "\n";
  Progress progress(options, "claims", plan.progressTotal);
  Context context{options, plan, progress, {}};
  for (const auto claim : kClaims) {
    claim(context);
    if (interrupted()) return 130;
  }
  recordValue(options, "claims.duration", general(plan.duration));
  writeTable(options, "claims", "The seed report's claims, measured (" + describe(options.criterion) + ")",
             {"claim", "measurement", "verdict"}, context.table);
  return interrupted() ? 130 : 0;
}

}  // namespace lab
