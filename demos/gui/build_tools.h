#pragma once
// Build mode's tools, in one table: what each adds, moves or deletes, the
// gesture it takes (a click, a drag, or several clicks), which of the
// gesture's points snap to particles, and the fields of what it adds, which
// the panel edits before it is added. No OpenGL here.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "particles/particle_system.h"
#include "scene_document.h"

namespace demo {

// A point of a gesture, in world units: snapped to a particle (then
// `particle` is its index and `at` its position) or to the grid; `raw` is
// the pointer's own position, where objects are picked.
struct BuildPoint {
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  std::optional<int> particle;
  Eigen::Vector2d raw = Eigen::Vector2d::Zero();
};

// What a tool reads and changes.
struct ToolContext {
  Json& document;                           // the edit is made here
  const particles::ParticleSystem& system;  // the scene on screen, built from the document before the edit
  const Json& particleFields;               // the fields of particles a tool adds at an end
  const Json& fields;                       // the fields of what this tool adds
  double pickRadius;                        // world units: how near a press must be to an object
  std::optional<ObjectRef>& selection;      // the tool selects what it adds or picks
};

enum class Gesture {
  Click,   // one press: its point
  Drag,    // a press and a release: two points
  Clicks,  // `points` clicks, or until Enter or a click on the first point (points = 0)
};

struct BuildTool {
  const char* name;   // "spring": the panel's button, the help and the script's tool name
  unsigned char key;  // its key in build mode
  const char* help;   // the gesture in a few words
  Gesture gesture;
  int points;            // Clicks: how many (0: until closed)
  unsigned particleEnds;  // bit k: point k snaps to a particle, and a point in empty space adds one
  Json (*defaults)();     // the fields new objects take
  // Makes the edit from the gesture's points and returns its name ("add
  // spring"); "" when the document is unchanged (a click that selects).
  // Throws std::invalid_argument with a one-line reason for a gesture that
  // makes nothing (a spring from a particle to itself).
  std::string (*apply)(ToolContext& context, const std::vector<BuildPoint>& points);

  bool snapsToParticle(std::size_t point) const { return point < 32 && ((particleEnds >> point) & 1u) != 0; }
};

// Every tool, the selecting one first.
const std::vector<BuildTool>& buildTools();

// The particle a point stands for: the one it snapped to, or a new one added
// there with the particle tool's fields.
int particleAtPoint(ToolContext& context, const BuildPoint& point);

}  // namespace demo
