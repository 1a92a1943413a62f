// Scene-file readers and writers of every constraint type (format: demos/scenes/FORMAT.md).
#include "particles/constraints/circular_wire.h"
#include "particles/constraints/line.h"
#include "particles/constraints/rod.h"
#include "scene_file/codecs.h"

namespace scenes {

namespace {
using particles::Constraint;

std::unique_ptr<Constraint> readRod(const JsonNode& node, int n) {
  node.allowOnly({"type", "particles", "length", "form"});
  const std::vector<int> p = node["particles"].particles(2, n);
  const double length = node["length"].positive();
  const JsonNode form = node["form"];
  const std::string name = form.present() ? form.text() : "squared";
  if (name != "squared" && name != "root") form.expected("\"squared\" or \"root\"");
  return std::make_unique<particles::RodConstraint>(p[0], p[1], length, particles::parseRodForm(name));
}
Json writeRod(const Constraint& constraint) {
  const auto& c = dynamic_cast<const particles::RodConstraint&>(constraint);
  return {{"type", c.type()},
          {"particles", c.particles()},
          {"length", c.length()},
          {"form", particles::rodFormName(c.form())}};
}

std::unique_ptr<Constraint> readCircularWire(const JsonNode& node, int n) {
  node.allowOnly({"type", "particle", "centre", "radius"});
  return std::make_unique<particles::CircularWireConstraint>(node["particle"].particle(n), node["centre"].vec2(),
                                                             node["radius"].positive());
}
Json writeCircularWire(const Constraint& constraint) {
  const auto& c = dynamic_cast<const particles::CircularWireConstraint&>(constraint);
  return {{"type", c.type()},
          {"particle", c.particles()[0]},
          {"centre", toJson(c.centre())},
          {"radius", c.radius()}};
}

std::unique_ptr<Constraint> readLine(const JsonNode& node, int n) {
  node.allowOnly({"type", "particle", "point", "angle"});
  return std::make_unique<particles::LineConstraint>(node["particle"].particle(n), node["point"].vec2(),
                                                     node["angle"].number());
}
Json writeLine(const Constraint& constraint) {
  const auto& c = dynamic_cast<const particles::LineConstraint&>(constraint);
  return {{"type", c.type()}, {"particle", c.particles()[0]}, {"point", toJson(c.point())}, {"angle", c.angle()}};
}
}  // namespace

const std::vector<ConstraintCodec>& constraintCodecs() {
  static const std::vector<ConstraintCodec> table = {
      {"rod", readRod, writeRod},
      {"circular-wire", readCircularWire, writeCircularWire},
      {"line", readLine, writeLine},
  };
  return table;
}

}  // namespace scenes
