// `particle-lab longtime`: long-time behaviour. The total energy against time
// over at least 500 s for every integrator on the pendulum and the 6-chain at
// one common dt per scene, and implicit Euler's energy loss per period against
// dt on the pendulum.
#include <cmath>
#include <limits>

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

}  // namespace

int runLongtime(const LabOptions& options) {
  prepareOutput(options);
  const bool q = options.quick;
  const auto integrators = selectedIntegrators(options);
  const double horizon = q ? 20.0 : 500.0, every = q ? 0.5 : 1.0;  // energy sampled every `every` s
  const std::vector<LongRun> runs = {{"pendulum", "pendulum", {}, 0.05}, {"6-chain", "test-chain", {{"cl", "6"}}, 0.01}};
  const scenes::PendulumParams pendulum = scenes::PendulumParams::seed();
  const double period = scenes::pendulumPeriod(pendulum);
  const std::vector<double> implicitSteps = q ? std::vector<double>{0.05, 0.2} : logSpace(0.005, 0.5, 7);
  Progress progress("longtime", static_cast<long>(runs.size() * integrators.size() + implicitSteps.size()));
  recordValue(options, "longtime.horizon", general(horizon));
  recordValue(options, "longtime.pendulum_period", fixed(period, 2));

  // Only non-finite states end a run: the drift itself is what is shown.
  FailureCriterion drift;
  drift.maxRelativeConstraintError = drift.energyRiseFraction = std::numeric_limits<double>::infinity();
  Csv energy(options, "longtime_energy.csv", {"problem", "integrator", "dt", "time", "energy_change"});
  std::vector<std::vector<std::string>> table;
  for (const auto& run : runs) {
    std::vector<std::string> row{run.label + " (dt = " + general(run.dt) + " s)"};
    for (const auto& name : integrators) {
      if (interrupted()) break;
      scenes::Scene scene = buildLabScene(run.scene, run.params);
      const double scale = releasableEnergy(*scene.system), e0 = scene.system->totalEnergy();
      auto stepper = particles::makeIntegrator(name);
      const long stride = std::max(1L, std::lround(every / run.dt));
      long k = 0;
      double last = 0.0;
      energy << run.label << name << run.dt << 0.0 << 0.0;
      energy.endRow();
      const RunResult r = simulate(scene, *stepper, run.dt, horizon, drift, [&](const particles::ParticleSystem& s) {
        last = (s.totalEnergy() - e0) / scale;
        if (++k % stride == 0) {
          energy << run.label << name << run.dt << s.time() << last;
          energy.endRow();
        }
        return true;
      });
      row.push_back(r.failed ? "non-finite at t = " + general(r.time, 3)
                               : std::abs(last) > 1e3 ? "diverged (" + general(last, 2) + ")" : general(last, 2));
      recordValue(options, "longtime.energy_change." + run.label + "." + name, general(last, 2));
      progress.tick();
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
    const double dt = T / std::round(T / wanted);
    scenes::Scene scene = buildLabScene("pendulum");
    const double swing0 = scene.system->totalEnergy() - eBottom;
    auto stepper = particles::makeIntegrator("implicit-euler");
    simulate(scene, *stepper, dt, T, drift);
    if (interrupted()) break;
    const double left = (scene.system->totalEnergy() - eBottom) / swing0;
    const double perPeriod = 1.0 - std::pow(std::max(left, 0.0), period / T);
    const double chain = chainLoss(dt);
    loss << dt << T / period << left << perPeriod << chain;
    loss.endRow();
    lossRows.push_back({general(dt), general(100 * left, 3) + "%", general(100 * perPeriod, 2) + "%",
                        general(100 * chain, 2) + "%"});
    progress.tick();
  }
  writeTable(options, "longtime_implicit_loss",
             "Implicit Euler on the pendulum (period P = " + fixed(period, 2) + " s) over " + general(T / period) +
                 " periods: swing energy E − E_bottom left, and lost per period; the 6-chain's energy lost over " +
                 general(chainT) + " s as a fraction of its potential drop g·m·L·cl(cl−1)/2",
             {"dt (s)", "pendulum swing energy left", "pendulum lost per period", "6-chain lost"}, lossRows);
  return interrupted() ? 130 : 0;
}

}  // namespace lab
