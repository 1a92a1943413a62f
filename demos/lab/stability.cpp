// `particle-lab stability`: for each integrator, the largest time step at which
// the test chain survives T simulated seconds, as a function of chain length,
// found by bisection; the seed report's Tables 1 and 2 are read off it.
#include <cmath>
#include <iostream>
#include <map>
#include <tuple>

#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/lab.h"

namespace lab {

namespace {

// Survival of one (integrator, cl, dt, T) probe, cached so that the bisections
// for the map and the tables never repeat a run.
class Prober {
 public:
  Prober(const Explosion& explosion, Progress& progress) : explosion_(explosion), progress_(progress) {}

  bool survives(const std::string& integrator, int cl, double dt, double duration) {
    const auto key = std::make_tuple(integrator, cl, dt, duration);
    const auto found = cache_.find(key);
    if (found != cache_.end()) return found->second;
    scenes::Scene chain = buildChain({cl});
    auto stepper = particles::makeIntegrator(integrator);
    const RunResult r = simulate(chain, *stepper, dt, duration, explosion_);
    progress_.tick();
    return cache_[key] = !r.exploded;
  }

  // Largest dt in [lo, hi] (log bisection, `rounds` halvings) that survives;
  // 0 when even lo explodes. Assumes survival is monotone in dt. Surviving
  // probes are the costly ones (they run all of T), so lo itself is probed
  // only when every bisection probe exploded.
  double maxStep(const std::string& integrator, int cl, double duration, double lo, double hi,
                 int rounds) {
    return bisectStep([&](double dt) { return survives(integrator, cl, dt, duration); }, lo, hi, rounds);
  }

  // Longest chain in [2, maxLength] that survives at dt; 0 when none does.
  int maxLength(const std::string& integrator, double dt, double duration, int maxLength) {
    if (survives(integrator, maxLength, dt, duration)) return maxLength;
    if (!survives(integrator, 2, dt, duration)) return 0;
    int lo = 2, hi = maxLength;
    while (hi - lo > 1 && !interrupted()) {
      const int mid = (lo + hi) / 2;
      (survives(integrator, mid, dt, duration) ? lo : hi) = mid;
    }
    return lo;
  }

 private:
  Explosion explosion_;
  Progress& progress_;
  std::map<std::tuple<std::string, int, double, double>, bool> cache_;
};

}  // namespace

int runStability(const LabOptions& options, const StabilityOptions& so) {
  prepareOutput(options);
  const auto integrators = selectedIntegrators(options);
  const std::vector<int> lengths = options.quick ? std::vector<int>{2, 6, 12}
                                                 : std::vector<int>{2, 3, 6, 12, 24, 48, 80, 160, 320, 500};
  const int rounds = options.quick ? 4 : 8;
  const int maxChain = options.quick ? 24 : 500;
  const std::vector<double> durations =
      options.quick ? std::vector<double>{0.5 * so.duration, so.duration}
                    : std::vector<double>{0.25 * so.duration, 0.5 * so.duration, so.duration, 2 * so.duration};
  const int sweepLength = options.quick ? 6 : 24;
  const double dtLo = 0.001, dtHi = 0.5;
  const double tableSteps[3] = {0.2, 0.1, 0.05};
  const int tableLengths[3] = {6, 12, 24};

  const long probesPerBisection = rounds + 2;
  Progress progress("stability", static_cast<long>(integrators.size()) *
                                     (lengths.size() * probesPerBisection + 3 * 10 +
                                      durations.size() * probesPerBisection));
  Prober prober(so.explosion, progress);

  scenes::Scene reference = buildChain({2});
  const double rod = chainRodLength(reference);
  const double g = gravityMagnitude(*reference.system);
  const double toDimensionless = std::sqrt(g / rod);

  Csv boundary(options.outDir + "/stability_boundary.csv",
               {"integrator", "chain_length", "duration", "max_dt", "max_dt_dimensionless"});
  Csv map(options.outDir + "/stability_map.csv",
          {"integrator", "chain_length", "dt", "dt_dimensionless", "survived"});
  std::map<std::string, std::map<int, double>> maxDt;
  const std::vector<double> gridSteps = logSpace(dtLo, dtHi, options.quick ? 5 : 12);
  for (const auto& name : integrators) {
    for (int cl : lengths) {
      if (interrupted()) break;
      const double best = prober.maxStep(name, cl, so.duration, dtLo, dtHi, rounds);
      if (interrupted()) break;  // a bisection cut short is not a measurement
      maxDt[name][cl] = best;
      boundary << name << cl << so.duration << best << best * toDimensionless;
      boundary.endRow();
      // The map follows from the boundary (survival is monotone in dt).
      for (double dt : gridSteps) {
        map << name << cl << dt << dt * toDimensionless << (dt <= best ? 1L : 0L);
        map.endRow();
      }
    }
  }

  // How the boundary moves with the survival time T.
  Csv sweep(options.outDir + "/stability_vs_duration.csv",
            {"integrator", "chain_length", "duration", "max_dt", "max_dt_dimensionless"});
  for (const auto& name : integrators)
    for (double duration : durations) {
      if (interrupted()) break;
      const double best = prober.maxStep(name, sweepLength, duration, dtLo, dtHi, rounds);
      if (interrupted()) break;
      sweep << name << sweepLength << duration << best << best * toDimensionless;
      sweep.endRow();
    }

  // The seed report's Tables 1 and 2, on our chain (their numbers cited beside ours).
  const std::map<std::string, std::vector<std::string>> seedTable1 = {
      {"symplectic-euler", {"0", "2", "2"}}, {"midpoint", {"1", "12", "52"}}, {"rk4", {"15", "40", "72"}}};
  const std::map<std::string, std::vector<std::string>> seedTable2 = {
      {"symplectic-euler", {"0.01", "0.01", "0.008"}},
      {"midpoint", {"0.1", "0.1", "0.085"}},
      {"rk4", {"0.25", "0.22", "0.115"}}};
  Csv table1Csv(options.outDir + "/table1_max_chain_length.csv", {"integrator", "dt", "max_chain_length"});
  std::vector<std::vector<std::string>> table1, table2;
  for (const auto& name : integrators) {
    std::vector<std::string> row{name};
    for (double dt : tableSteps) {
      if (interrupted()) break;
      const int longest = prober.maxLength(name, dt, so.duration, maxChain);
      if (interrupted()) break;
      table1Csv << name << dt << static_cast<long>(longest);
      table1Csv.endRow();
      row.push_back(longest >= maxChain ? "≥ " + std::to_string(maxChain) : std::to_string(longest));
    }
    const auto seed = seedTable1.find(name);
    for (int k = 0; k < 3; ++k) row.push_back(seed != seedTable1.end() ? seed->second[k] : "–");
    table1.push_back(row);

    std::vector<std::string> row2{name};
    for (int cl : tableLengths) {
      const auto it = maxDt[name].find(cl);
      const double best = it != maxDt[name].end() ? it->second
                                                   : prober.maxStep(name, cl, so.duration, dtLo, dtHi, rounds);
      row2.push_back(best <= 0.0 ? "< 0.001" : best >= dtHi ? "≥ 0.5" : general(best, 2));
      recordValue(options, "stability.max_dt." + name + ".cl" + std::to_string(cl), row2.back());
    }
    const auto seed2 = seedTable2.find(name);
    for (int k = 0; k < 3; ++k) row2.push_back(seed2 != seedTable2.end() ? seed2->second[k] : "–");
    table2.push_back(row2);
  }
  if (interrupted()) return 130;  // the tables would mix measured and cut-short entries
  writeTable(options, "table1", "Table 1: longest chain that survives T = " + general(so.duration) + " s",
             {"integrator", "dt 0.2", "dt 0.1", "dt 0.05", "seed dt 0.2", "seed dt 0.1", "seed dt 0.05"},
             table1);
  writeTable(options, "table2", "Table 2: largest dt at which the chain survives T = " + general(so.duration) + " s",
             {"integrator", "cl 6", "cl 12", "cl 24", "seed cl 6", "seed cl 12", "seed cl 24"}, table2);
  recordValue(options, "stability.duration", general(so.duration));
  recordValue(options, "stability.rod_length", general(rod));
  recordValue(options, "stability.gravity", general(g));
  recordValue(options, "stability.max_stretch", general(so.explosion.maxRelativeStretch));
  recordValue(options, "stability.energy_gain", general(so.explosion.energyGain));
  return interrupted() ? 130 : 0;
}

}  // namespace lab
