// `particle-lab stability`: for each integrator and chain length, the largest
// surviving time step of the test chain on a coarse scan — the largest dt on a
// 5% log grid at and below which every grid dt survives T on every member of a
// small ensemble of perturbed starts (scan.h), with the first failure, what
// fired there, and any survival above it. The same runs give the stability
// map (measured at every scanned dt), the boundary against T, and the
// boundary against the stiffest frequency present; Table 1 (longest chain at
// dt 0.2, 0.1, 0.05) is measured at those steps over a ladder of lengths, and
// Table 2 by a fine scan over more starts whose runs bound the per-run
// failure probability (certify.h).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <set>
#include <tuple>

#include "lab/certify.h"
#include "lab/chain.h"
#include "lab/experiments.h"
#include "lab/lab.h"
#include "lab/cells.h"
#include "lab/results.h"
#include "output/format_number.h"

namespace lab {

namespace {

// What the experiment runs.
struct StabilityPlan {
  double duration = 0.0;              // T of Tables 1 and 2, s
  std::vector<double> durations;      // the boundary against T: T/2, T, 2T, 4T
  std::vector<int> lengths;           // chain lengths scanned at the default k_s
  std::set<int> sweepLengths;         // of those, the ones scanned at every duration
  std::vector<int> feedbackLengths;   // scanned again at 4 k_s
  std::vector<int> ladder;            // Table 1: the lengths run at dt 0.2, 0.1, 0.05
  std::vector<int> tableLengths;      // Table 2's columns
  ScanSettings scan;                  // the dt grid and the ensemble
  int ladderMembers = 10;             // Table 1's ensemble
  CertifySettings certify;            // Table 2: survived steps and their failure bounds (certify.h) at T
  long certifyMaxSteps = 0;           // the certification's floor is T / this
  double perturbation = 1e-6;         // of the scene size, the perturbed starts
};

// Table 1's steps.
const std::vector<double> kTableSteps = {0.2, 0.1, 0.05};

StabilityPlan planFor(double duration, std::vector<double> grid, int members) {
  StabilityPlan plan;
  plan.duration = duration;
  plan.durations = {0.5 * duration, duration, 2.0 * duration, 4.0 * duration};
  plan.scan.grid = std::move(grid);
  plan.scan.members = members;
  plan.scan.beyond = 2.0;
  return plan;
}

void setCertification(StabilityPlan& plan, double top, long maxSteps) {
  plan.certify.top = top;
  plan.certify.floor = plan.duration / static_cast<double>(maxSteps);
  plan.certifyMaxSteps = maxSteps;
}

// Small grids and T at most 10 s: proves the code runs.
StabilityPlan quickPlan(const StabilityOptions& stability) {
  StabilityPlan plan = planFor(std::min(stability.duration, 10.0), stepGrid(0.025, 0.4), 2);
  plan.lengths = {2, 6};
  plan.sweepLengths = {6};
  plan.feedbackLengths = {2};
  plan.ladder = {2, 3, 6, 12};
  plan.tableLengths = {2};  // one certified length: the certification is most of the quick run
  setCertification(plan, 0.4, 20000);
  return plan;
}

StabilityPlan fullPlan(const StabilityOptions& stability) {
  StabilityPlan plan = planFor(stability.duration, stepGrid(0.05 / 16, 0.5), 3);
  plan.lengths = {2, 3, 6, 12, 24, 48, 80};
  plan.sweepLengths = {6, 12, 24};
  plan.feedbackLengths = {2, 3, 6};
  plan.ladder = {2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 80, 120, 160, 240};
  plan.tableLengths = {6, 12, 24};
  setCertification(plan, 0.5, 200000);
  return plan;
}

// The test chain's constants the frequencies are built from.
struct ChainConstants {
  double defaultStiffness = 0.0;  // the solver's feedback k_s
  double stiffFeedback = 0.0;     // 4 k_s: ω_feedback doubles
  double rod = 0.0;               // rod length r
  double gravity = 0.0;           // g
};

ChainConstants chainConstants() {
  ChainConstants constants;
  constants.defaultStiffness = buildChain({2}).system->solver().settings.stiffness;
  constants.stiffFeedback = 4.0 * constants.defaultStiffness;
  scenes::Scene reference = buildChain({2});
  constants.rod = chainRodLength(reference);
  constants.gravity = gravityMagnitude(*reference.system);
  return constants;
}

// One scan: an integrator on a chain with the solver's feedback stiffness k_s
// (0: the scene's default), evaluated at each of `durations`.
struct Cell {
  std::string integrator;
  int length;
  double stiffness;
  std::vector<double> durations;
};

// One run of Table 1: an integrator on a chain at one of its steps.
struct LadderCell {
  std::string integrator;
  double dt;
  int length;
};

scenes::Scene buildCell(int length, double stiffness) {
  scenes::Scene chain = buildChain({length});
  if (stiffness > 0.0) chain.system->solver().settings.stiffness = stiffness;
  return chain;
}

std::string listText(const std::vector<double>& values) {
  std::string text;
  for (double value : values) text += (text.empty() ? "" : ";") + general(value, 3);
  return text;
}

bool onGrid(const Boundary& boundary) { return !boundary.belowGrid() && !boundary.aboveGrid(); }

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

// An adaptive scheme chooses its own internal step: scanning its call
// interval would measure nothing, so it is left out here.
std::vector<std::string> scannedIntegrators(const LabOptions& options) {
  std::vector<std::string> integrators;
  for (const auto& name : selectedIntegrators(options)) {
    if (!particles::requireIntegrator(name).usesTolerance) {
      integrators.push_back(name);
      continue;
    }
    std::cout << name << ": not scanned (its internal step is chosen by --tolerance, dt is only its call interval)\n";
  }
  return integrators;
}

void printGrid(const StabilityPlan& plan) {
  const ScanSettings& scan = plan.scan;
  std::cout << "grid: " << scan.grid.size() << " dt from " << general(scan.grid.front(), 3) << " to "
            << general(scan.grid.back(), 3) << " s, neighbours " << general(scan.grid[1] / scan.grid[0] - 1, 2)
            << " apart; scanned up to " << scan.beyond << "x the first failure; "
            << output::plural(scan.members, "start") << " (perturbed by " << plan.perturbation
            << " of the scene size); T = " << general(plan.duration) << " s\n";
}

// The longest T a chain length is scanned for.
double longestDuration(const StabilityPlan& plan, int length) {
  return plan.sweepLengths.count(length) ? plan.durations.back() : plan.duration;
}

std::vector<Cell> scanCells(const StabilityPlan& plan, const std::vector<std::string>& integrators,
                            const ChainConstants& constants) {
  std::vector<Cell> cells;
  for (const auto& name : integrators) {
    for (int length : plan.lengths)
      cells.push_back({name, length, constants.defaultStiffness,
                       plan.sweepLengths.count(length) ? plan.durations : std::vector<double>{plan.duration}});
    for (int length : plan.feedbackLengths) cells.push_back({name, length, constants.stiffFeedback, {plan.duration}});
  }
  return cells;
}

std::vector<LadderCell> ladderCells(const StabilityPlan& plan, const std::vector<std::string>& integrators) {
  std::vector<LadderCell> cells;
  for (const auto& name : integrators)
    for (double dt : kTableSteps)
      for (int length : plan.ladder) cells.push_back({name, dt, length});
  return cells;
}

// The whip's frequency per chain length, over the longest T each is scanned for.
std::map<int, double> measureWhipRates(const LabOptions& options, const StabilityPlan& plan) {
  std::map<int, double> whipRate;
  const Results<double> rates =
      sweepResults<double>(options, plan.lengths.size(), [&](std::size_t k) -> std::optional<double> {
        const int length = plan.lengths[k];
        const double rate = fastestLinkRate(length, longestDuration(plan, length), options.criterion);
        if (interrupted()) return std::nullopt;
        return rate;
      });
  for (const auto& [k, rate] : rates) whipRate[plan.lengths[k]] = rate;
  return whipRate;
}

std::optional<std::vector<ScanRun>> scanCell(const Cell& cell, const ScanSettings& scan,
                                             const FailureCriterion& criterion) {
  ScanSettings settings = scan;
  settings.durations = cell.durations;
  return scanSteps(
      [&](double dt, int member, double duration) {
        return runMember([&] { return buildCell(cell.length, cell.stiffness); }, cell.integrator, dt, member, duration,
                         criterion, nullptr, settings.durations);
      },
      settings);
}

Results<std::vector<ScanRun>> runScans(const LabOptions& options, const StabilityPlan& plan,
                                       const std::vector<Cell>& cells) {
  Progress progress(options, "stability", static_cast<long>(cells.size()));
  return sweepResults<std::vector<ScanRun>>(
      options, cells.size(),
      [&](std::size_t k) {
        auto runs = scanCell(cells[k], plan.scan, options.criterion);
        progress.tick();
        return runs;
      },
      [&](std::size_t k) {  // the scan's steps are dominated by its smallest dt
        const Cell& cell = cells[k];
        return estimatedRunSeconds(buildCell(cell.length, cell.stiffness), cell.integrator, plan.scan.grid.front(),
                                   cell.durations.back());
      });
}

// A member that fails ends the cell: it and every longer chain fail at this dt.
std::optional<Probe> runLadderCell(const LadderCell& cell, const StabilityPlan& plan,
                                   const FailureCriterion& criterion) {
  Probe worst;
  for (int member = 0; member < plan.ladderMembers; ++member) {
    const auto probe = runMember([&] { return buildChain({cell.length}); }, cell.integrator, cell.dt, member,
                             plan.duration, criterion);
    if (!probe) return std::nullopt;
    if (!probe->survives(plan.duration, cell.dt)) return probe;
    worst = *probe;
  }
  return worst;
}

// Frequencies present: the feedback C̈ = −k_s C − k_d Ċ rings at √k_s;
// the chain's fastest transverse mode under its top tension
// (cl − 1) m g is ω ≈ 2 √((cl − 1) g / r) (a beaded string, tension T,
// bead mass m, spacing r: ω_max = 2 √(T / (m r))).
// The whip's rate is measured (fastestLinkRate). Which one governs is
// read off the products dt·ω (constant along a regime), not assumed.
struct Frequencies {
  double feedback, chain, whip;
  std::string stiffest;
};

Frequencies frequenciesOf(const Cell& cell, const ChainConstants& constants, const std::map<int, double>& whipRate) {
  Frequencies frequencies;
  frequencies.feedback = std::sqrt(cell.stiffness);
  frequencies.chain = 2.0 * std::sqrt((cell.length - 1) * constants.gravity / constants.rod);
  const auto whip = whipRate.find(cell.length);
  frequencies.whip = whip != whipRate.end() ? whip->second : 0.0;
  const double stiffest = std::max({frequencies.feedback, frequencies.chain, frequencies.whip});
  frequencies.stiffest = stiffest == frequencies.feedback ? "feedback"
                         : stiffest == frequencies.whip   ? "whip"
                                                          : "chain";
  return frequencies;
}

// What a scan says about one of its T.
struct Verdict {
  double duration;
  std::vector<GridSurvival> survival;
  Boundary boundary;
};

std::vector<Verdict> verdictsOf(const Cell& cell, const std::vector<ScanRun>& runs, int members) {
  std::vector<Verdict> verdicts;
  for (double duration : cell.durations) {
    auto survival = survivalAt(runs, duration, members);
    const Boundary boundary = boundaryOf(survival);
    verdicts.push_back({duration, std::move(survival), boundary});
  }
  return verdicts;
}

// The coarse scan's boundaries, [T][integrator][cl] at the default k_s, and at 4 k_s.
struct SafeSteps {
  std::map<double, std::map<std::string, std::map<int, Boundary>>> byDuration;
  std::map<std::string, std::map<int, Boundary>> stiff;
  const Boundary& at(double duration, const std::string& integrator, int length) {
    return byDuration[duration][integrator][length];
  }
};

// stability_boundary.csv and stability_map.csv, every scan's rows in cell order; the safe steps they show.
SafeSteps writeScanRows(const LabOptions& options, const StabilityPlan& plan, const std::vector<Cell>& cells,
                        const Results<std::vector<ScanRun>>& scans, const ChainConstants& constants,
                        const std::map<int, double>& whipRate) {
  Csv boundaryCsv(options, "stability_boundary.csv",
                  {"integrator", "chain_length", "feedback_ks", "duration", "largest_surviving_dt", "first_failure_dt",
                   "first_failure", "survival_above", "grid_lo", "grid_hi", "members", "omega_feedback",
                   "omega_chain", "omega_whip", "stiffest"});
  Csv mapCsv(options, "stability_map.csv",
             {"integrator", "chain_length", "feedback_ks", "duration", "dt", "members_run", "survivors", "survived",
              "failure", "max_relative_stretch", "max_energy_rise"});
  SafeSteps safe;
  for (const auto& [k, runs] : scans) {
    const Cell& cell = cells[k];
    const Frequencies frequencies = frequenciesOf(cell, constants, whipRate);
    for (const Verdict& verdict : verdictsOf(cell, runs, plan.scan.members)) {
      const Boundary& boundary = verdict.boundary;
      boundaryCsv << cell.integrator << cell.length << cell.stiffness << verdict.duration << boundary.safeDt
                  << boundary.firstFailureDt << failureName(boundary.firstFailure) << listText(boundary.survivalAbove)
                  << boundary.lowest << boundary.highest << static_cast<long>(plan.scan.members) << frequencies.feedback
                  << frequencies.chain << frequencies.whip << frequencies.stiffest;
      boundaryCsv.endRow();
      for (const GridSurvival& point : verdict.survival) {
        mapCsv << cell.integrator << cell.length << cell.stiffness << verdict.duration << point.dt
               << static_cast<long>(point.membersRun) << static_cast<long>(point.survivors)
               << static_cast<long>(point.survived) << failureName(point.survived ? Failure::None : point.failure)
               << point.maxRelativeStretch << point.maxEnergyRise;
        mapCsv.endRow();
      }
      if (cell.stiffness == constants.defaultStiffness)
        safe.byDuration[verdict.duration][cell.integrator][cell.length] = boundary;
      else safe.stiff[cell.integrator][cell.length] = boundary;
    }
  }
  return safe;
}

// Table 2's cells: every integrator at every table length, scanned at T.
struct CertifyCell {
  std::string integrator;
  int length;
};

std::vector<CertifyCell> certifyCells(const StabilityPlan& plan, const std::vector<std::string>& integrators) {
  std::vector<CertifyCell> cells;
  for (const auto& name : integrators)
    for (int length : plan.tableLengths) cells.push_back({name, length});
  return cells;
}

Results<Certificate> runCertifications(const LabOptions& options, const StabilityPlan& plan,
                                       const std::vector<CertifyCell>& cells, SafeSteps& safe) {
  Progress progress(options, "stability certification", static_cast<long>(cells.size()));
  return sweepResults<Certificate>(
      options, cells.size(),
      [&](std::size_t k) {
        const CertifyCell& cell = cells[k];
        auto certificate = certifySafeStep(
            [&](double dt, int member) {
              return runMember([&] { return buildChain({cell.length}); }, cell.integrator, dt, member, plan.duration,
                               options.criterion);
            },
            plan.duration, plan.certify);
        progress.tick();
        return certificate;
      },
      [&](std::size_t k) {  // most steps go to the decade below the coarse scan's boundary
        const CertifyCell& cell = cells[k];
        const double coarse = safe.at(plan.duration, cell.integrator, cell.length).safeDt;
        return estimatedRunSeconds(buildChain({cell.length}), cell.integrator,
                                   std::max(coarse > 0.0 ? coarse / 10.0 : plan.certify.floor, plan.certify.floor),
                                   plan.duration);
      });
}

// certified[integrator][cl]: Table 2.
using Certified = std::map<std::string, std::map<int, Certificate>>;

std::string bandName(double lo, double hi) { return general(lo, 3) + "_" + general(hi, 3); }

// stability_certified.csv, a row per certification; the certificates by integrator and length.
Certified writeCertificationRows(const LabOptions& options, const StabilityPlan& plan,
                                 const std::vector<CertifyCell>& cells, const Results<Certificate>& results,
                                 SafeSteps& coarse) {
  std::vector<std::string> columns{"integrator", "chain_length", "duration", "survived_dt", "runs_at_and_below",
                                   "failure_bound", "smallest_failure_dt", "smallest_failure", "grid_lo", "grid_hi",
                                   "resolution", "members", "points", "runs", "full_decades"};
  const std::vector<double>& edges = plan.certify.bandEdges;
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    const std::string name = bandName(edges[k], edges[k + 1]);
    for (const char* column : {"points_", "failed_points_", "runs_", "failed_runs_"}) columns.push_back(column + name);
  }
  columns.push_back("coarse_surviving_dt");
  Csv csv(options, "stability_certified.csv", columns);
  Certified certified;
  for (const auto& [k, c] : results) {
    const CertifyCell& cell = cells[k];
    csv << cell.integrator << static_cast<long>(cell.length) << plan.duration << c.survivedDt << c.atAndBelow.runs
        << c.bound() << c.smallestFailureDt << failureName(c.smallestFailure) << c.lowest << c.highest
        << plan.certify.resolution << static_cast<long>(plan.certify.members) << static_cast<long>(c.points) << c.runs
        << static_cast<long>(c.fullDecades);
    for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
      const FailureBand band = b < c.bands.size() ? c.bands[b] : FailureBand{};
      csv << static_cast<long>(band.points) << static_cast<long>(band.failedPoints) << band.runs.runs
          << band.runs.failures;
    }
    csv << coarse.at(plan.duration, cell.integrator, cell.length).safeDt;
    csv.endRow();
    certified[cell.integrator][cell.length] = c;
  }
  return certified;
}

// survived[integrator][dt][cl] on Table 1's ladder.
using LadderSurvival = std::map<std::string, std::map<double, std::map<int, bool>>>;

LadderSurvival writeLadderRows(const LabOptions& options, const StabilityPlan& plan,
                               const std::vector<LadderCell>& cells, const Results<Probe>& probes) {
  Csv ladderCsv(options, "table1_runs.csv",
                {"integrator", "dt", "chain_length", "survived", "failure", "failure_time"});
  LadderSurvival survived;
  for (const auto& [k, probe] : probes) {
    const LadderCell& cell = cells[k];
    const bool ok = probe.survives(plan.duration, cell.dt);
    ladderCsv << cell.integrator << cell.dt << static_cast<long>(cell.length) << static_cast<long>(ok)
              << failureName(ok ? Failure::None : probe.failure) << (ok ? plan.duration : probe.time);
    ladderCsv.endRow();
    survived[cell.integrator][cell.dt][cell.length] = ok;
  }
  return survived;
}

// The longest chain that survives at one dt: every length of the ladder up to it survives on every member.
struct LongestChain {
  int longest = 0, firstFail = 0;
  std::vector<double> above;  // lengths past the first failure that survive
};

LongestChain longestChain(const std::vector<int>& ladder, const std::map<int, bool>& survived) {
  LongestChain result;
  for (int length : ladder) {
    const auto found = survived.find(length);
    const bool ok = found != survived.end() && found->second;
    if (result.firstFail == 0 && ok) result.longest = length;
    else if (result.firstFail == 0) result.firstFail = length;
    else if (ok) result.above.push_back(length);
  }
  return result;
}

std::string longestChainText(const LongestChain& chain, const std::vector<int>& ladder) {
  std::string text = chain.firstFail == 0 ? "≥ " + std::to_string(ladder.back())
                     : chain.longest == 0 ? "< " + std::to_string(ladder.front())
                                          : std::to_string(chain.longest);
  if (!chain.above.empty()) text += " (" + listText(chain.above) + " survive)";
  return text;
}

// The published tables' values, beside the measured ones.
void appendSeed(std::vector<std::string>& row, const std::map<std::string, std::vector<std::string>>& seed,
                const std::string& integrator) {
  const auto found = seed.find(integrator);
  for (int k = 0; k < 3; ++k) row.push_back(found != seed.end() ? found->second[k] : "–");
}

// Table 1's rows, and table1_max_chain_length.csv.
std::vector<std::vector<std::string>> table1Rows(const LabOptions& options, const StabilityPlan& plan,
                                                 const std::vector<std::string>& integrators,
                                                 LadderSurvival& survived) {
  const std::map<std::string, std::vector<std::string>> seed = {
      {"symplectic-euler", {"0", "2", "2"}}, {"midpoint", {"1", "12", "52"}}, {"rk4", {"15", "40", "72"}}};
  Csv csv(options, "table1_max_chain_length.csv",
          {"integrator", "dt", "max_chain_length", "first_failing_length", "survival_above"});
  std::vector<std::vector<std::string>> rows;
  for (const auto& name : integrators) {
    std::vector<std::string> row{name};
    for (double dt : kTableSteps) {
      const LongestChain chain = longestChain(plan.ladder, survived[name][dt]);
      csv << name << dt << static_cast<long>(chain.longest) << static_cast<long>(chain.firstFail)
          << listText(chain.above);
      csv.endRow();
      row.push_back(longestChainText(chain, plan.ladder));
    }
    appendSeed(row, seed, name);
    rows.push_back(row);
  }
  return rows;
}

std::vector<std::vector<std::string>> table2Rows(const LabOptions& options, const StabilityPlan& plan,
                                                 const std::vector<std::string>& integrators, Certified& certified) {
  const std::map<std::string, std::vector<std::string>> seed = {
      {"symplectic-euler", {"0.01", "0.01", "0.008"}},
      {"midpoint", {"0.1", "0.1", "0.085"}},
      {"rk4", {"0.25", "0.22", "0.115"}}};
  std::vector<std::vector<std::string>> rows;
  for (const auto& name : integrators) {
    std::vector<std::string> row{name};
    for (int length : plan.tableLengths) {
      const Certificate& c = certified[name][length];
      row.push_back(survivedWithBoundText(c));
      const std::string key = name + ".cl" + std::to_string(length);
      recordValue(options, "stability.survived_dt." + key, survivedText(c));
      recordValue(options, "stability.bound." + key, c.belowFloor() ? "–" : boundText(c.atAndBelow));
    }
    appendSeed(row, seed, name);
    rows.push_back(row);
  }
  return rows;
}

using Rows = std::vector<std::vector<std::string>>;

// The coarse scan's largest surviving dt, first failure (what fired) and survival above it.
Rows boundaryRows(const StabilityPlan& plan, const std::vector<std::string>& integrators, SafeSteps& safe) {
  Rows rows;
  for (const auto& name : integrators)
    for (int length : plan.lengths) {
      const Boundary& boundary = safe.at(plan.duration, name, length);
      rows.push_back({name, std::to_string(length), safeStepText(boundary),
                      boundary.aboveGrid()
                          ? "–"
                          : general(boundary.firstFailureDt, 3) + " (" + failureName(boundary.firstFailure) + ")",
                      boundary.survivalAbove.empty() ? "–" : listText(boundary.survivalAbove)});
    }
  return rows;
}

// Each certification: the survived dt with its bound (failed runs / runs at and below it), the
// smallest failure, the scanned range, the failed runs / runs in each band below and above the
// survived dt, and the coarse scan's largest surviving dt.
Rows certifiedRows(const StabilityPlan& plan, const std::vector<std::string>& integrators, Certified& certified,
                   SafeSteps& safe) {
  Rows rows;
  for (const auto& name : integrators)
    for (int length : plan.tableLengths) {
      const Certificate& c = certified[name][length];
      std::vector<std::string> row{
          name, std::to_string(length), survivedText(c),
          c.belowFloor() ? "–" : countText(c.atAndBelow) + ", " + boundText(c.atAndBelow),
          c.aboveGrid() ? "–" : general(c.smallestFailureDt, 4) + " (" + failureName(c.smallestFailure) + ")",
          general(c.lowest, 3) + "–" + general(c.highest, 3) + " (" + std::to_string(c.points) + " dt, " +
              std::to_string(c.runs) + " runs)",
          c.fullDecades ? "yes" : "no (floor)"};
      for (std::size_t b = 0; b + 1 < plan.certify.bandEdges.size(); ++b)
        row.push_back(b < c.bands.size() && c.bands[b].points > 0 ? countText(c.bands[b].runs) : "–");
      row.push_back(safeStepText(safe.at(plan.duration, name, length)));
      rows.push_back(row);
    }
  return rows;
}

Rows durationRows(const StabilityPlan& plan, const std::vector<std::string>& integrators, SafeSteps& safe) {
  Rows rows;
  for (const auto& name : integrators)
    for (int length : plan.sweepLengths) {
      std::vector<std::string> row{name, std::to_string(length)};
      for (double d : plan.durations) row.push_back(safeStepText(safe.at(d, name, length)));
      rows.push_back(row);
    }
  return rows;
}

Rows frequencyRows(const StabilityPlan& plan, const std::vector<std::string>& integrators, SafeSteps& safe,
                   const ChainConstants& constants, std::map<int, double>& whipRate) {
  Rows rows;
  for (const auto& name : integrators)
    for (int length : plan.lengths) {
      const Boundary& boundary = safe.at(plan.duration, name, length);
      if (!onGrid(boundary)) continue;
      rows.push_back({name, std::to_string(length), general(boundary.safeDt, 2),
                      general(boundary.safeDt * std::sqrt(constants.defaultStiffness), 2),
                      general(boundary.safeDt * whipRate[length], 2),
                      general(boundary.safeDt * 2.0 * std::sqrt((length - 1) * constants.gravity / constants.rod), 2)});
    }
  return rows;
}

Rows feedbackRows(const StabilityPlan& plan, const std::vector<std::string>& integrators, SafeSteps& safe,
                  const ChainConstants& constants) {
  Rows rows;
  for (const auto& name : integrators)
    for (int length : plan.feedbackLengths) {
      const Boundary& soft = safe.at(plan.duration, name, length);
      const Boundary& stiff = safe.stiff[name][length];
      rows.push_back({name, std::to_string(length), safeStepText(soft), safeStepText(stiff),
                      onGrid(soft) ? general(soft.safeDt * std::sqrt(constants.defaultStiffness), 3) : "–",
                      onGrid(stiff) ? general(stiff.safeDt * std::sqrt(constants.stiffFeedback), 3) : "–"});
    }
  return rows;
}

// How far the boundary moves from T to 2T: the median ratio over every
// integrator and swept length with both boundaries on the grid.
void recordShifts(const LabOptions& options, const StabilityPlan& plan, const std::vector<std::string>& integrators,
                  SafeSteps& safe) {
  const char* step[] = {"half_to_T", "T_to_2T", "2T_to_4T"};
  for (std::size_t k = 0; k + 1 < plan.durations.size(); ++k) {
    std::vector<double> ratios;
    for (const auto& name : integrators)
      for (int length : plan.sweepLengths) {
        const Boundary& shorter = safe.at(plan.durations[k], name, length);
        const Boundary& longer = safe.at(plan.durations[k + 1], name, length);
        if (onGrid(shorter) && onGrid(longer)) ratios.push_back(longer.safeDt / shorter.safeDt);
      }
    recordValue(options, std::string("stability.shift.") + step[k], ratios.empty() ? "–" : fixed(median(ratios), 2));
  }
}

std::string conditionsText(const StabilityPlan& plan) {
  return "T = " + general(plan.duration) + " s, " + output::plural(plan.scan.members, "start") + ", 5% dt grid";
}

// Table 2's conditions: the certification's grid, ensemble and decade.
std::string certifiedConditionsText(const StabilityPlan& plan) {
  const CertifySettings& c = plan.certify;
  return "T = " + general(plan.duration) + " s, " + output::plural(c.members, "start") + ", " +
         general(100.0 * c.resolution) + "% dt grid descending from " + general(c.top) + " s until " +
         general(c.decades) + (c.decades == 1.0 ? " decade" : " decades") +
         " below the smallest failure survives (floor T/" + std::to_string(plan.certifyMaxSteps) + ")";
}

void writeSafeStepTables(const LabOptions& options, const StabilityPlan& plan, const Rows& table1, const Rows& table2,
                         const Rows& certified, const Rows& boundaries, const Rows& vsDuration) {
  const std::string at = conditionsText(plan);
  writeTable(options, "table1", "Table 1: longest chain (of " + std::to_string(plan.ladder.size()) + " lengths " +
                                    std::to_string(plan.ladder.front()) + "–" + std::to_string(plan.ladder.back()) +
                                    ") such that it and every shorter one survive, T = " + general(plan.duration) +
                                    " s, " + output::plural(plan.ladderMembers, "start"),
             {"integrator", "dt 0.2", "dt 0.1", "dt 0.05", "seed dt 0.2", "seed dt 0.1", "seed dt 0.05"}, table1);
  std::vector<std::string> table2Header{"integrator"};
  for (int length : plan.tableLengths) table2Header.push_back("cl " + std::to_string(length));
  for (const char* seed : {"seed cl 6", "seed cl 12", "seed cl 24"}) table2Header.push_back(seed);
  writeTable(options, "table2",
             "Table 2: the largest dt whose grid and starts all survived (it and every grid dt below it, down to "
             "the scan's bottom, on every start), with the 95% upper bound p on the per-run failure probability "
             "that those runs support (Clopper–Pearson, none failed), " +
                 certifiedConditionsText(plan),
             table2Header, table2);
  std::vector<std::string> certifiedHeader{"integrator", "chain length", "survived dt", "failed/runs at and below, bound",
                                           "smallest failure", "scanned", "a decade below"};
  const std::vector<double>& edges = plan.certify.bandEdges;
  for (std::size_t b = 0; b + 1 < edges.size(); ++b)
    certifiedHeader.push_back("failed/runs in (" + general(edges[b]) + ", " + general(edges[b + 1]) + "] × dt");
  certifiedHeader.push_back("coarse scan (" + output::plural(plan.scan.members, "start") + ", 5%)");
  writeTable(options, "stability_certified",
             "Table 2 in detail: the survived dt, the runs at and below it and the bound they support, the smallest "
             "failure, and the failed runs / runs in bands below and above the survived dt (every start run at every "
             "grid dt up to " + general(edges.back()) + "×), " + certifiedConditionsText(plan),
             certifiedHeader, certified);
  writeTable(options, "stability_boundary",
             "Coarse scan: the largest surviving dt (every grid dt at and below it survived on every start; no "
             "bound: see Table 2), the first failure (what fired) and survival above it, " + at,
             {"integrator", "chain length", "largest surviving dt", "first failure", "survives again at"}, boundaries);
  std::vector<std::string> header{"integrator", "chain length"};
  for (double d : plan.durations) header.push_back("T = " + general(d) + " s");
  writeTable(options, "stability_vs_duration",
             "Largest surviving dt of the coarse scan against T (" + output::plural(plan.scan.members, "start") +
                 ", 5% dt grid)",
             header, vsDuration);
}

void writeFrequencyTables(const LabOptions& options, const StabilityPlan& plan, const ChainConstants& constants,
                          const std::map<int, double>& whipRate, const Rows& feedback, const Rows& frequency) {
  const std::string at = conditionsText(plan);
  const std::string soft = general(constants.defaultStiffness), stiff = general(constants.stiffFeedback);
  writeTable(options, "stability_feedback",
             "Short chains: the coarse scan's largest surviving dt at the feedback stiffness k_s = " + soft + " and " + stiff + " (" + at +
                 "); dt·√k_s constant means the feedback governs",
             {"integrator", "chain length", "surviving dt, k_s " + soft, "surviving dt, k_s " + stiff, "dt·√k_s at " + soft,
              "dt·√k_s at " + stiff},
             feedback);
  Rows whipRows;
  for (int length : plan.lengths) {
    const auto whip = whipRate.find(length);
    whipRows.push_back({std::to_string(length), general(whip != whipRate.end() ? whip->second : 0.0, 3)});
  }
  writeTable(options, "stability_whip",
             "The whip: fastest rod rotation rate max |d × ḋ|/|d|² over the run (RK4, dt 0.005), 1/s",
             {"chain length", "ω_whip"}, whipRows);
  writeTable(options, "stability_frequency",
             "The coarse scan's largest surviving dt times each frequency present (" + at + "): √k_s = " +
                 general(std::sqrt(constants.defaultStiffness), 3) +
                 " (feedback), ω_whip measured, 2√((cl−1)g/r) (static chain mode); constant down a column: that "
                 "frequency governs",
             {"integrator", "chain length", "surviving dt", "dt·√k_s", "dt·ω_whip", "dt·ω_chain"}, frequency);
}

void recordSettings(const LabOptions& options, const StabilityPlan& plan, const ChainConstants& constants) {
  const ScanSettings& scan = plan.scan;
  const FailureCriterion& criterion = options.criterion;
  recordValue(options, "stability.duration", general(plan.duration));
  std::string durationText;
  for (double d : plan.durations) durationText += (durationText.empty() ? "" : ", ") + general(d);
  recordValue(options, "stability.durations", durationText);
  recordValue(options, "stability.members", std::to_string(scan.members));
  recordValue(options, "stability.ladder_members", std::to_string(plan.ladderMembers));
  recordValue(options, "stability.certify.members", std::to_string(plan.certify.members));
  recordValue(options, "stability.certify.resolution_percent", general(100.0 * plan.certify.resolution));
  recordValue(options, "stability.certify.top", general(plan.certify.top));
  recordValue(options, "stability.certify.decades", general(plan.certify.decades));
  recordValue(options, "stability.certify.max_steps", std::to_string(plan.certifyMaxSteps));
  recordValue(options, "stability.certify.floor", general(plan.certify.floor, 3));
  recordValue(options, "stability.perturbation", general(plan.perturbation));
  recordValue(options, "stability.grid_lo", general(scan.grid.front(), 3));
  recordValue(options, "stability.grid_hi", general(scan.grid.back(), 3));
  recordValue(options, "stability.grid_ratio", fixed(scan.grid[1] / scan.grid[0], 4));
  recordValue(options, "stability.grid_points", std::to_string(scan.grid.size()));
  recordValue(options, "stability.beyond", general(scan.beyond));
  recordValue(options, "stability.rod_length", general(constants.rod));
  recordValue(options, "stability.gravity", general(constants.gravity));
  recordValue(options, "stability.feedback_ks", general(constants.defaultStiffness));
  recordValue(options, "criterion.max_stretch", general(criterion.maxRelativeConstraintError));
  recordValue(options, "criterion.energy_rise", general(criterion.energyRiseFraction));
  recordValue(options, "criterion.text", describe(criterion));
}

}  // namespace

int runStability(const LabOptions& options, const StabilityOptions& stability) {
  prepareOutput(options, "stability.");
  std::cout << describe(options.criterion) << "\n";
  const std::vector<std::string> integrators = scannedIntegrators(options);
  StabilityPlan plan = options.quick ? quickPlan(stability) : fullPlan(stability);
  if (stability.failureBound > 0.0) plan.certify.members = membersForBound(plan.certify, stability.failureBound);
  const ChainConstants constants = chainConstants();
  const std::vector<Cell> cells = scanCells(plan, integrators, constants);
  printGrid(plan);

  std::map<int, double> whipRate = measureWhipRates(options, plan);
  if (interrupted()) return 130;
  const auto scans = runScans(options, plan, cells);
  SafeSteps safe = writeScanRows(options, plan, cells, scans, constants, whipRate);
  if (interrupted()) return 130;  // the rows written are complete scans; no table from a partial set

  const std::vector<LadderCell> ladder = ladderCells(plan, integrators);
  const auto probes = sweepResults<Probe>(options, ladder.size(), [&](std::size_t k) {
    return runLadderCell(ladder[k], plan, options.criterion);
  });
  LadderSurvival survived = writeLadderRows(options, plan, ladder, probes);
  if (interrupted()) return 130;

  const std::vector<CertifyCell> certifying = certifyCells(plan, integrators);
  Certified certified =
      writeCertificationRows(options, plan, certifying, runCertifications(options, plan, certifying, safe), safe);
  if (interrupted()) return 130;

  const Rows table1 = table1Rows(options, plan, integrators, survived);
  const Rows table2 = table2Rows(options, plan, integrators, certified);
  recordShifts(options, plan, integrators, safe);
  writeSafeStepTables(options, plan, table1, table2, certifiedRows(plan, integrators, certified, safe),
                      boundaryRows(plan, integrators, safe), durationRows(plan, integrators, safe));
  writeFrequencyTables(options, plan, constants, whipRate, feedbackRows(plan, integrators, safe, constants),
                       frequencyRows(plan, integrators, safe, constants, whipRate));
  recordSettings(options, plan, constants);
  return 0;
}

}  // namespace lab
