#include "lab/certify.h"

#include <cmath>
#include <stdexcept>

#include "output/format_number.h"

namespace lab {

namespace {

// One scanned grid dt: whether every member survived, and what fired first where one did not.
struct Point {
  double dt;
  bool survived;
  Failure failure;
};

void requireSettings(const CertifySettings& s) {
  if (!(s.top > 0.0) || !(s.resolution > 0.0) || s.members < 1 || !(s.decades > 0.0) || !(s.floor >= 0.0) ||
      s.floor >= s.top)
    throw std::invalid_argument("certify: top > floor >= 0, resolution > 0, members >= 1 and decades > 0 needed");
}

// Grid points above the safe dt, counted in the bands (edge_k, edge_k+1] × safe.
std::vector<FailureBand> bandsAbove(const std::vector<Point>& points, double safeDt,
                                    const std::vector<double>& edges) {
  std::vector<FailureBand> bands;
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) bands.push_back({edges[k], edges[k + 1]});
  for (const Point& p : points) {
    const double ratio = p.dt / safeDt;
    for (FailureBand& band : bands)
      if (ratio > band.lo * (1.0 + 1e-12) && ratio <= band.hi * (1.0 + 1e-12)) {
        ++band.points;
        band.failed += !p.survived;
      }
  }
  return bands;
}

}  // namespace

std::optional<Certificate> certifySafeStep(const MemberRun& run, double duration, const CertifySettings& s) {
  requireSettings(s);
  const double floor = s.floor > 0.0 ? s.floor : s.top * std::pow(10.0, -3.0 * s.decades);
  const std::vector<double> grid = stepGrid(floor, s.top, s.resolution);
  const double reach = std::pow(10.0, s.decades);  // survival needed below the smallest failure
  Certificate c;
  std::vector<Point> points;
  // Whether the last dt scanned lies a whole `decades` below the smallest failure (the top if none).
  const auto spansDecades = [&] {
    const double smallest = c.smallestFailureDt > 0.0 ? c.smallestFailureDt : s.top;
    return !points.empty() && points.back().dt * reach <= smallest * (1.0 + 1e-12);
  };
  for (auto dt = grid.rbegin(); dt != grid.rend() && !spansDecades(); ++dt) {
    Point point{*dt, true, Failure::None};
    for (int member = 0; member < s.members && point.survived; ++member) {
      const std::optional<Probe> probe = run(*dt, member);
      if (!probe) return std::nullopt;
      ++c.runs;
      if (!probe->survives(duration, *dt)) point = {*dt, false, probe->failure};
    }
    if (!point.survived) c.smallestFailureDt = *dt, c.smallestFailure = point.failure;
    points.push_back(point);
  }
  c.fullDecades = spansDecades();
  c.points = static_cast<int>(points.size());
  if (!points.empty()) c.highest = points.front().dt, c.lowest = points.back().dt;
  // Descending order: the safe dt is the first point below the smallest failure.
  for (const Point& p : points)
    if (p.survived && (c.smallestFailureDt == 0.0 || p.dt < c.smallestFailureDt)) {
      c.safeDt = p.dt;
      break;
    }
  if (c.safeDt > 0.0) c.bands = bandsAbove(points, c.safeDt, s.bandEdges);
  return c;
}

std::string certifiedText(const Certificate& c) {
  if (c.belowFloor()) return "< " + output::formatGeneral(c.lowest, 4);
  if (c.aboveGrid()) return "≥ " + output::formatGeneral(c.safeDt, 4);
  return output::formatGeneral(c.safeDt, 4) + (c.fullDecades ? "" : " †");
}

}  // namespace lab
