// `particle-lab longtime`: long-time behaviour. The total energy against time
// over at least 500 s for every integrator on the pendulum and the 6-chain at
// one common dt per scene, and implicit Euler's energy loss per period against
// dt on the pendulum.
#include <cmath>
#include <limits>

#include "lab/cells.h"
#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/lab_scene.h"
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

}  // namespace

int runLongtime(const LabOptions& options) {
  prepareOutput(options);
  const bool q = options.quick;
  const auto integrators = selectedIntegrators(options, true);
  const double horizon = q ? 20.0 : 500.0, every = q ? 0.5 : 1.0;  // energy sampled every `every` s
  const std::vector<LongRun> runs = {{"pendulum", "pendulum", {}, 0.05}, {"6-chain", "test-chain", {{"cl", "6"}}, 0.01}};
  const scenes::PendulumParams pendulum = scenes::PendulumParams::seed();
  const double period = scenes::pendulumPeriod(pendulum);
  const std::vector<double> implicitSteps = q ? std::vector<double>{0.05, 0.2} : logSpace(0.005, 0.5, 7);
  Progress progress(options, "longtime", static_cast<long>(runs.size() * integrators.size() + implicitSteps.size()));
  recordValue(options, "longtime.horizon", general(horizon));
  recordValue(options, "longtime.pendulum_period", fixed(period, 2));
  recordValue(options, "longtime.adaptive_tolerance", general(particles::IntegratorSettings{}.tolerance));

  // Only non-finite states end a run: the drift itself is what is shown.
  FailureCriterion drift;
  drift.maxRelativeConstraintError = drift.energyRiseFraction = std::numeric_limits<double>::infinity();
  Csv energy(options, "longtime_energy.csv", {"problem", "integrator", "dt", "time", "energy_change"});
  std::vector<std::vector<std::string>> table;
  for (const auto& run : runs) {
    std::vector<std::string> row{run.label + " (dt = " + general(run.dt) + " s)"};
    for (const auto& name : integrators) {
      if (interrupted()) break;
      const auto result = cell<EnergyRun>(options, [&]() -> std::optional<EnergyRun> {
        scenes::Scene scene = buildLabScene(run.scene, run.params);
        const double scale = releasableEnergy(*scene.system), e0 = scene.system->totalEnergy();
        auto stepper = particles::makeIntegrator(name);
        const long stride = std::max(1L, std::lround(every / run.dt));
        long k = 0;
        EnergyRun out;
        const RunResult r = simulate(scene, *stepper, run.dt, horizon, drift, [&](const particles::ParticleSystem& s) {
          out.last = (s.totalEnergy() - e0) / scale;
          if (++k % stride == 0) out.samples.push_back({s.time(), out.last});
          return true;
        });
        progress.tick();
        if (r.cutShort) return std::nullopt;
        out.failed = r.failed, out.time = r.time;
        return out;
      });
      if (!result) continue;  // another shard's cell, or cut short (the check above ends the loop)
      energy << run.label << name << run.dt << 0.0 << 0.0;
      energy.endRow();
      for (const auto& [t, change] : result->samples) {
        energy << run.label << name << run.dt << t << change;
        energy.endRow();
      }
      const double last = result->last;
      row.push_back(result->failed ? "non-finite at t = " + general(result->time, 3)
                                   : std::abs(last) > 1e3 ? "diverged (" + general(last, 2) + ")" : general(last, 2));
      recordValue(options, "longtime.energy_change." + run.label + "." + name, general(last, 2));
    }
    table.push_back(row);
  }
  std::vector<std::string> header{"problem"};
  for (const auto& name : integrators) header.push_back(name);
  writeTable(options, "longtime_energy",
             "Energy change (E(T) − E(0)) / E_s after T = " + general(horizon) +
                 " s at one dt per scene (E_s: the energy the scene can release, lab/failure.h)",
             header, table);

  // Implicit Euler damps: the swing energy E − E_bottom left after whole
  // periods P gives the fraction lost per period, 1 − (E_s(T)/E_s(0))^(P/T).
  const double T = q ? 2 * period : 5 * period;
  std::map<std::string, std::string> bottom{{"angle", "0"}};
  const double eBottom = buildLabScene("pendulum", bottom).system->totalEnergy();
  // The 6-chain beside it: energy lost over 60 s as a fraction of the potential
  // drop from the start to hanging straight, g·m·L·cl(cl−1)/2.
  const double chainT = q ? 5.0 : 60.0;
  const auto chainLoss = [&](double dt) {
    scenes::Scene chain = buildChain(ChainSpec(6));
    const double drop = releasableEnergy(*chain.system);  // g·m·L·cl(cl−1)/2 for the test chain
    const double e0 = chain.system->totalEnergy();
    auto stepper = particles::makeIntegrator("implicit-euler");
    simulate(chain, *stepper, chainT / std::round(chainT / dt), chainT, drift);
    return (e0 - chain.system->totalEnergy()) / drop;
  };
  Csv loss(options, "longtime_implicit_loss.csv",
           {"dt", "periods", "swing_energy_left", "loss_per_period", "chain6_loss"});
  std::vector<std::vector<std::string>> lossRows;
  for (double wanted : implicitSteps) {
    if (interrupted()) break;
    const auto result = cell<Damping>(options, [&]() -> std::optional<Damping> {
      Damping d;
      d.dt = T / std::round(T / wanted);
      scenes::Scene scene = buildLabScene("pendulum");
      const double swing0 = scene.system->totalEnergy() - eBottom;
      auto stepper = particles::makeIntegrator("implicit-euler");
      simulate(scene, *stepper, d.dt, T, drift);
      if (interrupted()) return std::nullopt;
      d.left = (scene.system->totalEnergy() - eBottom) / swing0;
      d.perPeriod = 1.0 - std::pow(std::max(d.left, 0.0), period / T);
      d.chain = chainLoss(d.dt);
      progress.tick();
      return d;
    });
    if (!result) continue;  // another shard's cell, or cut short (the check above ends the loop)
    const Damping& d = *result;
    loss << d.dt << T / period << d.left << d.perPeriod << d.chain;
    loss.endRow();
    lossRows.push_back({general(d.dt), general(100 * d.left, 3) + "%", general(100 * d.perPeriod, 2) + "%",
                        general(100 * d.chain, 2) + "%"});
  }
  writeTable(options, "longtime_implicit_loss",
             "Implicit Euler on the pendulum (period P = " + fixed(period, 2) + " s) over " + general(T / period) +
                 " periods: swing energy E − E_bottom left, and lost per period; the 6-chain's energy lost over " +
                 general(chainT) + " s as a fraction of its potential drop g·m·L·cl(cl−1)/2",
             {"dt (s)", "pendulum swing energy left", "pendulum lost per period", "6-chain lost"}, lossRows);
  return interrupted() ? 130 : 0;
}

}  // namespace lab
