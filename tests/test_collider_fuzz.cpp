// Seeded fuzzing of particles placed inside, on and at the corners of every
// collider kind, through the scene-file reader, so that it runs in the
// sanitizer build. Each generated file holds one particle (a point or a disc)
// near one collider (half-plane, box — also in the older "walls" spelling —
// polygon, capsule or disc, of sizes 5 cm to 2 m): at a corner, on a face, on
// a cap, at a disc's centre, a hair inside or outside any of these, at rest,
// sliding or moving at up to 30 m/s, under gravity of 0, 9.81 or 100 m/s² in
// any direction, with or without friction, with restitution 0, 0.5 or 1, as
// a point or a disc of radius 1 or 10 cm. Each file must either
//   - be refused at load with one line naming the particle and the collider
//     it starts inside, and only when it is inside deeper than the reader's
//     rounding (FORMAT.md, Colliders), or
//   - run for a short while under every integrator with every step
//     completed, the state finite, the particle never left inside a collider,
//     and no energy gained beyond the bound below.
// The energy bound. Contacts take energy away (e ≤ 1, Coulomb friction,
// resting contacts) but for two effects of the scheme's own state, so a run
// may end at most
//     E(t) − E(0) ≤ ½ m |g|² dt t            (explicit Euler only)
//                 + m |g| (v_max + |g| dt) dt
//                 + 10⁻⁶ E_s
// above its start, with v_max the largest speed so far and E_s =
// m (|g| L + ½ |v₀|²) the scale of its energies (L the collider's size):
//   - explicit Euler gains ½ m |g|² dt every second under constant gravity
//     (its position lags its velocity by half a step), colliders or not;
//   - the contact pass follows the step's path of constant acceleration
//     (contact_path.h), whose velocity differs from the one a scheme reports
//     by up to ½ |g| dt (symplectic and implicit Euler lead by half a step),
//     so a bounce that reverses the normal velocity may change the energy
//     computed from the reported velocity by up to m |g| |v| dt. The next
//     bounce undoes it; it does not accumulate.
// A particle held at a corner while its velocity grows as g t (the trap this
// guards against) gains ½ m g² t², which passes the bound within 5 steps.
//
// Also here: the two hand-made cases that once trapped such a particle — a
// frictionless particle dropped on a triangle's slope and one at rest on a
// disc at 60° from its top — slide off with their energy kept under every
// integrator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "scene.h"
#include "scene_file/scene_file.h"

namespace {

using scenes::Json;
using Vec = Eigen::Vector2d;

// ---- an independent description of the colliders' geometry ----------------

enum class Kind { HalfPlane, Box, Polygon, Capsule, Disc };
const char* kindName(Kind k) {
  static const char* names[] = {"halfPlane", "box", "polygon", "capsule", "disc"};
  return names[static_cast<int>(k)];
}

struct Shape {
  Kind kind = Kind::Box;
  std::vector<Vec> points;  // half-plane: its point; box, polygon: corners ccw; capsule: core ends; disc: centre
  Vec normal{0.0, 1.0};     // half-plane only
  double radius = 0.0;      // capsule, disc
  double size = 1.0;        // its extent (the energy scale's length)
  double restitution = 0.5, friction = 0.0;
};

double segmentDistance(const Vec& x, const Vec& a, const Vec& b) {
  const Vec e = b - a;
  const double t = std::clamp((x - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
  return (x - (a + t * e)).norm();
}

Vec edgeNormal(const Vec& a, const Vec& b) {  // outward for a counter-clockwise loop
  const Vec e = (b - a).normalized();
  return {e.y(), -e.x()};
}

// Signed distance from x to the shape's surface, negative inside.
double signedDistance(const Shape& s, const Vec& x) {
  switch (s.kind) {
    case Kind::HalfPlane:
      return s.normal.dot(x - s.points[0]);
    case Kind::Capsule:
      return segmentDistance(x, s.points[0], s.points[1]) - s.radius;
    case Kind::Disc:
      return (x - s.points[0]).norm() - s.radius;
    default: {
      const std::size_t n = s.points.size();
      double inside = -1e300, outside = 1e300;
      for (std::size_t k = 0; k < n; ++k) {
        const Vec& a = s.points[k];
        const Vec& b = s.points[(k + 1) % n];
        inside = std::max(inside, edgeNormal(a, b).dot(x - a));
        outside = std::min(outside, segmentDistance(x, a, b));
      }
      return inside <= 0.0 ? inside : outside;
    }
  }
}

Json toJson(const Vec& v) { return Json::array({v.x(), v.y()}); }

Json colliderJson(const Shape& s, bool asWall) {
  Json c;
  switch (s.kind) {
    case Kind::HalfPlane:
      c = {{"type", "halfPlane"}, {"point", toJson(s.points[0])}, {"normal", toJson(s.normal)}};
      break;
    case Kind::Box:
      c = {{"min", toJson(s.points[0])}, {"max", toJson(s.points[2])}};
      if (!asWall) c["type"] = "box";
      break;
    case Kind::Polygon: {
      Json vertices = Json::array();
      for (const Vec& p : s.points) vertices.push_back(toJson(p));
      c = {{"type", "polygon"}, {"vertices", vertices}};
      break;
    }
    case Kind::Capsule:
      c = {{"type", "capsule"}, {"from", toJson(s.points[0])}, {"to", toJson(s.points[1])}, {"radius", s.radius}};
      break;
    case Kind::Disc:
      c = {{"type", "disc"}, {"centre", toJson(s.points[0])}, {"radius", s.radius}};
      break;
  }
  c["restitution"] = s.restitution;
  c["friction"] = s.friction;
  return c;
}

// ---- places on a shape ----------------------------------------------------

// A point of the shape and the outward direction there (at a corner, the
// bisector of its faces' normals; inside, any direction).
struct Place {
  const char* what;
  Vec point;
  Vec outward;
};

Vec unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

std::vector<Place> placesOn(const Shape& s, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Place> places;
  switch (s.kind) {
    case Kind::HalfPlane: {
      const Vec along(-s.normal.y(), s.normal.x());
      places.push_back({"face", s.points[0], s.normal});
      places.push_back({"face", s.points[0] + (u(rng) - 0.5) * s.size * along, s.normal});
      places.push_back({"deep inside", s.points[0] - 0.3 * s.size * s.normal, s.normal});
      break;
    }
    case Kind::Box:
    case Kind::Polygon: {
      const std::size_t n = s.points.size();
      Vec centroid = Vec::Zero();
      for (const Vec& p : s.points) centroid += p / static_cast<double>(n);
      places.push_back({"centre", centroid, unit(2 * M_PI * u(rng))});
      for (std::size_t k = 0; k < n; ++k) {
        const Vec& prev = s.points[(k + n - 1) % n];
        const Vec& a = s.points[k];
        const Vec& b = s.points[(k + 1) % n];
        const Vec face = edgeNormal(a, b);
        places.push_back({"corner", a, (edgeNormal(prev, a) + face).normalized()});
        places.push_back({"face", a + 0.5 * (b - a), face});
        places.push_back({"face", a + u(rng) * (b - a), face});
        places.push_back({"face by a corner", a + 1e-7 * (b - a), face});
      }
      break;
    }
    case Kind::Capsule: {
      const Vec& a = s.points[0];
      const Vec& b = s.points[1];
      const Vec side = edgeNormal(a, b);
      const Vec axis = (b - a).normalized();
      places.push_back({"core", a + 0.5 * (b - a), side});
      places.push_back({"core end", a, -axis});
      places.push_back({"side", a + u(rng) * (b - a) + s.radius * side, side});
      places.push_back({"side", a + 0.5 * (b - a) - s.radius * side, -side});
      places.push_back({"seam of side and cap", b + s.radius * side, side});
      const double angle = std::atan2(-axis.y(), -axis.x()) + (u(rng) - 0.5) * M_PI;
      places.push_back({"cap", a + s.radius * unit(angle), unit(angle)});
      places.push_back({"cap tip", b + s.radius * axis, axis});
      break;
    }
    case Kind::Disc: {
      const Vec& c = s.points[0];
      places.push_back({"centre", c, unit(2 * M_PI * u(rng))});
      for (double degrees : {0.0, 30.0, 60.0, 90.0, 180.0}) {  // from the top
        const Vec n = unit(M_PI / 2 - degrees * M_PI / 180.0);
        places.push_back({"surface", c + s.radius * n, n});
      }
      const Vec n = unit(2 * M_PI * u(rng));
      places.push_back({"surface", c + s.radius * n, n});
      break;
    }
  }
  return places;
}

// ---- the generator --------------------------------------------------------

struct Case {
  std::string text;        // the scene file
  std::string description; // for a failure's message
  double depth = 0.0;      // how far the particle starts inside its deepest collider (≤ 0: outside)
  int deepest = -1;        // that collider's index
  bool inWalls = false;    // the colliders are listed as "walls"
  double mass = 1.0, gravity = 9.81, energyScale = 1.0;
  std::vector<Shape> shapes;
  double particleRadius = 0.0;
  Vec start = Vec::Zero();
};

class Generator {
 public:
  explicit Generator(unsigned seed) : rng_(seed) {}

  Case next() {
    Case c;
    c.shapes.push_back(randomShape());
    const Shape shape = c.shapes[0];
    const std::vector<Place> places = placesOn(shape, rng_);
    // Corners (of boxes and polygons) half the time: they are where a
    // particle meets two faces at once.
    std::vector<std::size_t> corners;
    for (std::size_t k = 0; k < places.size(); ++k)
      if (std::string(places[k].what) == "corner") corners.push_back(k);
    const Place& place = places[!corners.empty() && u() < 0.5 ? corners[pick(corners.size())] : pick(places.size())];
    // Offsets along the outward direction, as fractions of the collider's
    // size: exactly on, round-off either way, a hair outside, inside by more
    // than the reader's rounding; or a few 10⁻¹⁰ m either way, within the
    // contact pass's slop of 10⁻⁹ m (touching).
    static const double offsets[] = {0.0, 0.0, 0.0, 1e-15, -1e-15, 1e-12, -1e-12, 1e-9, 1e-6, 1e-3, -1e-3, -0.05};
    static const double withinSlop[] = {5e-10, 2e-10, -2e-10};
    const double offset = u() < 0.25 ? withinSlop[pick(std::size(withinSlop))]
                                     : offsets[pick(std::size(offsets))] * shape.size;
    static const double radii[] = {0.0, 0.0, 0.0, 0.01, 0.1};
    c.particleRadius = radii[pick(std::size(radii))];
    const Vec x = place.point + (offset + c.particleRadius) * place.outward;
    c.start = x;

    Vec v = Vec::Zero();
    const char* motion = "at rest";
    if (u() < 0.5) {
      static const double speeds[] = {0.01, 0.3, 3.0, 30.0};
      v = speeds[pick(std::size(speeds))] * unit(2 * M_PI * u());
      motion = "moving";
    } else if (u() < 0.3) {
      v = 2.0 * Vec(-place.outward.y(), place.outward.x());
      motion = "sliding";
    }
    static const double gravities[] = {9.81, 9.81, 9.81, 0.0, 100.0};
    c.gravity = gravities[pick(std::size(gravities))];
    const Vec g = u() < 0.7 ? Vec(0.0, -c.gravity) : Vec(c.gravity * unit(2 * M_PI * u()));
    static const double masses[] = {1.0, 0.001, 50.0};
    c.mass = masses[pick(std::size(masses))];
    static const double dts[] = {0.001, 0.005, 0.01};

    const bool asWall = shapeIsBox(c.shapes) && u() < 0.3;
    Json particle = {{"position", toJson(x)}, {"mass", c.mass}, {"velocity", toJson(v)}};
    if (c.particleRadius > 0.0) particle["radius"] = c.particleRadius;
    Json colliders = Json::array();
    for (const Shape& s : c.shapes) colliders.push_back(colliderJson(s, asWall));
    Json scene = {{"name", "fuzz"},
                  {"dt", dts[pick(std::size(dts))]},
                  {"particles", Json::array({particle})},
                  {"forces", Json::array({Json{{"type", "gravity"}, {"acceleration", toJson(g)}}})}};
    scene[asWall ? "walls" : "colliders"] = colliders;
    c.inWalls = asWall;
    c.text = scene.dump();

    for (std::size_t k = 0; k < c.shapes.size(); ++k) {
      const double depth = -(signedDistance(c.shapes[k], x) - c.particleRadius);
      if (c.deepest < 0 || depth > c.depth) {
        c.depth = depth;
        c.deepest = static_cast<int>(k);
      }
    }
    c.energyScale = c.mass * (c.gravity * shape.size + 0.5 * v.squaredNorm()) + 1e-300;
    char text[400];
    std::snprintf(text, sizeof text, "%s %s (μ %g, e %g), particle r %g %s, offset %g, g %g%s", motion, place.what,
                  shape.friction, shape.restitution, c.particleRadius, kindName(shape.kind), offset, c.gravity,
                  asWall ? ", as walls" : "");
    c.description = text;
    return c;
  }

 private:
  double u() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }
  std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }

  static bool shapeIsBox(const std::vector<Shape>& shapes) {
    return std::all_of(shapes.begin(), shapes.end(), [](const Shape& s) { return s.kind == Kind::Box; });
  }

  void material(Shape& s) {
    static const double restitutions[] = {0.0, 0.5, 1.0};
    static const double frictions[] = {0.0, 0.0, 0.3, 2.0};
    s.restitution = restitutions[pick(std::size(restitutions))];
    s.friction = frictions[pick(std::size(frictions))];
  }

  Shape randomShape() {
    Shape s;
    s.kind = static_cast<Kind>(pick(5));
    const Vec centre(4.0 * u() - 2.0, 4.0 * u() - 2.0);
    s.size = std::exp(std::log(0.05) + u() * std::log(40.0));  // 0.05 … 2
    const double turn = 2 * M_PI * u();
    switch (s.kind) {
      case Kind::HalfPlane:
        s.normal = u() < 0.5 ? Vec(0.0, 1.0) : unit(turn);
        s.points = {centre};
        break;
      case Kind::Box: {
        const Vec half(0.5 * s.size, (0.1 + 0.4 * u()) * s.size);
        s.points = {centre - half, {centre.x() + half.x(), centre.y() - half.y()}, centre + half,
                    {centre.x() - half.x(), centre.y() + half.y()}};
        break;
      }
      case Kind::Polygon: {  // a triangle (often with a 45° slope) or a random convex n-gon
        const int n = u() < 0.5 ? 3 : 3 + static_cast<int>(pick(5));
        if (n == 3 && u() < 0.5) {
          s.points = {centre + Vec(-0.5, 0.0) * s.size, centre + Vec(0.5, 0.0) * s.size,
                      centre + Vec(0.0, 0.5) * s.size};
        } else {
          std::vector<double> angles;
          for (int k = 0; k < n; ++k) angles.push_back(turn + 2 * M_PI * (k + 0.8 * u()) / n);
          for (double a : angles) s.points.push_back(centre + 0.5 * s.size * unit(a));
        }
        break;
      }
      case Kind::Capsule:
        s.radius = (0.02 + 0.3 * u()) * s.size;
        s.points = {centre - 0.5 * s.size * unit(turn), centre + 0.5 * s.size * unit(turn)};
        break;
      case Kind::Disc:
        s.radius = 0.5 * s.size;
        s.points = {centre};
        break;
    }
    material(s);
    return s;
  }

  std::mt19937 rng_;
};

// ---- running one case -----------------------------------------------------

// The reader refuses a particle deeper inside a collider than 10⁻⁶ of its
// distance from the origin (at least 10⁻⁶); cases between clearly outside and
// clearly inside may go either way.
double rounding(const Case& c) {
  const Json doc = Json::parse(c.text);
  const Json& p = doc["particles"][0]["position"];
  return 1e-6 * std::max(1.0, std::hypot(p[0].get<double>(), p[1].get<double>()));
}

struct Worst {
  double share = -1e300;  // largest (E − E(0)) / the bound seen
  std::string where;
};

// Runs the case under one integrator; false (with a failure recorded) if any
// check fails.
bool runUnder(const Case& c, const particles::IntegratorInfo& info, int steps, Worst& worst) {
  scenes::Scene scene = scenes::readScene(c.text, "fuzz");
  particles::ParticleSystem& s = *scene.system;
  auto integrator = particles::makeIntegrator(info.name, scene.integratorSettings);
  const double e0 = s.totalEnergy();
  const bool euler = std::string(info.name) == "euler";
  double fastest = s.velocity(0).norm();
  for (int k = 1; k <= steps; ++k) {
    const particles::StepStats stats = s.step(*integrator, scene.dt);
    const double t = k * scene.dt;
    if (stats.failure != particles::StepFailure::None) {
      ADD_FAILURE() << info.name << ": step " << k << " failed (" << particles::stepFailureName(stats.failure) << ")";
      return false;
    }
    if (!s.finite()) {
      ADD_FAILURE() << info.name << ": non-finite state at step " << k;
      return false;
    }
    fastest = std::max(fastest, s.velocity(0).norm());
    const double drift = euler ? 0.5 * c.mass * c.gravity * c.gravity * scene.dt * t : 0.0;
    const double bounce = c.mass * c.gravity * (fastest + c.gravity * scene.dt) * scene.dt;
    const double bound = drift + bounce + 1e-6 * c.energyScale;
    const double share = (s.totalEnergy() - e0) / bound;
    if (share > worst.share) {
      worst.share = share;
      worst.where = c.description + ", step " + std::to_string(k);
    }
    if (share > 1.0) {
      ADD_FAILURE() << info.name << ": energy " << e0 << " → " << s.totalEnergy() << " J at step " << k
                    << ", beyond the bound of " << bound << " J";
      return false;
    }
  }
  const Vec x = s.position(0);
  for (std::size_t k = 0; k < c.shapes.size(); ++k) {
    const double depth = -(signedDistance(c.shapes[k], x) - c.particleRadius);
    if (depth > 1e-6 * std::max(1.0, x.norm())) {
      ADD_FAILURE() << info.name << ": the particle ends " << depth << " inside collider " << k;
      return false;
    }
  }
  return true;
}

TEST(ColliderFuzz, EveryPlacementIsRefusedByNameOrRunsFiniteWithoutGainingEnergy) {
  Generator generator(20261204);
  const int cases = 600, steps = 60;
  int refused = 0, ran = 0;
  std::map<std::string, Worst> worst;  // per integrator
  for (int n = 0; n < cases; ++n) {
    const Case c = generator.next();
    SCOPED_TRACE("case " + std::to_string(n) + ": " + c.description + "\n" + c.text);
    bool loaded = true;
    try {
      scenes::readScene(c.text, "fuzz");
    } catch (const scenes::SceneFileError& e) {
      loaded = false;
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_EQ(message.rfind("fuzz: $.particles[0]: the particle starts inside ", 0), 0u) << message;
      EXPECT_GT(c.depth, 0.0) << "refused a particle outside every collider: " << message;
      const std::string list = c.inWalls ? "walls[" : "colliders[";
      const std::size_t at = message.find(list);
      ASSERT_NE(at, std::string::npos) << message;
      const int named = std::atoi(message.c_str() + at + list.size());
      ASSERT_TRUE(named >= 0 && named < static_cast<int>(c.shapes.size())) << message;
      EXPECT_GT(-(signedDistance(c.shapes[named], c.start) - c.particleRadius), 0.0)
          << "named a collider the particle is not inside: " << message;
    }
    if (loaded) {
      EXPECT_LE(c.depth, rounding(c)) << "loaded a particle " << c.depth << " inside collider " << c.deepest;
      ++ran;
      for (const particles::IntegratorInfo& info : particles::integratorTable())
        if (!runUnder(c, info, steps, worst[info.name])) break;
    } else {
      ++refused;
    }
    if (HasFailure()) return;
  }
  std::printf("[ fuzz     ] %d placements: %d refused at load, %d run under %zu integrators for %d steps\n", cases,
              refused, ran, particles::integratorTable().size(), steps);
  for (const auto& [name, w] : worst)
    std::printf("[ fuzz     ] %-16s largest energy gain %.2f of the bound (%s)\n", name.c_str(), w.share,
                w.where.c_str());
  EXPECT_GT(refused, cases / 10);
  EXPECT_GT(ran, cases / 2);
}

// The hand-made cases: each starts at rest or falls a little onto a surface
// it then leaves; after 1 s the particle must be clear of the collider (by
// `clear`), and its energy within the bound above of the start and no lower
// than the start less the landing's loss (the bounces at e = 0.5 that follow
// take all of its normal energy ½ m v_n²) and the scheme's
// own loss (½ m |g|² dt t for symplectic and implicit Euler and xpbd, a
// symplectic Euler per substep) and 10⁻³ of the energy.
struct SlideOff {
  const char* name;
  const char* text;
  double landingLoss;  // J, at most
  double clear;        // m
};

TEST(ColliderFuzz, FrictionlessParticlesSlideOffATrianglesSlopeAndADiscWithTheirEnergyKept) {
  const double g = 9.81, dt = 0.005;
  const double vn = std::sqrt(2 * g * 0.05) * std::sqrt(0.5);  // landing on the 45° slope after a 5 cm fall
  const SlideOff cases[] = {
      {"dropped on a triangle's slope",
       R"({"name": "near-poly-slope", "dt": 0.005, "particles": [{"position": [0.5, 0.55], "mass": 1}],
           "forces": [{"type": "gravity", "acceleration": [0, -9.81]}],
           "colliders": [{"type": "polygon", "vertices": [[-1, 0], [1, 0], [0, 1]]}]})",
       0.5 * vn * vn, 0.3},
      {"at rest on a disc, 30° from its top",
       R"({"name": "rest-on-disc-60deg", "dt": 0.005,
           "particles": [{"position": [0.5000005000000001, 0.8660262698098423], "mass": 1}],
           "forces": [{"type": "gravity", "acceleration": [0, -9.81]}],
           "colliders": [{"type": "disc", "centre": [0, 0], "radius": 1}]})",
       0.0, 0.3},
  };
  for (const SlideOff& c : cases)
    for (const particles::IntegratorInfo& info : particles::integratorTable()) {
      SCOPED_TRACE(std::string(c.name) + " under " + info.name);
      scenes::Scene scene = scenes::readScene(c.text, c.name);
      particles::ParticleSystem& s = *scene.system;
      auto integrator = particles::makeIntegrator(info.name, scene.integratorSettings);
      const double e0 = s.totalEnergy();
      double fastest = 0.0;
      const int steps = 200;
      for (int k = 0; k < steps; ++k) {
        ASSERT_EQ(s.step(*integrator, dt).failure, particles::StepFailure::None);
        fastest = std::max(fastest, s.velocity(0).norm());
      }
      const double t = steps * dt, own = 0.5 * g * g * dt * t;
      const double gain = s.totalEnergy() - e0;
      std::printf("[ slide    ] %-36s %-16s clear by %.3f m, energy %+.4f J\n", c.name, info.name,
                  s.colliders()[0].distance(s.position(0)).distance, gain);
      EXPECT_GT(s.colliders()[0].distance(s.position(0)).distance, c.clear);
      const bool euler = std::string(info.name) == "euler";
      EXPECT_LE(gain, (euler ? own : 0.0) + g * (fastest + g * dt) * dt + 1e-6 * e0);
      EXPECT_GE(gain, -c.landingLoss - own - 1e-3 * e0);
    }
}

}  // namespace
