#pragma once
// The tables that map a force or constraint type name in a scene file to its
// reader and writer. Adding a type is one reader, one writer and one entry in
// force_codecs.cpp, constraint_codecs.cpp or collider_codecs.cpp; nothing else switches on types.
#include <memory>
#include <vector>


#include "particles/collider.h"
#include "particles/constraint.h"
#include "particles/force.h"
#include "scene_file/json_node.h"

namespace scenes {

struct ForceCodec {
  const char* type;  // as Force::type() and the file's "type"
  // Reads the object's fields (node is the whole object, "type" included);
  // may throw SceneFileError, and the engine's std::invalid_argument.
  std::unique_ptr<particles::Force> (*read)(const JsonNode& node, int particleCount);
  Json (*write)(const particles::Force& force);  // every field, "type" included
};

struct ConstraintCodec {
  const char* type;  // as Constraint::type()
  std::unique_ptr<particles::Constraint> (*read)(const JsonNode& node, int particleCount);
  Json (*write)(const particles::Constraint& constraint);
};

// Colliders by kind; the file's "type" is particles::colliderName(shape).
struct ColliderCodec {
  particles::ColliderShape shape;
  particles::Collider (*read)(const JsonNode& node);  // may throw SceneFileError
  Json (*write)(const particles::Collider& collider);
};

const std::vector<ForceCodec>& forceCodecs();
const std::vector<ColliderCodec>& colliderCodecs();
const std::vector<ConstraintCodec>& constraintCodecs();

inline Json toJson(const Eigen::Vector2d& p) { return Json::array({p.x(), p.y()}); }

}  // namespace scenes
