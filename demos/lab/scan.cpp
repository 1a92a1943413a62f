#include "lab/scan.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lab {

Maxima Probe::maximaUpTo(double duration, double dt) const {
  for (const Maxima& m : maximaAt)
    if (std::abs(m.time - duration) <= 0.5 * dt) return m;
  return {time, maxRelativeStretch, maxEnergyRise};
}

int stepsPerOctave(double resolution) { return static_cast<int>(std::ceil(std::log(2.0) / std::log1p(resolution))); }

std::vector<double> stepGrid(double lo, double hi, double resolution, double anchor) {
  const int perOctave = stepsPerOctave(resolution);
  const int first = static_cast<int>(std::ceil(perOctave * std::log2(lo / anchor) - 1e-9));
  const int last = static_cast<int>(std::floor(perOctave * std::log2(hi / anchor) + 1e-9));
  std::vector<double> grid;
  for (int k = first; k <= last; ++k) {
    // anchor·2^(k/m), exact at whole octaves
    const int octave = (k >= 0 ? k : k - perOctave + 1) / perOctave, rest = k - octave * perOctave;
    grid.push_back(std::ldexp(anchor * std::pow(2.0, static_cast<double>(rest) / perOctave), octave));
  }
  return grid;
}

std::vector<double> stepGridDividing(double duration, double lo, double hi, double resolution, double anchor) {
  std::vector<double> grid;
  long previous = 0;
  const std::vector<double> fine = stepGrid(lo, hi, resolution, anchor);
  for (auto dt = fine.rbegin(); dt != fine.rend(); ++dt) {  // descending: n ascending
    const long steps = std::max(1L, std::lround(duration / *dt));
    if (steps == previous) continue;
    previous = steps;
    grid.insert(grid.begin(), duration / steps);
  }
  return grid;
}

std::optional<std::vector<ScanRun>> scanSteps(const std::function<std::optional<Probe>(double, int, double)>& run,
                                               const ScanSettings& s) {
  const double shortest = *std::min_element(s.durations.begin(), s.durations.end());
  const double longest = *std::max_element(s.durations.begin(), s.durations.end());
  std::vector<ScanRun> runs;
  double firstFailure = 0.0;
  for (double dt : s.grid) {
    if (firstFailure > 0.0 && dt > s.beyond * firstFailure) break;
    bool failedShortest = false;
    for (int member = 0; member < s.members && !failedShortest; ++member) {
      const std::optional<Probe> probe = run(dt, member, longest);
      if (!probe) return std::nullopt;
      runs.push_back({dt, member, *probe});
      failedShortest = !probe->survives(shortest, dt);
    }
    if (failedShortest && firstFailure == 0.0) firstFailure = dt;
  }
  return runs;
}

std::vector<GridSurvival> survivalAt(const std::vector<ScanRun>& runs, double duration, int members) {
  std::vector<GridSurvival> out;
  double earliest = 0.0;
  for (const ScanRun& r : runs) {
    if (out.empty() || out.back().dt != r.dt) {
      out.push_back({r.dt, true});
      earliest = std::numeric_limits<double>::infinity();
    }
    GridSurvival& g = out.back();
    ++g.membersRun;
    const bool ok = r.probe.survives(duration, r.dt);
    g.survivors += ok;
    if (!ok && r.probe.time < earliest) earliest = r.probe.time, g.failure = r.probe.failure;
    const Maxima upTo = r.probe.maximaUpTo(duration, r.dt);
    g.maxRelativeStretch = std::max(g.maxRelativeStretch, upTo.stretch);
    g.maxEnergyRise = std::max(g.maxEnergyRise, upTo.rise);
  }
  // A dt survives only if every member was run and survived (the scan skips
  // the members after one that failed).
  for (GridSurvival& g : out) g.survived = g.membersRun == members && g.survivors == members;
  return out;
}

Boundary boundaryOf(const std::vector<GridSurvival>& survival) {
  Boundary b;
  if (survival.empty()) return b;
  b.lowest = survival.front().dt;
  b.highest = survival.back().dt;
  std::size_t k = 0;
  for (; k < survival.size() && survival[k].survived; ++k) b.safeDt = survival[k].dt;
  if (k < survival.size()) {
    b.firstFailureDt = survival[k].dt;
    b.firstFailure = survival[k].failure;
    for (std::size_t j = k + 1; j < survival.size(); ++j)
      if (survival[j].survived) b.survivalAbove.push_back(survival[j].dt);
  }
  return b;
}

int survivorsBelowFirstFailure(const std::vector<GridSurvival>& survival) {
  int count = 0;
  for (const GridSurvival& g : survival) {
    if (!g.survived) break;
    ++count;
  }
  return count;
}

}  // namespace lab
