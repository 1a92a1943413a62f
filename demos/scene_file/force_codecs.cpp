// Scene-file readers and writers of every force type (format: demos/scenes/FORMAT.md).
#include "particles/forces/angular_spring.h"
#include "particles/forces/drag.h"
#include "particles/forces/face_area.h"
#include "particles/forces/gravity.h"
#include "particles/forces/mouse_spring.h"
#include "particles/forces/pressure.h"
#include "particles/forces/spring.h"
#include "particles/forces/wind.h"
#include "scene_file/codecs.h"
#include "scene_limits.h"

namespace scenes {

namespace {
using particles::Force;

std::unique_ptr<Force> readGravity(const JsonNode& node, int) {
  node.allowOnly({"type", "acceleration"});
  return std::make_unique<particles::GravityForce>(node["acceleration"].vec2());
}
Json writeGravity(const Force& force) {
  const auto& f = dynamic_cast<const particles::GravityForce&>(force);
  return {{"type", f.type()}, {"acceleration", toJson(f.acceleration())}};
}

std::unique_ptr<Force> readDrag(const JsonNode& node, int) {
  node.allowOnly({"type", "damping"});
  return std::make_unique<particles::DragForce>(node["damping"].nonNegative());
}
Json writeDrag(const Force& force) {
  const auto& f = dynamic_cast<const particles::DragForce&>(force);
  return {{"type", f.type()}, {"damping", f.damping()}};
}

// "torn": true marks a spring (or angle spring) whose link broke: it is read
// torn (Force::dropLinks on its own link) and written only when torn.
void readTorn(const JsonNode& node, Force& force, int i, int j) {
  if (node["torn"].boolean(false)) force.dropLinks(particles::LinkSet({{i, j}}));
}

std::unique_ptr<Force> readSpring(const JsonNode& node, int n) {
  node.allowOnly({"type", "particles", "restLength", "stiffness", "damping", "torn"});
  const std::vector<int> p = node["particles"].particles(2, n);
  auto spring = std::make_unique<particles::SpringForce>(p[0], p[1], node["restLength"].positive(),
                                                         node["stiffness"].nonNegative(),
                                                         node["damping"].nonNegative());
  readTorn(node, *spring, p[0], p[1]);
  return spring;
}
Json writeSpring(const Force& force) {
  const auto& f = dynamic_cast<const particles::SpringForce&>(force);
  Json out = {{"type", f.type()},
              {"particles", {f.first(), f.second()}},
              {"restLength", f.restLength()},
              {"stiffness", f.stiffness()},
              {"damping", f.damping()}};
  if (!f.enabled()) out["torn"] = true;
  return out;
}

std::unique_ptr<Force> readAngularSpring(const JsonNode& node, int n) {
  node.allowOnly({"type", "particles", "restAngle", "stiffness", "damping", "torn"});
  const std::vector<int> p = node["particles"].particles(3, n);
  auto spring = std::make_unique<particles::AngularSpringForce>(p[0], p[1], p[2], node["restAngle"].number(),
                                                                node["stiffness"].nonNegative(),
                                                                node["damping"].nonNegative());
  readTorn(node, *spring, p[0], p[1]);
  return spring;
}
Json writeAngularSpring(const Force& force) {
  const auto& f = dynamic_cast<const particles::AngularSpringForce&>(force);
  Json out = {{"type", f.type()},
              {"particles", f.triple()},
              {"restAngle", f.restAngle()},
              {"stiffness", f.stiffness()},
              {"damping", f.damping()}};
  if (!f.enabled()) out["torn"] = true;
  return out;
}

std::unique_ptr<Force> readMouseSpring(const JsonNode& node, int n) {
  node.allowOnly({"type", "particle", "target", "stiffness", "damping"});
  return std::make_unique<particles::MouseSpringForce>(node["particle"].particle(n), node["target"].vec2(),
                                                       node["stiffness"].nonNegative(),
                                                       node["damping"].nonNegative());
}
Json writeMouseSpring(const Force& force) {
  const auto& f = dynamic_cast<const particles::MouseSpringForce&>(force);
  return {{"type", f.type()},
          {"particle", f.particle()},
          {"target", toJson(f.target())},
          {"stiffness", f.stiffness()},
          {"damping", f.damping()}};
}
std::unique_ptr<Force> readWind(const JsonNode& node, int n) {
  node.allowOnly({"type", "edges", "speed", "direction", "drag", "gust", "gustPeriod", "seed"});
  const JsonNode list = node["edges"];
  if (!list.present()) list.expected("an array of particle pairs [i, j]");
  if (list.arraySize() > static_cast<std::size_t>(SceneLimits::forces))
    list.reject(std::to_string(list.arraySize()) + " edges exceed the limit of " + std::to_string(SceneLimits::forces));
  std::vector<std::array<int, 2>> edges;
  for (std::size_t k = 0; k < list.arraySize(); ++k) {
    const std::vector<int> p = list[k].particles(2, n);
    edges.push_back({p[0], p[1]});
  }
  particles::WindSettings wind;
  wind.speed = node["speed"].nonNegative();
  wind.direction = node["direction"].number();
  wind.drag = node["drag"].nonNegative();
  if (node["gust"].present()) wind.gust = node["gust"].inRange(0.0, 1.0);
  if (node["gustPeriod"].present()) wind.gustPeriod = node["gustPeriod"].positive();
  if (node["seed"].present()) wind.seed = node["seed"].integer(0, 2147483647);
  return std::make_unique<particles::WindForce>(std::move(edges), wind);
}
Json writeWind(const Force& force) {
  const auto& f = dynamic_cast<const particles::WindForce&>(force);
  const particles::WindSettings& w = f.settings();
  Json edges = Json::array();
  for (const auto& [i, j] : f.edges()) edges.push_back({i, j});
  return {{"type", f.type()}, {"speed", w.speed},           {"direction", w.direction},
          {"drag", w.drag},   {"gust", w.gust},             {"gustPeriod", w.gustPeriod},
          {"seed", w.seed},   {"edges", std::move(edges)}};
}

constexpr std::size_t kMaxRing = 100000;  // corners of one ring (at most the particles of a scene)

std::unique_ptr<Force> readFaceArea(const JsonNode& node, int n) {
  node.allowOnly({"type", "faces", "stiffness", "floor"});
  const JsonNode list = node["faces"];
  if (!list.present()) list.expected("an array of faces {\"particles\": [...], \"restArea\": A0}");
  if (list.arraySize() > static_cast<std::size_t>(SceneLimits::forces))
    list.reject(std::to_string(list.arraySize()) + " faces exceed the limit of " + std::to_string(SceneLimits::forces));
  std::vector<particles::AreaFace> faces;
  for (std::size_t k = 0; k < list.arraySize(); ++k) {
    const JsonNode face = list[k];
    face.allowOnly({"particles", "restArea"});
    faces.push_back({face["particles"].ring(n, kMaxRing), face["restArea"].positive()});
  }
  const double stiffness = node["stiffness"].nonNegative(), floor = node["floor"].inRange(0.0, 1.0);
  return std::make_unique<particles::FaceAreaForce>(std::move(faces), stiffness, floor);
}
Json writeFaceArea(const Force& force) {
  const auto& f = dynamic_cast<const particles::FaceAreaForce&>(force);
  Json faces = Json::array();
  for (const particles::AreaFace& face : f.faces()) faces.push_back({{"particles", face.ring}, {"restArea", face.restArea}});
  return {{"type", f.type()}, {"stiffness", f.stiffness()}, {"floor", f.floor()}, {"faces", std::move(faces)}};
}

std::unique_ptr<Force> readPressure(const JsonNode& node, int n) {
  node.allowOnly({"type", "particles", "restArea", "pressure", "torn"});
  const std::vector<int> ring = node["particles"].ring(n, kMaxRing);
  auto force = std::make_unique<particles::PressureForce>(ring, node["restArea"].positive(),
                                                          node["pressure"].nonNegative());
  readTorn(node, *force, ring[0], ring[1]);
  return force;
}
Json writePressure(const Force& force) {
  const auto& f = dynamic_cast<const particles::PressureForce&>(force);
  Json out = {{"type", f.type()}, {"particles", f.ring()}, {"restArea", f.restArea()}, {"pressure", f.pressure()}};
  if (!f.enabled()) out["torn"] = true;
  return out;
}
}  // namespace

const std::vector<ForceCodec>& forceCodecs() {
  static const std::vector<ForceCodec> table = {
      {"gravity", readGravity, writeGravity},
      {"drag", readDrag, writeDrag},
      {"spring", readSpring, writeSpring},
      {"angular-spring", readAngularSpring, writeAngularSpring},
      {"mouse-spring", readMouseSpring, writeMouseSpring},
      {"wind", readWind, writeWind},
      {"face-area", readFaceArea, writeFaceArea},
      {"pressure", readPressure, writePressure},
  };
  return table;
}

}  // namespace scenes
