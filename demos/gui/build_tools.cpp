#include "build_tools.h"

#include <cmath>
#include <stdexcept>

#include "build_geometry.h"
#include "particles/forces/angular_spring.h"
#include "scene_file/codecs.h"

namespace demo {

namespace {
using scenes::toJson;

// The object's own fields first, then the tool's (stiffness, damping, ...).
Json withFields(Json object, const Json& fields) {
  for (const auto& [key, value] : fields.items()) object[key] = value;
  return object;
}

std::string addTo(ToolContext& c, const char* list, Json object) {
  const std::string type = object.value("type", std::string(list));
  c.selection = addObject(c.document, list, std::move(object));
  return "add " + type;
}

// Two different particles at a drag's ends (new ones where it starts or ends
// in empty space), for the objects between two particles.
std::pair<int, int> twoParticles(ToolContext& c, const std::vector<BuildPoint>& p, const char* what) {
  if (p[0].particle && p[0].particle == p[1].particle)
    throw std::invalid_argument(std::string(what) + " needs two different particles: drag from one to another");
  if ((p[1].at - p[0].at).norm() == 0.0)
    throw std::invalid_argument(std::string(what) + " needs its ends apart: drag from one point to another");
  const int a = particleAtPoint(c, p[0]);
  return {a, particleAtPoint(c, p[1])};
}

Json noFields() { return Json::object(); }
Json particleDefaults() { return {{"mass", 0.1}, {"radius", 0.0}, {"pinned", false}}; }
Json springDefaults() { return {{"stiffness", 50.0}, {"damping", 0.2}}; }
Json rodDefaults() { return {{"form", "squared"}}; }
Json angleDefaults() { return {{"stiffness", 0.2}, {"damping", 0.002}}; }
Json materialDefaults() { return {{"restitution", 0.5}, {"friction", 0.0}}; }
Json capsuleDefaults() { return {{"radius", 0.02}, {"restitution", 0.5}, {"friction", 0.0}}; }

// --- the tools' edits -----------------------------------------------------------

// A click selects what is under it; a drag from a particle moves it, from a
// collider moves the collider.
std::string selectOrMove(ToolContext& c, const std::vector<BuildPoint>& p) {
  const std::optional<ObjectRef> picked = pickObject(c.document, c.system, p[0].raw, c.pickRadius);
  const Eigen::Vector2d delta = p[1].at - p[0].at;
  if (!picked || (p[1].raw - p[0].raw).norm() < 0.25 * c.pickRadius) {  // a click that wobbles is a click
    c.selection = picked;
    return "";
  }
  c.selection = picked;
  if (picked->list == "particles") {
    moveParticle(c.document, static_cast<int>(picked->index), p[1].at);
    return "move " + picked->name();
  }
  if (picked->list == "colliders" || picked->list == "walls") {
    translateCollider(c.document, *picked, delta);
    return "move " + picked->name();
  }
  return "";
}

std::string deleteAt(ToolContext& c, const std::vector<BuildPoint>& p) {
  const std::optional<ObjectRef> picked = pickObject(c.document, c.system, p[0].raw, c.pickRadius);
  if (!picked) throw std::invalid_argument("nothing here to delete");
  deleteObject(c.document, *picked);
  c.selection.reset();
  return "delete " + picked->name();
}

std::string addParticleAt(ToolContext& c, const std::vector<BuildPoint>& p) {
  if (p[0].particle) {  // a click on a particle selects it
    c.selection = ObjectRef{"particles", static_cast<std::size_t>(*p[0].particle)};
    return "";
  }
  c.selection = ObjectRef{"particles", static_cast<std::size_t>(particleAtPoint(c, p[0]))};
  return "add particle";
}

std::string addSpring(ToolContext& c, const std::vector<BuildPoint>& p) {
  const auto [a, b] = twoParticles(c, p, "a spring");
  const double length = (particlePosition(c.document, a) - particlePosition(c.document, b)).norm();
  return addTo(c, "forces", withFields({{"type", "spring"}, {"particles", {a, b}}, {"restLength", length}}, c.fields));
}

std::string addRod(ToolContext& c, const std::vector<BuildPoint>& p) {
  const auto [a, b] = twoParticles(c, p, "a rod");
  const double length = (particlePosition(c.document, a) - particlePosition(c.document, b)).norm();
  return addTo(c, "constraints", withFields({{"type", "rod"}, {"particles", {a, b}}, {"length", length}}, c.fields));
}

// Three clicks: an arm's end, the vertex, the other arm's end. The rest angle
// is the angle drawn (the spring's own θ, particles/forces/angular_spring.h).
std::string addAngleSpring(ToolContext& c, const std::vector<BuildPoint>& p) {
  if ((p[0].particle && (p[0].particle == p[1].particle || p[0].particle == p[2].particle)) ||
      (p[1].particle && p[1].particle == p[2].particle))
    throw std::invalid_argument("an angle spring needs three different particles (an end, the vertex, an end)");
  const int a = particleAtPoint(c, p[0]), v = particleAtPoint(c, p[1]), b = particleAtPoint(c, p[2]);
  const Eigen::Vector2d zero = Eigen::Vector2d::Zero();
  const double angle = particles::angularSpringKernel(particlePosition(c.document, a), particlePosition(c.document, v),
                                                      particlePosition(c.document, b), zero, zero, zero)
                           .angle;
  return addTo(c, "forces",
               withFields({{"type", "angular-spring"}, {"particles", {a, v, b}}, {"restAngle", angle}}, c.fields));
}

// A drag from the wire's centre to the bead on it.
std::string addWire(ToolContext& c, const std::vector<BuildPoint>& p) {
  const double radius = (p[1].at - p[0].at).norm();
  if (radius == 0.0) throw std::invalid_argument("a wire needs a radius: drag from its centre to the bead");
  const int bead = particleAtPoint(c, p[1]);
  return addTo(c, "constraints",
               withFields({{"type", "circular-wire"}, {"particle", bead}, {"centre", toJson(p[0].at)}, {"radius", radius}},
                          c.fields));
}

// A drag from the particle along the line it slides on.
std::string addLine(ToolContext& c, const std::vector<BuildPoint>& p) {
  const Eigen::Vector2d along = p[1].at - p[0].at;
  if (along.norm() == 0.0) throw std::invalid_argument("a line needs a direction: drag from the particle along it");
  const int bead = particleAtPoint(c, p[0]);
  return addTo(c, "constraints",
               withFields({{"type", "line"},
                           {"particle", bead},
                           {"point", toJson(particlePosition(c.document, bead))},
                           {"angle", std::atan2(along.y(), along.x())}},
                          c.fields));
}

// A drag from a point of the surface outward, away from the solid side.
std::string addHalfPlane(ToolContext& c, const std::vector<BuildPoint>& p) {
  const Eigen::Vector2d normal = p[1].at - p[0].at;
  if (normal.norm() == 0.0) throw std::invalid_argument("a half-plane needs a normal: drag from its surface outward");
  return addTo(c, "colliders",
               withFields({{"type", "halfPlane"}, {"point", toJson(p[0].at)}, {"normal", toJson(normal)}}, c.fields));
}

std::string addBox(ToolContext& c, const std::vector<BuildPoint>& p) {
  const Eigen::Vector2d lo = p[0].at.cwiseMin(p[1].at), hi = p[0].at.cwiseMax(p[1].at);
  if (!((hi - lo).array() > 0.0).all()) throw std::invalid_argument("a box needs a width and a height: drag corner to corner");
  return addTo(c, "colliders", withFields({{"type", "box"}, {"min", toJson(lo)}, {"max", toJson(hi)}}, c.fields));
}

std::string addPolygon(ToolContext& c, const std::vector<BuildPoint>& p) {
  std::vector<Eigen::Vector2d> points;
  for (const BuildPoint& q : p) points.push_back(q.at);
  const std::vector<Eigen::Vector2d> hull = convexHull(points);
  if (hull.size() < 3) throw std::invalid_argument("a polygon needs three corners not on one line");
  Json vertices = Json::array();
  for (const Eigen::Vector2d& v : hull) vertices.push_back(toJson(v));
  return addTo(c, "colliders", withFields({{"type", "polygon"}, {"vertices", vertices}}, c.fields));
}

std::string addCapsule(ToolContext& c, const std::vector<BuildPoint>& p) {
  if ((p[1].at - p[0].at).norm() == 0.0) throw std::invalid_argument("a capsule needs a length: drag end to end");
  return addTo(c, "colliders", withFields({{"type", "capsule"}, {"from", toJson(p[0].at)}, {"to", toJson(p[1].at)}}, c.fields));
}

std::string addDisc(ToolContext& c, const std::vector<BuildPoint>& p) {
  const double radius = (p[1].at - p[0].at).norm();
  if (radius == 0.0) throw std::invalid_argument("a disc needs a radius: drag from its centre");
  return addTo(c, "colliders", withFields({{"type", "disc"}, {"centre", toJson(p[0].at)}, {"radius", radius}}, c.fields));
}
}  // namespace

int particleAtPoint(ToolContext& c, const BuildPoint& p) {
  if (p.particle) return *p.particle;
  return addParticle(c.document, p.at, c.particleFields);
}

const std::vector<BuildTool>& buildTools() {
  static const std::vector<BuildTool> table = {
      {"select", 'm', "click: select; drag a particle or collider: move it", Gesture::Drag, 2, 0b01, noFields, selectOrMove},
      {"particle", 'n', "click: add a particle", Gesture::Click, 1, 0b1, particleDefaults, addParticleAt},
      {"spring", 'k', "drag from particle to particle", Gesture::Drag, 2, 0b11, springDefaults, addSpring},
      {"rod", 'd', "drag from particle to particle", Gesture::Drag, 2, 0b11, rodDefaults, addRod},
      {"angle spring", 'j', "click an end, the vertex, the other end", Gesture::Clicks, 3, 0b111, angleDefaults,
       addAngleSpring},
      {"wire", 'w', "drag from the centre to the bead", Gesture::Drag, 2, 0b10, noFields, addWire},
      {"line", 't', "drag from the particle along the line", Gesture::Drag, 2, 0b01, noFields, addLine},
      {"half-plane", 'H', "drag from the surface outward", Gesture::Drag, 2, 0, materialDefaults, addHalfPlane},
      {"box", 'B', "drag corner to corner", Gesture::Drag, 2, 0, materialDefaults, addBox},
      {"polygon", 'P', "click the corners; Enter or the first corner closes", Gesture::Clicks, 0, 0, materialDefaults,
       addPolygon},
      {"capsule", 'C', "drag end to end", Gesture::Drag, 2, 0, capsuleDefaults, addCapsule},
      {"disc", 'D', "drag from the centre out", Gesture::Drag, 2, 0, materialDefaults, addDisc},
      {"delete", 'x', "click an object to delete it", Gesture::Click, 1, 0, noFields, deleteAt},
  };
  return table;
}

}  // namespace demo
