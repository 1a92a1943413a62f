#include "lab/certify.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "output/format_number.h"

namespace lab {

namespace {

// One scanned grid dt: the starts run there and how many failed, and what fired first.
struct Point {
  double dt = 0.0;
  FailureCount runs;
  Failure failure = Failure::None;
  bool survived(int members) const { return runs.failures == 0 && runs.runs == members; }
};

void requireSettings(const CertifySettings& s) {
  if (!(s.top > 0.0) || !(s.resolution > 0.0) || s.members < 1 || !(s.decades > 0.0) || !(s.floor >= 0.0) ||
      s.floor >= s.top)
    throw std::invalid_argument("certify: top > floor >= 0, resolution > 0, members >= 1 and decades > 0 needed");
  if (!std::is_sorted(s.bandEdges.begin(), s.bandEdges.end()) || s.bandEdges.empty() || !(s.bandEdges[0] > 0.0))
    throw std::invalid_argument("certify: band edges must be positive and ascending");
}

bool inBand(double ratio, const FailureBand& band) {
  return ratio > band.lo * (1.0 + 1e-12) && ratio <= band.hi * (1.0 + 1e-12);
}

// Grid points counted in the bands (edge_k, edge_k+1] × the survived dt.
std::vector<FailureBand> bandsAround(const std::vector<Point>& points, double survivedDt, int members,
                                     const std::vector<double>& edges) {
  std::vector<FailureBand> bands;
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    FailureBand band;
    band.lo = edges[k], band.hi = edges[k + 1];
    bands.push_back(band);
  }
  for (const Point& p : points)
    for (FailureBand& band : bands)
      if (inBand(p.dt / survivedDt, band)) {
        ++band.points;
        band.failedPoints += !p.survived(members);
        band.runs += p.runs;
      }
  return bands;
}

}  // namespace

int membersForBound(const CertifySettings& settings, double bound) {
  const double pointsPerDecade = stepsPerOctave(settings.resolution) * std::log2(10.0) * settings.decades;
  const long needed = runsForBound(bound);
  return std::max(settings.members, static_cast<int>(std::ceil(static_cast<double>(needed) / pointsPerDecade)));
}

std::optional<Certificate> certifySafeStep(const MemberRun& run, double duration, const CertifySettings& s) {
  requireSettings(s);
  const double floor = s.floor > 0.0 ? s.floor : s.top * std::pow(10.0, -3.0 * s.decades);
  const std::vector<double> grid = stepGrid(floor, s.top, s.resolution);
  const double reach = std::pow(10.0, s.decades);  // survival needed below the smallest failure
  Certificate c;
  std::vector<Point> points;  // descending dt
  // Whether the last dt scanned lies a whole `decades` below the smallest failure (the top if none).
  const auto spansDecades = [&] {
    const double smallest = c.smallestFailureDt > 0.0 ? c.smallestFailureDt : s.top;
    return !points.empty() && points.back().dt * reach <= smallest * (1.0 + 1e-12);
  };
  // Runs members from `from` on at one point, stopping at the first failure unless `every`.
  const auto runMembers = [&](Point& point, int from, bool every) {
    for (int member = from; member < s.members && (every || point.runs.failures == 0); ++member) {
      const std::optional<Probe> probe = run(point.dt, member);
      if (!probe) return false;
      ++c.runs;
      ++point.runs.runs;
      if (!probe->survives(duration, point.dt)) {
        if (point.runs.failures++ == 0) point.failure = probe->failure;
      }
    }
    return true;
  };
  for (auto dt = grid.rbegin(); dt != grid.rend() && !spansDecades(); ++dt) {
    Point point;
    point.dt = *dt;
    if (!runMembers(point, 0, false)) return std::nullopt;
    if (!point.survived(s.members)) c.smallestFailureDt = *dt, c.smallestFailure = point.failure;
    points.push_back(point);
  }
  c.fullDecades = spansDecades();
  c.points = static_cast<int>(points.size());
  if (!points.empty()) c.highest = points.front().dt, c.lowest = points.back().dt;
  // Descending order: the survived dt is the first point below the smallest failure.
  for (const Point& p : points)
    if (p.survived(s.members) && (c.smallestFailureDt == 0.0 || p.dt < c.smallestFailureDt)) {
      c.survivedDt = p.dt;
      break;
    }
  if (c.survivedDt == 0.0) return c;
  // Every start at the failing points up to the last band: failure fractions of runs.
  for (Point& p : points)
    if (p.dt > c.survivedDt && p.dt <= s.bandEdges.back() * c.survivedDt * (1.0 + 1e-12) &&
        !runMembers(p, p.runs.runs, true))
      return std::nullopt;
  for (const Point& p : points)
    if (p.dt <= c.survivedDt) c.atAndBelow += p.runs;
  c.bands = bandsAround(points, c.survivedDt, s.members, s.bandEdges);
  return c;
}

std::string survivedText(const Certificate& c) {
  if (c.belowFloor()) return "< " + output::formatGeneral(c.lowest, 4);
  if (c.aboveGrid()) return "≥ " + output::formatGeneral(c.survivedDt, 4);
  return output::formatGeneral(c.survivedDt, 4) + (c.fullDecades ? "" : " †");
}

std::string survivedWithBoundText(const Certificate& c) {
  if (c.belowFloor()) return survivedText(c);
  return survivedText(c) + " (" + boundText(c.atAndBelow) + ")";
}

}  // namespace lab
