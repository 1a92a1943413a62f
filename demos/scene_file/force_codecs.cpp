// Scene-file readers and writers of every force type (format: demos/scenes/FORMAT.md).
#include "particles/forces/angular_spring.h"
#include "particles/forces/drag.h"
#include "particles/forces/gravity.h"
#include "particles/forces/mouse_spring.h"
#include "particles/forces/spring.h"
#include "scene_file/codecs.h"

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

std::unique_ptr<Force> readSpring(const JsonNode& node, int n) {
  node.allowOnly({"type", "particles", "restLength", "stiffness", "damping"});
  const std::vector<int> p = node["particles"].particles(2, n);
  return std::make_unique<particles::SpringForce>(p[0], p[1], node["restLength"].positive(),
                                                  node["stiffness"].nonNegative(),
                                                  node["damping"].nonNegative());
}
Json writeSpring(const Force& force) {
  const auto& f = dynamic_cast<const particles::SpringForce&>(force);
  return {{"type", f.type()},
          {"particles", {f.first(), f.second()}},
          {"restLength", f.restLength()},
          {"stiffness", f.stiffness()},
          {"damping", f.damping()}};
}

std::unique_ptr<Force> readAngularSpring(const JsonNode& node, int n) {
  node.allowOnly({"type", "particles", "restAngle", "stiffness", "damping"});
  const std::vector<int> p = node["particles"].particles(3, n);
  return std::make_unique<particles::AngularSpringForce>(p[0], p[1], p[2], node["restAngle"].number(),
                                                         node["stiffness"].nonNegative(),
                                                         node["damping"].nonNegative());
}
Json writeAngularSpring(const Force& force) {
  const auto& f = dynamic_cast<const particles::AngularSpringForce&>(force);
  return {{"type", f.type()},
          {"particles", f.triple()},
          {"restAngle", f.restAngle()},
          {"stiffness", f.stiffness()},
          {"damping", f.damping()}};
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
}  // namespace

const std::vector<ForceCodec>& forceCodecs() {
  static const std::vector<ForceCodec> table = {
      {"gravity", readGravity, writeGravity},
      {"drag", readDrag, writeDrag},
      {"spring", readSpring, writeSpring},
      {"angular-spring", readAngularSpring, writeAngularSpring},
      {"mouse-spring", readMouseSpring, writeMouseSpring},
  };
  return table;
}

}  // namespace scenes
