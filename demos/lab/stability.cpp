// `particle-lab stability`: for each integrator and chain length, the safe
// time step of the test chain — the largest dt on a 5% log grid at and below
// which every grid dt survives T on every member of a small ensemble of
// perturbed starts — found by scanning (scan.h), with the first failure, what
// fired there, and any survival above it. The same runs give the stability
// map (measured at every scanned dt), the boundary against T, and the
// boundary against the stiffest frequency present; Table 1 (longest chain at
// dt 0.2, 0.1, 0.05) is measured at those steps over a ladder of lengths.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <set>
#include <tuple>

#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/lab.h"
#include "lab/cells.h"
#include "format_number.h"

namespace lab {

namespace {

// One scan: an integrator on a chain with the solver's feedback stiffness k_s
// (0: the scene's default), evaluated at each of `durations`.
struct Cell {
  std::string integrator;
  int length;
  double stiffness;
  std::vector<double> durations;
};

scenes::Scene buildCell(int length, double stiffness) {
  scenes::Scene chain = buildChain({length});
  if (stiffness > 0.0) chain.system->solver().settings.stiffness = stiffness;
  return chain;
}

std::string listText(const std::vector<double>& values) {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : ";") + general(v, 3);
  return text;
}

// The fastest rotation rate any rod reaches over [0, T], max |d × ḋ| / |d|²
// (1/s, d = x_i − x_j): the frequency the whip of the chain's tip actually
// brings, measured on an RK4 run at dt 0.005 (inside its safe range for
// every chain scanned here).
double fastestLinkRate(int length, double duration, const FailureCriterion& criterion) {
  scenes::Scene chain = buildChain({length});
  std::vector<std::pair<int, int>> rods;
  for (const auto& c : chain.system->constraints())
    if (c->particles().size() == 2) rods.push_back({c->particles()[0], c->particles()[1]});
  double fastest = 0.0;
  auto rk4 = particles::makeIntegrator("rk4");
  simulate(chain, *rk4, 0.005, duration, criterion, [&](const particles::ParticleSystem& s) {
    for (const auto& [i, j] : rods) {
      const Eigen::Vector2d d = s.position(i) - s.position(j);
      const Eigen::Vector2d v = s.velocities().segment<2>(2 * i) - s.velocities().segment<2>(2 * j);
      fastest = std::max(fastest, std::abs(d.x() * v.y() - d.y() * v.x()) / d.squaredNorm());
    }
    return true;
  });
  return fastest;
}

}  // namespace

int runStability(const LabOptions& options, const StabilityOptions& so) {
  prepareOutput(options);
  const FailureCriterion& criterion = options.criterion;
  std::cout << describe(criterion) << "\n";

  // An adaptive scheme chooses its own internal step: scanning its call
  // interval would measure nothing, so it is left out here.
  std::vector<std::string> integrators;
  for (const auto& name : selectedIntegrators(options))
    if (!particles::requireIntegrator(name).usesTolerance) integrators.push_back(name);
    else std::cout << name << ": not scanned (its internal step is chosen by --tolerance, dt is only its call interval)\n";

  const bool q = options.quick;
  const double T = q ? std::min(so.duration, 10.0) : so.duration;
  const std::vector<double> durations = {0.5 * T, T, 2.0 * T, 4.0 * T};  // the boundary against T
  const std::vector<int> lengths = q ? std::vector<int>{2, 6} : std::vector<int>{2, 3, 6, 12, 24, 48, 80};
  const std::set<int> sweepLengths = q ? std::set<int>{6} : std::set<int>{6, 12, 24};
  const std::vector<int> feedbackLengths = q ? std::vector<int>{2} : std::vector<int>{2, 3, 6};
  const double defaultStiffness = buildChain({2}).system->solver().settings.stiffness;
  const double stiffFeedback = 4.0 * defaultStiffness;  // ω_feedback doubles
  ScanSettings scan;
  scan.grid = stepGrid(q ? 0.025 : 0.05 / 16, q ? 0.4 : 0.5);
  scan.members = q ? 2 : 3;
  scan.beyond = 2.0;
  const double perturbation = 1e-6;

  std::vector<Cell> cells;
  for (const auto& name : integrators) {
    for (int cl : lengths)
      cells.push_back({name, cl, defaultStiffness, sweepLengths.count(cl) ? durations : std::vector<double>{T}});
    for (int cl : feedbackLengths) cells.push_back({name, cl, stiffFeedback, {T}});
  }

  scenes::Scene reference = buildChain({2});
  const double rod = chainRodLength(reference);
  const double g = gravityMagnitude(*reference.system);

  std::cout << "grid: " << scan.grid.size() << " dt from " << general(scan.grid.front(), 3) << " to "
            << general(scan.grid.back(), 3) << " s, neighbours " << general(scan.grid[1] / scan.grid[0] - 1, 2)
            << " apart; scanned up to " << scan.beyond << "x the first failure; " << scenes::plural(scan.members, "start")
            << " (perturbed by " << perturbation << " of the scene size); T = " << general(T) << " s\n";

  // The whip's frequency per chain length, over the longest T each is scanned for.
  std::vector<int> whipLengths(lengths);
  std::map<int, double> whipRate;
  sweep<double>(
      options, whipLengths.size(),
      [&](std::size_t k) -> std::optional<double> {
        const int cl = whipLengths[k];
        const double rate = fastestLinkRate(cl, sweepLengths.count(cl) ? durations.back() : T, criterion);
        if (interrupted()) return std::nullopt;
        return rate;
      },
      [&](std::size_t k, double& rate) { whipRate[whipLengths[k]] = rate; });
  if (interrupted()) return 130;

  Csv boundaryCsv(options, "stability_boundary.csv",
                  {"integrator", "chain_length", "feedback_ks", "duration", "safe_dt", "first_failure_dt",
                   "first_failure", "survival_above", "grid_lo", "grid_hi", "members", "omega_feedback",
                   "omega_chain", "omega_whip", "stiffest"});
  Csv mapCsv(options, "stability_map.csv",
             {"integrator", "chain_length", "feedback_ks", "duration", "dt", "members_run", "survivors", "survived",
              "failure", "max_relative_stretch", "max_energy_rise"});
  Progress progress(options, "stability", static_cast<long>(cells.size()));

  // safe[T][integrator][cl] at the default k_s; safe boundaries at 4 k_s.
  std::map<double, std::map<std::string, std::map<int, Boundary>>> safe;
  std::map<std::string, std::map<int, Boundary>> stiffSafe;
  sweep<std::vector<ScanRun>>(
      options, cells.size(),
      [&](std::size_t k) {
        const Cell& c = cells[k];
        ScanSettings s = scan;
        s.durations = c.durations;
        auto runs = scanSteps(
            [&](double dt, int member, double duration) {
              return runMember([&] { return buildCell(c.length, c.stiffness); }, c.integrator, dt, member,
                               duration, criterion);
            },
            s);
        progress.tick();
        return runs;
      },
      [&](std::size_t k, std::vector<ScanRun>& runs) {
        const Cell& c = cells[k];
        // Frequencies present: the feedback C̈ = −k_s C − k_d Ċ rings at √k_s;
        // the chain's fastest transverse mode under its top tension
        // (cl − 1) m g is ω ≈ 2 √((cl − 1) g / r) (a beaded string, tension T,
        // bead mass m, spacing r: ω_max = 2 √(T / (m r))).
        // The whip's rate is measured (fastestLinkRate). Which one governs is
        // read off the products dt·ω (constant along a regime), not assumed.
        const double omegaFeedback = std::sqrt(c.stiffness);
        const double omegaChain = 2.0 * std::sqrt((c.length - 1) * g / rod);
        const double omegaWhip = whipRate[c.length];
        const double stiffest = std::max({omegaFeedback, omegaChain, omegaWhip});
        const std::string stiffestName = stiffest == omegaFeedback ? "feedback" : stiffest == omegaWhip ? "whip" : "chain";
        for (double duration : c.durations) {
          const auto survival = survivalAt(runs, duration, scan.members);
          const Boundary b = boundaryOf(survival);
          boundaryCsv << c.integrator << c.length << c.stiffness << duration << b.safeDt << b.firstFailureDt
                      << failureName(b.firstFailure) << listText(b.survivalAbove) << b.lowest << b.highest
                      << static_cast<long>(scan.members) << omegaFeedback << omegaChain << omegaWhip << stiffestName;
          boundaryCsv.endRow();
          for (const GridSurvival& gs : survival) {
            mapCsv << c.integrator << c.length << c.stiffness << duration << gs.dt << static_cast<long>(gs.membersRun)
                   << static_cast<long>(gs.survivors) << static_cast<long>(gs.survived)
                   << failureName(gs.survived ? Failure::None : gs.failure) << gs.maxRelativeStretch
                   << gs.maxEnergyRise;
            mapCsv.endRow();
          }
          if (c.stiffness == defaultStiffness) safe[duration][c.integrator][c.length] = b;
          else stiffSafe[c.integrator][c.length] = b;
        }
      },
      [&](std::size_t k) {  // the scan's steps are dominated by its smallest dt
        const Cell& c = cells[k];
        return estimatedRunSeconds(buildCell(c.length, c.stiffness), c.integrator, scan.grid.front(),
                                   c.durations.back());
      });
  if (interrupted()) return 130;  // the rows written are complete scans; no table from a partial set

  // Table 1: the longest chain that survives T at dt 0.2, 0.1, 0.05 — every
  // length of the ladder up to it survives on every member.
  const double tableSteps[3] = {0.2, 0.1, 0.05};
  const std::vector<int> ladder = q ? std::vector<int>{2, 3, 6, 12}
                                    : std::vector<int>{2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 80, 120, 160, 240};
  struct LadderCell {
    std::string integrator;
    double dt;
    int length;
  };
  std::vector<LadderCell> ladderCells;
  for (const auto& name : integrators)
    for (double dt : tableSteps)
      for (int cl : ladder) ladderCells.push_back({name, dt, cl});
  Csv ladderCsv(options, "table1_runs.csv",
                {"integrator", "dt", "chain_length", "survived", "failure", "failure_time"});
  std::map<std::string, std::map<double, std::map<int, bool>>> ladderSurvived;
  sweep<Probe>(
      options, ladderCells.size(),
      [&](std::size_t k) -> std::optional<Probe> {
        const LadderCell& c = ladderCells[k];
        Probe worst;
        for (int member = 0; member < scan.members; ++member) {
          const auto p = runMember([&] { return buildChain({c.length}); }, c.integrator, c.dt, member, T, criterion);
          if (!p) return std::nullopt;
          if (!p->survives(T, c.dt)) return p;
          worst = *p;
        }
        return worst;
      },
      [&](std::size_t k, Probe& p) {
        const LadderCell& c = ladderCells[k];
        const bool ok = p.survives(T, c.dt);
        ladderCsv << c.integrator << c.dt << static_cast<long>(c.length) << static_cast<long>(ok)
                  << failureName(ok ? Failure::None : p.failure) << (ok ? T : p.time);
        ladderCsv.endRow();
        ladderSurvived[c.integrator][c.dt][c.length] = ok;
      });
  if (interrupted()) return 130;

  // Everything measured: the tables and quoted values.
  const std::map<std::string, std::vector<std::string>> seedTable1 = {
      {"symplectic-euler", {"0", "2", "2"}}, {"midpoint", {"1", "12", "52"}}, {"rk4", {"15", "40", "72"}}};
  const std::map<std::string, std::vector<std::string>> seedTable2 = {
      {"symplectic-euler", {"0.01", "0.01", "0.008"}},
      {"midpoint", {"0.1", "0.1", "0.085"}},
      {"rk4", {"0.25", "0.22", "0.115"}}};
  const std::vector<int> tableLengths = q ? std::vector<int>{2, 6} : std::vector<int>{6, 12, 24};
  Csv table1Csv(options, "table1_max_chain_length.csv",
                {"integrator", "dt", "max_chain_length", "first_failing_length", "survival_above"});
  std::vector<std::vector<std::string>> table1, table2, details, vsDuration, feedback, frequency;
  for (const auto& name : integrators) {
    std::vector<std::string> row{name};
    for (double dt : tableSteps) {
      int longest = 0, firstFail = 0;
      std::vector<double> above;
      for (int cl : ladder) {
        const bool ok = ladderSurvived[name][dt][cl];
        if (firstFail == 0 && ok) longest = cl;
        else if (firstFail == 0) firstFail = cl;
        else if (ok) above.push_back(cl);
      }
      table1Csv << name << dt << static_cast<long>(longest) << static_cast<long>(firstFail) << listText(above);
      table1Csv.endRow();
      std::string cell = firstFail == 0 ? "≥ " + std::to_string(ladder.back())
                         : longest == 0 ? "< " + std::to_string(ladder.front())
                                        : std::to_string(longest);
      if (!above.empty()) cell += " (" + listText(above) + " survive)";
      row.push_back(cell);
    }
    const auto seed = seedTable1.find(name);
    for (int k = 0; k < 3; ++k) row.push_back(seed != seedTable1.end() ? seed->second[k] : "–");
    table1.push_back(row);

    std::vector<std::string> row2{name};
    for (int cl : tableLengths) {
      const Boundary& b = safe[T][name][cl];
      row2.push_back(safeStepText(b));
      recordValue(options, "stability.safe_dt." + name + ".cl" + std::to_string(cl), row2.back());
    }
    const auto seed2 = seedTable2.find(name);
    for (int k = 0; k < 3; ++k) row2.push_back(seed2 != seedTable2.end() ? seed2->second[k] : "–");
    table2.push_back(row2);

    for (int cl : lengths) {
      const Boundary& b = safe[T][name][cl];
      details.push_back({name, std::to_string(cl), safeStepText(b),
                         b.aboveGrid() ? "–" : general(b.firstFailureDt, 3) + " (" + failureName(b.firstFailure) + ")",
                         b.survivalAbove.empty() ? "–" : listText(b.survivalAbove)});
    }
    for (int cl : sweepLengths) {
      std::vector<std::string> r{name, std::to_string(cl)};
      for (double d : durations) r.push_back(safeStepText(safe[d][name][cl]));
      vsDuration.push_back(r);
    }
    for (int cl : lengths) {
      const Boundary& b = safe[T][name][cl];
      if (b.belowGrid() || b.aboveGrid()) continue;
      frequency.push_back({name, std::to_string(cl), general(b.safeDt, 2),
                           general(b.safeDt * std::sqrt(defaultStiffness), 2), general(b.safeDt * whipRate[cl], 2),
                           general(b.safeDt * 2.0 * std::sqrt((cl - 1) * g / rod), 2)});
    }
    for (int cl : feedbackLengths) {
      const Boundary& a = safe[T][name][cl];
      const Boundary& b = stiffSafe[name][cl];
      feedback.push_back({name, std::to_string(cl), safeStepText(a), safeStepText(b),
                          a.belowGrid() || a.aboveGrid() ? "–" : general(a.safeDt * std::sqrt(defaultStiffness), 3),
                          b.belowGrid() || b.aboveGrid() ? "–" : general(b.safeDt * std::sqrt(stiffFeedback), 3)});
    }
  }

  // How far the boundary moves from T to 2T: the median ratio over every
  // integrator and swept length with both boundaries on the grid.
  std::vector<double> shift;
  for (std::size_t k = 0; k + 1 < durations.size(); ++k) {
    std::vector<double> ratios;
    for (const auto& name : integrators)
      for (int cl : sweepLengths) {
        const Boundary &a = safe[durations[k]][name][cl], &b = safe[durations[k + 1]][name][cl];
        if (!a.belowGrid() && !a.aboveGrid() && !b.belowGrid() && !b.aboveGrid()) ratios.push_back(b.safeDt / a.safeDt);
      }
    shift.push_back(ratios.empty() ? std::nan("") : median(ratios));
    const char* step[] = {"half_to_T", "T_to_2T", "2T_to_4T"};
    recordValue(options, std::string("stability.shift.") + step[k],
                ratios.empty() ? "–" : fixed(shift.back(), 2));
  }

  const std::string at = "T = " + general(T) + " s, " + scenes::plural(scan.members, "start") + ", 5% dt grid";
  writeTable(options, "table1", "Table 1: longest chain (of " + std::to_string(ladder.size()) + " lengths " +
                                    std::to_string(ladder.front()) + "–" + std::to_string(ladder.back()) +
                                    ") such that it and every shorter one survive, " + at,
             {"integrator", "dt 0.2", "dt 0.1", "dt 0.05", "seed dt 0.2", "seed dt 0.1", "seed dt 0.05"}, table1);
  std::vector<std::string> table2Header{"integrator"};
  for (int cl : tableLengths) table2Header.push_back("cl " + std::to_string(cl));
  for (const char* seed : {"seed cl 6", "seed cl 12", "seed cl 24"}) table2Header.push_back(seed);
  writeTable(options, "table2", "Table 2: safe dt (every grid dt at or below it survives), " + at,
             table2Header, table2);
  writeTable(options, "stability_boundary", "Safe dt, first failure (what fired) and survival above it, " + at,
             {"integrator", "chain length", "safe dt", "first failure", "survives again at"}, details);
  std::vector<std::string> header{"integrator", "chain length"};
  for (double d : durations) header.push_back("T = " + general(d) + " s");
  writeTable(options, "stability_vs_duration", "Safe dt against T (" + scenes::plural(scan.members, "start") + ")",
             header, vsDuration);
  writeTable(options, "stability_feedback",
             "Short chains: safe dt at the feedback stiffness k_s = " + general(defaultStiffness) + " and " +
                 general(stiffFeedback) + " (" + at + "); dt·√k_s constant means the feedback governs",
             {"integrator", "chain length", "safe dt, k_s " + general(defaultStiffness),
              "safe dt, k_s " + general(stiffFeedback), "dt·√k_s at " + general(defaultStiffness),
              "dt·√k_s at " + general(stiffFeedback)},
             feedback);
  std::vector<std::vector<std::string>> whipRows;
  for (int cl : lengths) whipRows.push_back({std::to_string(cl), general(whipRate[cl], 3)});
  writeTable(options, "stability_whip",
             "The whip: fastest rod rotation rate max |d × ḋ|/|d|² over the run (RK4, dt 0.005), 1/s",
             {"chain length", "ω_whip"}, whipRows);
  writeTable(options, "stability_frequency",
             "Safe dt times each frequency present (" + at + "): √k_s = " + general(std::sqrt(defaultStiffness), 3) +
                 " (feedback), ω_whip measured, 2√((cl−1)g/r) (static chain mode); constant down a column: that "
                 "frequency governs",
             {"integrator", "chain length", "safe dt", "dt·√k_s", "dt·ω_whip", "dt·ω_chain"}, frequency);
  recordValue(options, "stability.duration", general(T));
  std::string durationText;
  for (double d : durations) durationText += (durationText.empty() ? "" : ", ") + general(d);
  recordValue(options, "stability.durations", durationText);
  recordValue(options, "stability.members", std::to_string(scan.members));
  recordValue(options, "stability.perturbation", general(perturbation));
  recordValue(options, "stability.grid_lo", general(scan.grid.front(), 3));
  recordValue(options, "stability.grid_hi", general(scan.grid.back(), 3));
  recordValue(options, "stability.grid_ratio", fixed(scan.grid[1] / scan.grid[0], 4));
  recordValue(options, "stability.grid_points", std::to_string(scan.grid.size()));
  recordValue(options, "stability.beyond", general(scan.beyond));
  recordValue(options, "stability.rod_length", general(rod));
  recordValue(options, "stability.gravity", general(g));
  recordValue(options, "stability.feedback_ks", general(defaultStiffness));
  recordValue(options, "criterion.max_stretch", general(criterion.maxRelativeConstraintError));
  recordValue(options, "criterion.energy_rise", general(criterion.energyRiseFraction));
  recordValue(options, "criterion.text", describe(criterion));
  return 0;
}

}  // namespace lab
