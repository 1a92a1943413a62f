// Reading a scene from a JSON scene file (format: demos/scenes/FORMAT.md).
#include "scene_file/scene_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <cerrno>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "join_names.h"
#include "particles/cancel.h"
#include "particles/check.h"
#include "particles/integrator.h"
#include "particles/solver_names.h"
#include "particles/forces/face_area.h"
#include "particles/tearing.h"
#include "scene_file/codecs.h"
#include "scene_file/json_parse.h"
#include "scene_limits.h"
#include "starting_overlap.h"

namespace scenes {

namespace {

// Runs build(); an engine object refusing its values (std::invalid_argument)
// becomes a SceneFileError at node's path.
template <class Build>
auto guarded(const JsonNode& node, Build&& build) {
  try {
    return build();
  } catch (const std::invalid_argument& e) {
    node.reject(e.what());
  }
}

// The table entry whose type matches the node's "type", or an error listing the types.
template <class Codec>
const Codec& codecFor(const JsonNode& node, const std::vector<Codec>& table, const char* kind) {
  const JsonNode type = node["type"];
  const std::string name = type.present() ? type.text() : "";
  for (const Codec& codec : table)
    if (name == codec.type) return codec;
  type.expected(std::string("a ") + kind + " type (" +
                joinNames(table, [](const Codec& codec) { return std::string(codec.type); }) + ")");
}

void readIntegrator(const JsonNode& node, Scene& scene) {
  if (!node.present()) return;
  if (const particles::IntegratorInfo* info = particles::findIntegrator(node.text())) {
    scene.integrator = info->name;
    return;
  }
  node.expected("an integrator (" + particles::integratorNames() + ")");
}

void readIntegratorSettings(const JsonNode& node, particles::IntegratorSettings& s) {
  if (!node.present()) return;
  node.allowOnly({"tolerance", "substeps", "iterations", "lines"});
  // Each field is checked by the engine's own rules as it is read, so a
  // refusal (a tolerance below rounding) names the field's path.
  const auto read = [&](const char* key, auto value) {
    const JsonNode field = node[key];
    if (!field.present()) return;
    value(field);
    guarded(field, [&] { s.validate(); });
  };
  read("tolerance", [&](const JsonNode& field) { s.dopri5.tolerance = field.positive(); });
  const auto integer = [](const JsonNode& field, particles::IntRange range) { return field.integer(range.min, range.max); };
  read("substeps", [&](const JsonNode& field) { s.xpbd.substeps = integer(field, particles::XpbdSettings::substepRange); });
  read("iterations",
       [&](const JsonNode& field) { s.xpbd.iterations = integer(field, particles::XpbdSettings::iterationRange); });
  read("lines", [&](const JsonNode& field) { s.xpbd.lines = field.boolean(); });
}

void readView(const JsonNode& node, Scene& scene) {
  if (!node.present()) return;
  node.allowOnly({"min", "max"});
  scene.viewMin = node["min"].vec2();
  scene.viewMax = node["max"].vec2();
  if (!(scene.viewMax.array() > scene.viewMin.array()).all()) node["max"].expected("a point above and right of min");
}

void readSolver(const JsonNode& node, particles::SolverSettings& s) {
  if (!node.present()) return;
  node.allowOnly({"tolerance", "maxIterations", "maxCgWork", "stiffness", "damping", "warmStart", "method", "preconditioner"});
  if (node["tolerance"].present()) s.tolerance = node["tolerance"].positive();
  if (node["maxIterations"].present()) s.maxIterations = node["maxIterations"].integer(0, 1000000);
  if (node["maxCgWork"].present()) s.maxCgWork = node["maxCgWork"].nonNegative();
  if (node["stiffness"].present()) s.stiffness = node["stiffness"].nonNegative();
  if (node["damping"].present()) s.damping = node["damping"].nonNegative();
  s.warmStart = node["warmStart"].boolean(s.warmStart);
  const JsonNode method = node["method"];
  if (method.present()) {
    const std::optional<particles::SolveMethod> value = particles::solveMethodNamed(method.text());
    if (!value) method.expected(particles::validSolveMethodNames());
    s.method = *value;
  }
  const JsonNode preconditioner = node["preconditioner"];
  if (preconditioner.present()) {
    const std::optional<particles::Preconditioner> value = particles::preconditionerNamed(preconditioner.text());
    if (!value) preconditioner.expected(particles::validPreconditionerNames());
    s.preconditioner = *value;
  }
}

void readTearing(const JsonNode& node, particles::TearSettings& tearing) {
  if (!node.present()) return;
  node.allowOnly({"strain"});
  tearing.strain = node["strain"].nonNegative();
}

void readParticle(const JsonNode& node, particles::ParticleSystem& s) {
  node.allowOnly({"position", "velocity", "mass", "pinned", "radius"});
  const Eigen::Vector2d x = node["position"].vec2();
  const JsonNode velocity = node["velocity"];
  const Eigen::Vector2d v = velocity.present() ? velocity.vec2() : Eigen::Vector2d::Zero();
  const int i = s.addParticle(x, node["mass"].positive(), v);
  if (node["pinned"].boolean(false)) s.setPinned(i, true);
  if (node["radius"].present()) s.setCollidable(i, node["radius"].positive());
}

// A collider whose numbers the contact arithmetic cannot hold is refused: it
// multiplies up to four lengths (the impact test's discriminant (m·d)² −
// |d|² (|m|² − R²)) and divides by an edge's length, so every coordinate and
// radius is at most kColliderReach in magnitude (a product of four stays
// finite) and every side, edge, segment and radius at least 1/kColliderReach
// long (a product of four stays a normal number, and an edge's normal e/|e|
// is defined), and longer than the rounding of its coordinates (1e-12 of
// their magnitude, as the contact code's round-off). A floor with corners at
// ±1e200 let particles fall through it; a box of side 5e-324 gave NaN.
constexpr double kColliderReach = 1e75;

void refuseUnrepresentable(const JsonNode& node, const particles::Collider& c) {
  const std::string kind = particles::colliderName(c.shape);
  double largest = c.radius;
  for (const Eigen::Vector2d& p : c.points) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  if (largest > kColliderReach)
    node.reject(kind + ": a coordinate or radius of " + particles::formatValue(largest) + " is beyond " +
                particles::formatValue(kColliderReach) + ", which the contact arithmetic cannot hold (it multiplies up "
                "to four lengths); bring the collider nearer the origin");
  // A length of exactly 0 (a capsule's ends or a polygon's vertices that
  // coincide) is left to the collider's own check, which names it so.
  const auto requireLength = [&](double length, const std::string& what) {
    const double rounding = 1e-12 * (1.0 + largest);
    if (length == 0.0) return;
    if (!(length >= 1.0 / kColliderReach))
      node.reject(kind + ": " + what + " of " + particles::formatValue(length) + " is shorter than " +
                  particles::formatValue(1.0 / kColliderReach) + ", which the contact arithmetic cannot hold");
    if (!(length > rounding))
      node.reject(kind + ": " + what + " of " + particles::formatValue(length) +
                  " is within the rounding of its coordinates (" + particles::formatValue(rounding) +
                  " at this distance from the origin)");
  };
  if (c.radius > 0.0 || c.shape == particles::ColliderShape::Disc) requireLength(c.radius, "a radius");
  const std::size_t n = c.points.size();
  // hypot: |b − a| without the underflow of squaring a side of 5e-324.
  const auto length = [](const Eigen::Vector2d& e) { return std::hypot(e.x(), e.y()); };
  if (n == 2) requireLength(length(c.points[1] - c.points[0]), "a segment");
  if (n >= 3)
    for (std::size_t k = 0; k < n; ++k) requireLength(length(c.points[(k + 1) % n] - c.points[k]), "a side");
}

// A collider by its "type"; "walls" holds boxes without one (the older spelling).
particles::Collider readColliderOfType(const JsonNode& node, bool box) {
  if (box)
    for (const ColliderCodec& codec : colliderCodecs())
      if (codec.shape == particles::ColliderShape::Box) return codec.read(node);
  const JsonNode type = node["type"];
  const std::string name = type.present() ? type.text() : "";
  for (const ColliderCodec& codec : colliderCodecs())
    if (name == particles::colliderName(codec.shape)) return codec.read(node);
  type.expected("a collider type (" + joinNames(particles::colliderKinds()) + ")");
}

particles::Collider readCollider(const JsonNode& node, bool box) {
  const particles::Collider collider = readColliderOfType(node, box);
  refuseUnrepresentable(node, collider);
  return collider;
}

void readCollisionEdges(const JsonNode& list, particles::ParticleSystem& s) {
  for (std::size_t k = 0; k < list.arraySize(); ++k) {
    particles::throwIfCancelled();
    const JsonNode node = list[k];
    const std::vector<int> p = node.particles(2, s.size());
    guarded(node, [&] { s.addCollisionEdge(p[0], p[1]); });
  }
}

// A particle that starts inside a collider (starting_overlap.h) is refused
// at the particle's path, naming the collider by its list and index.
void refuseParticlesInsideColliders(const JsonNode& root, const particles::ParticleSystem& s) {
  const std::optional<StartingOverlap> overlap = firstStartingOverlap(s, true);
  if (!overlap) return;
  std::vector<std::pair<const char*, std::size_t>> paths;  // each collider's list and index, in order
  for (const char* list : {"walls", "colliders"})
    for (std::size_t k = 0; k < root[list].arraySize(); ++k) paths.emplace_back(list, k);
  const auto& [list, index] = paths.at(overlap->collider);
  root["particles"][static_cast<std::size_t>(overlap->particle)].reject(
      "the particle starts inside " + std::string(list) + "[" + std::to_string(index) + "] (by " +
      particles::formatValue(overlap->depth) + "): a contact cannot push it out without adding energy");
}

// An array of at most limit elements (absent: none).
void requireCount(const JsonNode& node, const char* what, long long limit) {
  const std::size_t count = node.arraySize();
  if (count > static_cast<std::size_t>(limit))
    node.reject(std::to_string(count) + " " + what + " exceed the limit of " + std::to_string(limit));
}

// The surface a file's face-area forces describe: their faces of four
// corners are the scene's faces (which the demo shades), their sides the
// wind's edges when no wind names its own, and collision edges on them make
// the face edges collide (Scene::edgeContacts), as the built-in cloth's.
void takeSurface(Scene& scene) {
  const particles::ParticleSystem& s = *scene.system;
  for (const auto& force : s.forceObjects())
    if (const auto* area = dynamic_cast<const particles::FaceAreaForce*>(force.get()))
      for (const particles::AreaFace& face : area->faces())
        if (face.ring.size() == 4) scene.faces.push_back({face.ring[0], face.ring[1], face.ring[2], face.ring[3]});
  if (scene.faces.empty()) return;
  scene.windEdges = faceEdges(scene);
  scene.edgeContacts = !s.collisionEdges().empty();
}

Scene readDocument(const JsonNode& root, const std::string& source) {
  root.allowOnly({"name", "integrator", "integratorSettings", "dt", "time", "view", "solver", "particleRestitution",
                  "particleFriction", "tearing", "particles", "forces", "constraints", "walls", "colliders",
                  "collisionEdges"});
  Scene scene;
  scene.name = root["name"].present() ? root["name"].text() : source;
  readIntegrator(root["integrator"], scene);
  readIntegratorSettings(root["integratorSettings"], scene.integratorSettings);
  if (root["dt"].present()) scene.dt = root["dt"].positive();
  readView(root["view"], scene);
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;
  readSolver(root["solver"], s.solver().settings);
  if (root["particleRestitution"].present())
    s.contactSettings().particleRestitution = root["particleRestitution"].inRange(0.0, 1.0);
  if (root["particleFriction"].present())
    s.contactSettings().particleFriction = root["particleFriction"].nonNegative();
  readTearing(root["tearing"], s.tearing());

  const JsonNode particleList = root["particles"];
  if (!particleList.present()) particleList.expected("an array of particles");
  requireCount(particleList, "particles", SceneLimits::particles);
  requireCount(root["forces"], "forces", SceneLimits::forces);
  requireCount(root["constraints"], "constraints", SceneLimits::constraints);
  requireCount(root["walls"], "walls", SceneLimits::walls);
  requireCount(root["colliders"], "colliders", SceneLimits::walls);
  requireCount(root["collisionEdges"], "collisionEdges", SceneLimits::forces);
  // Each list is read element by element with the cancel flag watched
  // (particles/cancel.h): a signal stops the load of a large file.
  for (std::size_t k = 0; k < particleList.arraySize(); ++k) {
    particles::throwIfCancelled();
    const JsonNode node = particleList[k];
    guarded(node, [&] { readParticle(node, s); });
  }
  const int n = s.size();
  for (std::size_t k = 0, count = root["forces"].arraySize(); k < count; ++k) {
    particles::throwIfCancelled();
    const JsonNode node = root["forces"][k];
    const ForceCodec& codec = codecFor(node, forceCodecs(), "force");
    guarded(node, [&] { s.addForce(codec.read(node, n)); });
  }
  std::vector<long long> constraintsOn(n, 0);  // constraints per particle
  for (std::size_t k = 0, count = root["constraints"].arraySize(); k < count; ++k) {
    particles::throwIfCancelled();
    const JsonNode node = root["constraints"][k];
    const ConstraintCodec& codec = codecFor(node, constraintCodecs(), "constraint");
    std::unique_ptr<particles::Constraint> constraint = guarded(node, [&] { return codec.read(node, n); });
    for (int i : constraint->particles())
      if (++constraintsOn[i] > SceneLimits::constraintsPerParticle)
        node.reject("particle " + std::to_string(i) + " has more than the limit of " +
                    std::to_string(SceneLimits::constraintsPerParticle) + " constraints");
    guarded(node, [&] { s.addConstraint(std::move(constraint)); });
  }
  for (const char* list : {"walls", "colliders"})
    for (std::size_t k = 0, count = root[list].arraySize(); k < count; ++k) {
      particles::throwIfCancelled();
      const JsonNode node = root[list][k];
      const particles::Collider collider = readCollider(node, list == std::string("walls"));
      guarded(node, [&] { s.addCollider(collider); });
    }
  readCollisionEdges(root["collisionEdges"], s);
  refuseParticlesInsideColliders(root, s);
  // A saved state's clock; the forces that follow it (gusts) take it up.
  if (root["time"].present()) s.restore({s.positions(), s.velocities(), root["time"].nonNegative()});
  takeSurface(scene);
  return scene;
}

// The bare word (NaN, Infinity, -inf, ...) at which parsing stopped, with its
// sign, as [start, start + length) of text; length 0 when there is none.
std::pair<std::size_t, std::size_t> nonNumberAt(const std::string& text, std::size_t byte) {
  const auto alpha = [&](std::size_t k) { return std::isalpha(static_cast<unsigned char>(text[k])) != 0; };
  std::size_t start = std::min(byte, text.size()), end = start;
  while (start > 0 && alpha(start - 1)) --start;
  while (end < text.size() && alpha(end)) ++end;
  std::string word = text.substr(start, end - start);
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (word != "nan" && word != "inf" && word != "infinity") return {start, 0};
  if (start > 0 && (text[start - 1] == '-' || text[start - 1] == '+')) --start;
  return {start, end - start};
}

Scene readText(const std::string& text, const std::string& source, bool locateNonNumbers) {
  Json document;
  try {
    document = parseJson(text);
  } catch (const JsonSyntaxError& e) {
    const auto [start, length] = nonNumberAt(text, e.byte);
    if (locateNonNumbers && length > 0) {
      // JSON cannot hold NaN or Infinity. Read the file again with the word as
      // a string, so that the error names the JSON path of the value.
      std::string quoted = text;
      quoted.replace(start, length, "\"" + text.substr(start, length) + " (not a JSON number)\"");
      readText(quoted, source, false);
    }
    throw SceneFileError(source + ": $: expected valid JSON, got a " + e.what());
  } catch (const SceneFileError& e) {  // nested too deep, a duplicate key
    throw SceneFileError(source + ": " + e.what());
  }
  return readSceneDocument(document, source);
}

// Closes a file descriptor when it goes out of scope.
struct FileDescriptor {
  int fd;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

[[noreturn]] void cannotRead(const std::string& path, const std::string& why) {
  throw SceneFileError(path + ": cannot read the file (" + why + ")");
}

}  // namespace

Scene readScene(const std::string& text, const std::string& source) { return readText(text, source, true); }

Scene readSceneDocument(const Json& document, const std::string& source) {
  try {
    return readDocument(JsonNode(&document, "$"), source);
  } catch (const SceneFileError& e) {
    throw SceneFileError(source + ": " + e.what());
  }
}

Scene loadSceneFile(const std::string& path) {
  // Only a regular file, opened without blocking (a FIFO with no writer would
  // block open) and read up to the size limit (a device such as /dev/zero
  // never ends, and a file may grow while it is read).
  const FileDescriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0) cannotRead(path, std::strerror(errno));
  struct stat info {};
  if (::fstat(file.fd, &info) != 0) cannotRead(path, std::strerror(errno));
  if (!S_ISREG(info.st_mode))
    cannotRead(path, S_ISDIR(info.st_mode) ? "a directory, not a regular file" : "not a regular file");
  const std::size_t limit = SceneLimits::fileBytes;
  const auto tooLarge = [&] { cannotRead(path, "larger than the limit of " + std::to_string(limit) + " bytes"); };
  if (static_cast<std::uintmax_t>(info.st_size) > limit) tooLarge();
  std::string text(static_cast<std::size_t>(info.st_size) + 1, '\0');
  std::size_t size = 0;
  while (true) {
    if (size == text.size()) {
      if (size > limit) tooLarge();
      text.resize(std::min(2 * size, limit + 1));
    }
    const ssize_t got = ::read(file.fd, &text[size], text.size() - size);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) cannotRead(path, std::strerror(errno));
    if (got == 0) break;
    size += static_cast<std::size_t>(got);
  }
  if (size > limit) tooLarge();
  text.resize(size);
  return readScene(text, path);
}

}  // namespace scenes
