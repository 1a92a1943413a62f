// Writing a scene as a JSON scene file (format: demos/scenes/FORMAT.md).
#include <cstring>

#include "particles/solver_names.h"
#include "particles/tearing.h"
#include "scene_file/codecs.h"
#include "scene_file/scene_file.h"

namespace scenes {

namespace {
template <class Codec, class Object>
Json writeWith(const std::vector<Codec>& table, const Object& object) {
  for (const Codec& codec : table)
    if (std::strcmp(codec.type, object.type()) == 0) return codec.write(object);
  throw std::logic_error(std::string("no scene-file writer for type '") + object.type() + "'");
}
Json writeCollider(const particles::Collider& collider) {
  for (const ColliderCodec& codec : colliderCodecs())
    if (codec.shape == collider.shape) return codec.write(collider);
  throw std::logic_error(std::string("no scene-file writer for collider '") +
                         particles::colliderName(collider.shape) + "'");
}
}  // namespace

Json integratorSettingsToJson(const particles::IntegratorSettings& settings) {
  return {{"tolerance", settings.dopri5.tolerance},
          {"substeps", settings.xpbd.substeps},
          {"iterations", settings.xpbd.iterations},
          {"lines", settings.xpbd.lines}};
}

Json sceneToJson(const Scene& scene) {
  const particles::ParticleSystem& s = *scene.system;
  const particles::SolverSettings& solver = s.solver().settings;
  Json doc;
  doc["name"] = scene.name;
  doc["integrator"] = scene.integrator;
  doc["integratorSettings"] = integratorSettingsToJson(scene.integratorSettings);
  doc["dt"] = scene.dt;
  if (s.time() != 0.0) doc["time"] = s.time();  // a state saved on the run
  doc["view"] = {{"min", toJson(scene.viewMin)}, {"max", toJson(scene.viewMax)}};
  doc["solver"] = {{"tolerance", solver.tolerance},
                   {"maxIterations", solver.maxIterations},
                   {"maxCgWork", solver.maxCgWork},
                   {"stiffness", solver.stiffness},
                   {"damping", solver.damping},
                   {"warmStart", solver.warmStart},
                   {"method", particles::nameOf(solver.method)},
                   {"preconditioner", particles::nameOf(solver.preconditioner)}};
  doc["particleRestitution"] = s.contactSettings().particleRestitution;
  doc["particleFriction"] = s.contactSettings().particleFriction;
  if (s.tearing().on()) doc["tearing"] = {{"strain", s.tearing().strain}};
  doc["particles"] = Json::array();
  for (int i = 0; i < s.size(); ++i) {
    Json p = {{"position", toJson(s.position(i))}, {"velocity", toJson(s.velocity(i))}, {"mass", s.masses()[i]}};
    if (s.pinned(i)) p["pinned"] = true;
    if (s.collidable(i)) p["radius"] = s.radii()[i];
    doc["particles"].push_back(std::move(p));
  }
  doc["forces"] = Json::array();
  for (const auto& force : s.forceObjects()) doc["forces"].push_back(writeWith(forceCodecs(), *force));
  doc["constraints"] = Json::array();
  for (const auto& constraint : s.constraints()) doc["constraints"].push_back(writeWith(constraintCodecs(), *constraint));
  doc["colliders"] = Json::array();
  for (const particles::Collider& collider : s.colliders()) doc["colliders"].push_back(writeCollider(collider));
  if (!s.collisionEdges().empty()) {
    doc["collisionEdges"] = Json::array();
    for (const particles::CollisionEdge& e : s.collisionEdges()) doc["collisionEdges"].push_back({e.a, e.b});
  }
  return doc;
}

// One top-level field per line, and one line per particle, force, constraint
// and collider, so that a file reads (and diffs) as a list of objects.
std::string writeScene(const Scene& scene) {
  const Json doc = sceneToJson(scene);
  std::string out = "{";
  for (auto field = doc.begin(); field != doc.end(); ++field) {
    out += (field == doc.begin() ? "\n  \"" : ",\n  \"") + field.key() + "\": ";
    const Json& value = field.value();
    if (value.is_array() && !value.empty() && value.front().is_object()) {
      out += "[";
      for (std::size_t k = 0; k < value.size(); ++k) out += (k ? ",\n    " : "\n    ") + value[k].dump();
      out += "\n  ]";
    } else {
      out += value.dump();
    }
  }
  return out + "\n}\n";
}

}  // namespace scenes
