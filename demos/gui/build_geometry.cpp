#include "build_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace demo {

namespace {
double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  const double s = e.squaredNorm() > 0.0 ? std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + s * e - p).norm();
}
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

std::size_t wallCount(const Json& document) {
  const auto walls = document.find("walls");
  return walls != document.end() && walls->is_array() ? walls->size() : 0;
}

// A collider as the hull of its points grown by its radius: the polygon (or
// segment) through its points, and a circle of the radius at each point; a
// half-plane (unbounded) as its surface line, `reach` long each way.
particles::Sketch colliderOutline(const particles::Collider& c, double reach) {
  particles::Sketch out;
  Eigen::Vector2d lo, hi;
  if (!c.bounds(lo, hi)) {
    const Eigen::Vector2d along(-c.normal.y(), c.normal.x());
    out.lines.push_back({c.points[0] - reach * along, c.points[0] + reach * along});
    return out;
  }
  const std::size_t n = c.points.size();
  for (std::size_t k = 0; n > 1 && k < (n > 2 ? n : 1); ++k) {
    const Eigen::Vector2d a = c.points[k], b = c.points[(k + 1) % n];
    if (c.radius > 0.0 && n == 2) {  // a capsule's sides
      const Eigen::Vector2d side = c.radius * Eigen::Vector2d(a.y() - b.y(), b.x() - a.x()).normalized();
      out.lines.push_back({a + side, b + side});
      out.lines.push_back({a - side, b - side});
    } else {
      out.lines.push_back({a, b});
    }
  }
  if (c.radius > 0.0)
    for (const Eigen::Vector2d& p : c.points) out.circles.push_back({p, c.radius});
  return out;
}

// The system's collider of a collider reference (walls first).
const particles::Collider* colliderOf(const Json& document, const particles::ParticleSystem& system,
                                      const ObjectRef& ref) {
  std::size_t index = ref.index;
  if (ref.list == "colliders") index += wallCount(document);
  else if (ref.list != "walls") return nullptr;
  return index < system.colliders().size() ? &system.colliders()[index] : nullptr;
}

// Each list of the document with the number of its objects in the system.
struct Listed {
  const char* list;
  std::size_t count;
};
std::vector<Listed> pickableLists(const Json& document, const particles::ParticleSystem& system) {
  const std::size_t walls = std::min(wallCount(document), system.colliders().size());
  return {{"forces", system.forceObjects().size()},
          {"constraints", system.constraints().size()},
          {"collisionEdges", system.collisionEdges().size()},
          {"walls", walls},
          {"colliders", system.colliders().size() - walls}};
}
}  // namespace

particles::Sketch outlineOf(const Json& document, const particles::ParticleSystem& system, const ObjectRef& ref,
                            double reach) {
  particles::Sketch out;
  const particles::Phase phase = system.phase();
  const auto inRange = [&](std::size_t count) { return ref.index < count; };
  if (ref.list == "particles" && inRange(static_cast<std::size_t>(system.size())))
    out.circles.push_back({system.position(static_cast<int>(ref.index)), 0.0});
  else if (ref.list == "forces" && inRange(system.forceObjects().size()))
    system.forceObjects()[ref.index]->sketch(phase, out);
  else if (ref.list == "constraints" && inRange(system.constraints().size()))
    system.constraints()[ref.index]->sketch(phase, out);
  else if (ref.list == "collisionEdges" && inRange(system.collisionEdges().size()))
    out.lines.push_back({system.position(system.collisionEdges()[ref.index].a),
                         system.position(system.collisionEdges()[ref.index].b)});
  else if (const particles::Collider* c = colliderOf(document, system, ref))
    out = colliderOutline(*c, reach);
  return out;
}

double distanceTo(const particles::Sketch& sketch, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& line : sketch.lines) best = std::min(best, distanceToSegment(p, line.a, line.b));
  for (const auto& circle : sketch.circles) best = std::min(best, std::abs((p - circle.centre).norm() - circle.radius));
  return best;
}

std::optional<int> nearestParticle(const particles::ParticleSystem& system, const Eigen::Vector2d& p, double radius) {
  std::optional<int> best;
  double bestDistance = radius;
  for (int i = 0; i < system.size(); ++i) {
    const double d = (system.position(i) - p).norm();
    if (d <= bestDistance) {
      bestDistance = d;
      best = i;
    }
  }
  return best;
}

std::optional<ObjectRef> pickObject(const Json& document, const particles::ParticleSystem& system,
                                    const Eigen::Vector2d& p, double radius) {
  if (const std::optional<int> particle = nearestParticle(system, p, radius))
    return ObjectRef{"particles", static_cast<std::size_t>(*particle)};
  std::optional<ObjectRef> best;
  double bestDistance = radius;
  for (const Listed& listed : pickableLists(document, system))
    for (std::size_t k = 0; k < listed.count; ++k) {
      const ObjectRef ref{listed.list, k};
      double d = distanceTo(outlineOf(document, system, ref, 1e3 * radius), p);
      // Inside a collider counts as at the edge of the reach: an outline near by wins.
      if (const particles::Collider* c = colliderOf(document, system, ref))
        if (c->distance(p).distance < 0.0) d = std::min(d, radius);
      if (d < bestDistance || (!best && d <= bestDistance)) {  // a tie goes to the first listed
        bestDistance = d;
        best = ref;
      }
    }
  return best;
}

std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  // Lower hull left to right, then upper hull right to left; a point that
  // does not turn left is dropped.
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace demo
