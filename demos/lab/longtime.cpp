// `particle-lab longtime`: long-time behaviour. The total energy against time
// over at least 500 s for every integrator on the pendulum and the 6-chain at
// one common dt per scene, and implicit Euler's energy loss per period against
// dt on the pendulum.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "lab/cells.h"
#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/lab_scene.h"
#include "lab/results.h"
#include "scenes/pendulum.h"

namespace lab {

namespace {

struct LongRun {
  std::string label;
  std::string scene;
  std::map<std::string, std::string> params;
  double dt;  // common to every integrator: inside every scheme's safe range
};

// One integrator's run: (E − E(0)) / E_s sampled against time.
struct EnergyRun {
  std::vector<std::pair<double, double>> samples;  // (t, energy change), every `every` s
  bool failed = false;
  double time = 0.0;  // reached
  double last = 0.0;  // the energy change after the last step
};
template <class Io>
void fields(Io& io, EnergyRun& r) {
  io("samples", r.samples), io("failed", r.failed), io("time", r.time), io("last", r.last);
}

// Implicit Euler at one dt: the pendulum's swing energy left and lost per period, the 6-chain's loss.
struct Damping {
  double dt = 0.0, left = 0.0, perPeriod = 0.0, chain = 0.0;
};
template <class Io>
void fields(Io& io, Damping& d) {
  io("dt", d.dt), io("left", d.left), io("per_period", d.perPeriod), io("chain", d.chain);
}

// What the experiment runs.
struct LongtimePlan {
  double horizon = 0.0;               // T of the energy runs, s
  double every = 0.0;                 // their energy is sampled every `every` s
  std::vector<double> implicitSteps;  // dt of implicit Euler's damping runs (moved to divide their T)
  double pendulumPeriods = 0.0;       // the damping runs' T on the pendulum, in periods
  double chainDuration = 0.0;         // the damping runs' T on the 6-chain, s
};

// Short runs: proves the code runs.
LongtimePlan quickPlan() { return {20.0, 0.5, {0.05, 0.2}, 2.0, 5.0}; }
LongtimePlan fullPlan() { return {500.0, 1.0, logSpace(0.005, 0.5, 7), 5.0, 60.0}; }

const std::vector<LongRun> kLongRuns = {{"pendulum", "pendulum", {}, 0.05},
                                        {"6-chain", "test-chain", {{"cl", "6"}}, 0.01}};

// The drift runs: constrained scenes under the schemes that keep energy
// bounded without constraints (symplectic Euler, Verlet) and the one that
// projects onto the constraints (RATTLE), each at a dt and its halvings.
struct DriftScene {
  LongRun run;               // run.dt: the largest of the halvings
  std::vector<double> steps;
};
const std::vector<std::string> kDriftIntegrators = {"symplectic-euler", "verlet", "rattle"};

std::vector<DriftScene> driftScenes(bool quick) {
  const int halvings = quick ? 2 : 3;
  std::vector<DriftScene> scenes = {{{"pendulum", "pendulum", {}, 0.05}, {}},
                                    {{"bead on a wire", "wire", {{"beads", "1"}}, 0.05}, {}},
                                    {{"6-chain", "test-chain", {{"cl", "6"}}, 0.01}, {}}};
  for (DriftScene& scene : scenes)
    for (int k = 0; k < halvings; ++k) scene.steps.push_back(scene.run.dt / std::pow(2.0, k));
  return scenes;
}

// One drift cell: scene, integrator, dt.
struct DriftCell {
  std::size_t scene;
  std::string integrator;
  double dt;
};

std::vector<DriftCell> driftCells(const std::vector<DriftScene>& scenes) {
  std::vector<DriftCell> cells;
  for (std::size_t k = 0; k < scenes.size(); ++k)
    for (const auto& name : kDriftIntegrators)
      for (double dt : scenes[k].steps) cells.push_back({k, name, dt});
  return cells;
}

// Least-squares slope of the energy change against time (per second), and its largest magnitude.
std::pair<double, double> driftOf(const EnergyRun& run) {
  double st = 0, se = 0, stt = 0, ste = 0, largest = 0;
  for (const auto& [t, e] : run.samples) st += t, se += e, stt += t * t, ste += t * e, largest = std::max(largest, std::abs(e));
  const double n = static_cast<double>(run.samples.size());
  const double denominator = n * stt - st * st;
  return {n > 1 && denominator > 0 ? (n * ste - st * se) / denominator : std::nan(""), largest};
}

// Only non-finite states end a run: the drift itself is what is shown.
FailureCriterion driftCriterion() {
  FailureCriterion drift;
  drift.maxRelativeConstraintError = drift.energyRiseFraction = std::numeric_limits<double>::infinity();
  return drift;
}

std::optional<EnergyRun> runEnergy(const LongtimePlan& plan, const LongRun& run, const std::string& integrator) {
  scenes::Scene scene = buildLabScene(run.scene, run.params);
  const double scale = releasableEnergy(*scene.system), e0 = scene.system->totalEnergy();
  auto stepper = particles::makeIntegrator(integrator);
  const long stride = std::max(1L, std::lround(plan.every / run.dt));
  long step = 0;
  EnergyRun out;
  const RunResult result =
      simulate(scene, *stepper, run.dt, plan.horizon, driftCriterion(), [&](const particles::ParticleSystem& s) {
        out.last = (s.totalEnergy() - e0) / scale;
        if (++step % stride == 0) out.samples.push_back({s.time(), out.last});
        return true;
      });
  if (result.cutShort) return std::nullopt;
  out.failed = result.failed, out.time = result.time;
  return out;
}

std::string energyText(const EnergyRun& run) {
  if (run.failed) return "non-finite at t = " + general(run.time, 3);
  return std::abs(run.last) > 1e3 ? "diverged (" + general(run.last, 2) + ")" : general(run.last, 2);
}

// Cell k is kLongRuns[k / integrators] under integrator k % integrators.
void writeEnergy(const LabOptions& options, const LongtimePlan& plan, const std::vector<std::string>& integrators,
                 const Results<EnergyRun>& results) {
  Csv energy(options, "longtime_energy.csv", {"problem", "integrator", "dt", "time", "energy_change"});
  std::vector<std::vector<std::string>> table;
  for (std::size_t r = 0; r < kLongRuns.size(); ++r) {
    const LongRun& run = kLongRuns[r];
    std::vector<std::string> row{run.label + " (dt = " + general(run.dt) + " s)"};
    for (std::size_t i = 0; i < integrators.size(); ++i) {
      const auto found = results.find(r * integrators.size() + i);
      if (found == results.end()) continue;  // another shard's cell, or cut short
      const EnergyRun& result = found->second;
      energy << run.label << integrators[i] << run.dt << 0.0 << 0.0;
      energy.endRow();
      for (const auto& [t, change] : result.samples) {
        energy << run.label << integrators[i] << run.dt << t << change;
        energy.endRow();
      }
      row.push_back(energyText(result));
      recordValue(options, "longtime.energy_change." + run.label + "." + integrators[i], general(result.last, 2));
    }
    table.push_back(row);
  }
  std::vector<std::string> header{"problem"};
  for (const auto& name : integrators) header.push_back(name);
  writeTable(options, "longtime_energy",
             "Energy change (E(T) − E(0)) / E_s after T = " + general(plan.horizon) +
                 " s at one dt per scene (E_s: the energy the scene can release, lab/failure.h)",
             header, table);
}

// The 6-chain beside the pendulum: energy lost over its T as a fraction of the
// potential drop from the start to hanging straight, g·m·L·cl(cl−1)/2.
double chainLoss(double dt, double duration) {
  scenes::Scene chain = buildChain(ChainSpec(6));
  const double drop = releasableEnergy(*chain.system);  // g·m·L·cl(cl−1)/2 for the test chain
  const double e0 = chain.system->totalEnergy();
  auto stepper = particles::makeIntegrator("implicit-euler");
  simulate(chain, *stepper, duration / std::round(duration / dt), duration, driftCriterion());
  return (e0 - chain.system->totalEnergy()) / drop;
}

// Implicit Euler damps: the swing energy E − E_bottom left after whole
// periods P gives the fraction lost per period, 1 − (E_s(T)/E_s(0))^(P/T).
std::optional<Damping> measureDamping(const LongtimePlan& plan, double wanted, double period, double eBottom) {
  const double T = plan.pendulumPeriods * period;
  Damping damping;
  damping.dt = T / std::round(T / wanted);
  scenes::Scene scene = buildLabScene("pendulum");
  const double swing0 = scene.system->totalEnergy() - eBottom;
  auto stepper = particles::makeIntegrator("implicit-euler");
  simulate(scene, *stepper, damping.dt, T, driftCriterion());
  if (interrupted()) return std::nullopt;
  damping.left = (scene.system->totalEnergy() - eBottom) / swing0;
  damping.perPeriod = 1.0 - std::pow(std::max(damping.left, 0.0), period / T);
  damping.chain = chainLoss(damping.dt, plan.chainDuration);
  return damping;
}

void writeDamping(const LabOptions& options, const LongtimePlan& plan, double period,
                  const Results<Damping>& results) {
  const double T = plan.pendulumPeriods * period;
  Csv loss(options, "longtime_implicit_loss.csv",
           {"dt", "periods", "swing_energy_left", "loss_per_period", "chain6_loss"});
  std::vector<std::vector<std::string>> lossRows;
  std::vector<std::pair<double, double>> chain;  // (dt, lost), ascending dt
  for (const auto& [k, damping] : results) {
    loss << damping.dt << T / period << damping.left << damping.perPeriod << damping.chain;
    loss.endRow();
    lossRows.push_back({general(damping.dt), general(100 * damping.left, 3) + "%",
                        general(100 * damping.perPeriod, 2) + "%", general(100 * damping.chain, 2) + "%"});
    chain.emplace_back(damping.dt, damping.chain);
  }
  // How the chain's loss moves with dt, as the report states it: it grows with dt, or the first
  // pair of steps where it does not.
  std::sort(chain.begin(), chain.end());
  std::string trend = "grows with dt too";
  for (std::size_t k = 1; k < chain.size(); ++k)
    if (!(chain[k].second > chain[k - 1].second)) {
      trend = "does not grow with dt everywhere: " + general(100 * chain[k - 1].second, 2) + "% at dt " +
              general(chain[k - 1].first, 3) + " s against " + general(100 * chain[k].second, 2) + "% at " +
              general(chain[k].first, 3) + " s";
      break;
    }
  recordValue(options, "longtime.implicit_chain_trend", trend);
  writeTable(options, "longtime_implicit_loss",
             "Implicit Euler on the pendulum (period P = " + fixed(period, 2) + " s) over " + general(T / period) +
                 " periods: swing energy E − E_bottom left, and lost per period; the 6-chain's energy lost over " +
                 general(plan.chainDuration) + " s as a fraction of its potential drop g·m·L·cl(cl−1)/2",
             {"dt (s)", "pendulum swing energy left", "pendulum lost per period", "6-chain lost"}, lossRows);
}

// longtime_drift.csv and its table: per scene, integrator and dt, the drift
// rate (slope of (E − E(0))/E_s against t, per 100 s), the largest |E − E(0)|/E_s,
// and the order in dt of the drift rate between successive halvings.
void writeDrift(const LabOptions& options, const LongtimePlan& plan, const std::vector<DriftScene>& scenes,
                const std::vector<DriftCell>& cells, const Results<EnergyRun>& results) {
  Csv csv(options, "longtime_drift.csv",
          {"problem", "integrator", "dt", "duration", "failed", "time", "drift_per_100s", "max_abs_change"});
  std::vector<std::vector<std::string>> rows;
  std::map<std::pair<std::size_t, std::string>, std::vector<std::pair<double, double>>> rates;  // (dt, rate)
  for (const auto& [k, run] : results) {
    const DriftCell& cell = cells[k];
    const auto [slope, largest] = driftOf(run);
    const bool diverged = run.failed || !(largest <= 1e3);
    csv << scenes[cell.scene].run.label << cell.integrator << cell.dt << plan.horizon << static_cast<long>(diverged)
        << run.time << 100.0 * slope << largest;
    csv.endRow();
    if (!diverged) rates[{cell.scene, cell.integrator}].push_back({cell.dt, 100.0 * slope});
    std::string order = "–";
    const auto& earlier = rates[{cell.scene, cell.integrator}];
    if (!diverged && earlier.size() >= 2) {
      const auto& [dtBefore, rateBefore] = earlier[earlier.size() - 2];
      order = fixed(std::log(std::abs(rateBefore / (100.0 * slope))) / std::log(dtBefore / cell.dt), 2);
    }
    rows.push_back({scenes[cell.scene].run.label, cell.integrator, general(cell.dt),
                    diverged ? energyText(run) : general(100.0 * slope, 2), diverged ? "–" : general(largest, 2),
                    order});
    if (!diverged)
      recordValue(options, "longtime.drift." + scenes[cell.scene].run.label + "." + cell.integrator + ".dt" +
                               general(cell.dt),
                  general(100.0 * slope, 2));
  }
  writeTable(options, "longtime_drift",
             "Energy drift of the constrained scenes over T = " + general(plan.horizon) +
                 " s: the least-squares slope of (E − E(0))/E_s against t, per 100 s, the largest |E − E(0)|/E_s, "
                 "and the order of the drift rate in dt from the halving above (|rate(2h)/rate(h)| = 2^order)",
             {"problem", "integrator", "dt", "drift per 100 s", "max |ΔE|/E_s", "order of the drift in dt"}, rows);
}

}  // namespace

int runLongtime(const LabOptions& options) {
  prepareOutput(options, "longtime.");
  const LongtimePlan plan = options.quick ? quickPlan() : fullPlan();
  const auto integrators = selectedIntegrators(options, true);
  const double period = scenes::pendulumPeriod(scenes::PendulumParams::seed());
  Progress progress(options, "longtime", static_cast<long>(kLongRuns.size() * integrators.size() + plan.implicitSteps.size()));
  recordValue(options, "longtime.horizon", general(plan.horizon));
  recordValue(options, "longtime.pendulum_period", fixed(period, 2));
  recordValue(options, "longtime.adaptive_tolerance", general(particles::IntegratorSettings{}.dopri5.tolerance));

  const auto energy = resultsInTurn<EnergyRun>(
      options, kLongRuns.size() * integrators.size(),
      [&](std::size_t k) {
        auto run = runEnergy(plan, kLongRuns[k / integrators.size()], integrators[k % integrators.size()]);
        progress.tick();
        return run;
      },
      true);
  writeEnergy(options, plan, integrators, energy);

  const std::vector<DriftScene> drift = driftScenes(options.quick);
  const std::vector<DriftCell> driftRuns = driftCells(drift);
  const auto drifts = sweepResults<EnergyRun>(options, driftRuns.size(), [&](std::size_t k) {
    LongRun run = drift[driftRuns[k].scene].run;
    run.dt = driftRuns[k].dt;
    return runEnergy(plan, run, driftRuns[k].integrator);
  });
  writeDrift(options, plan, drift, driftRuns, drifts);

  const double eBottom = buildLabScene("pendulum", {{"angle", "0"}}).system->totalEnergy();
  const auto damping = resultsInTurn<Damping>(
      options, plan.implicitSteps.size(),
      [&](std::size_t k) {
        auto damping = measureDamping(plan, plan.implicitSteps[k], period, eBottom);
        if (damping) progress.tick();
        return damping;
      },
      true);
  writeDamping(options, plan, period, damping);
  return interrupted() ? 130 : 0;
}

}  // namespace lab
