// Scene-file readers and writers of every collider kind (format: demos/scenes/FORMAT.md).
#include "scene_file/codecs.h"

namespace scenes {

namespace {
using particles::Collider;

// restitution e ∈ [0, 1] (default 0.5) and Coulomb friction μ ≥ 0 (default 0), on every kind.
Collider withMaterial(Collider c, const JsonNode& node) {
  if (node["restitution"].present()) c.restitution = node["restitution"].inRange(0.0, 1.0);
  if (node["friction"].present()) c.friction = node["friction"].nonNegative();
  return c;
}
Json material(Json object, const Collider& c) {
  object["restitution"] = c.restitution;
  object["friction"] = c.friction;
  return object;
}

Collider readHalfPlane(const JsonNode& node) {
  node.allowOnly({"type", "point", "normal", "restitution", "friction"});
  const Eigen::Vector2d n = node["normal"].vec2();
  if (!(n.cwiseAbs().maxCoeff() > 0.0)) node["normal"].expected("a non-zero vector");
  return withMaterial(Collider::halfPlane(node["point"].vec2(), n), node);
}
Json writeHalfPlane(const Collider& c) {
  return material({{"type", "halfPlane"}, {"point", toJson(c.points[0])}, {"normal", toJson(c.normal)}}, c);
}

Collider readBox(const JsonNode& node) {
  node.allowOnly({"type", "min", "max", "restitution", "friction"});
  const Eigen::Vector2d min = node["min"].vec2(), max = node["max"].vec2();
  if (!(max.array() > min.array()).all()) node["max"].expected("a point above and right of min");
  return withMaterial(Collider::box(min, max), node);
}
Json writeBox(const Collider& c) {
  return material({{"type", "box"}, {"min", toJson(c.points[0])}, {"max", toJson(c.points[2])}}, c);
}

Collider readPolygon(const JsonNode& node) {
  node.allowOnly({"type", "vertices", "restitution", "friction"});
  const JsonNode list = node["vertices"];
  if (!list.present()) list.expected("an array of at least 3 vertices [x, y], counter-clockwise");
  if (list.arraySize() > 1000) list.reject("a polygon has at most 1000 vertices");
  std::vector<Eigen::Vector2d> vertices;
  for (std::size_t k = 0; k < list.arraySize(); ++k) vertices.push_back(list[k].vec2());
  return withMaterial(Collider::polygon(vertices), node);
}
Json writePolygon(const Collider& c) {
  Json vertices = Json::array();
  for (const Eigen::Vector2d& p : c.points) vertices.push_back(toJson(p));
  return material({{"type", "polygon"}, {"vertices", vertices}}, c);
}

Collider readCapsule(const JsonNode& node) {
  node.allowOnly({"type", "from", "to", "radius", "restitution", "friction"});
  return withMaterial(Collider::capsule(node["from"].vec2(), node["to"].vec2(), node["radius"].positive()), node);
}
Json writeCapsule(const Collider& c) {
  return material({{"type", "capsule"},
                   {"from", toJson(c.points[0])},
                   {"to", toJson(c.points[1])},
                   {"radius", c.radius}},
                  c);
}

Collider readDisc(const JsonNode& node) {
  node.allowOnly({"type", "centre", "radius", "restitution", "friction"});
  return withMaterial(Collider::disc(node["centre"].vec2(), node["radius"].positive()), node);
}
Json writeDisc(const Collider& c) {
  return material({{"type", "disc"}, {"centre", toJson(c.points[0])}, {"radius", c.radius}}, c);
}
}  // namespace

const std::vector<ColliderCodec>& colliderCodecs() {
  static const std::vector<ColliderCodec> table = {
      {particles::ColliderShape::HalfPlane, readHalfPlane, writeHalfPlane},
      {particles::ColliderShape::Box, readBox, writeBox},
      {particles::ColliderShape::Polygon, readPolygon, writePolygon},
      {particles::ColliderShape::Capsule, readCapsule, writeCapsule},
      {particles::ColliderShape::Disc, readDisc, writeDisc},
  };
  return table;
}

}  // namespace scenes
