#pragma once
// Build mode's state: the tool in hand and the fields of what it adds, the
// gesture in progress, the selection, the grid, the file field, and the
// edit history (undo and redo) of the document being built. The App turns
// the mouse and keys into these calls and commits the edits a tool makes
// (build_actions.cpp); nothing here draws or reads the window.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "build_tools.h"
#include "edit_history.h"

namespace demo {

class BuildMode {
 public:
  BuildMode();

  bool active() const { return active_; }
  void setActive(bool active);

  // --- tools ------------------------------------------------------------------
  std::size_t toolIndex() const { return tool_; }
  const BuildTool& tool() const { return buildTools()[tool_]; }
  void selectTool(std::size_t index);  // ends a gesture in progress
  std::optional<std::size_t> toolForKey(unsigned char key) const;
  std::optional<std::size_t> toolNamed(const std::string& name) const;  // as the table names it, or with '-' for ' '
  Json& fields(std::size_t tool) { return fields_.at(tool); }
  const Json& fields(std::size_t tool) const { return fields_.at(tool); }
  const Json& particleFields() const;  // the particle tool's: what a tool adds at an end in empty space

  // --- gestures (world units) --------------------------------------------------
  // The point of the gesture's next press (release: its release) at `world`:
  // on the particle within pickRadius if the tool's point snaps to one, else
  // on the grid.
  BuildPoint pointAt(const Eigen::Vector2d& world, const particles::ParticleSystem& system, double pickRadius,
                     bool release) const;
  void press(const BuildPoint& point);
  void moveTo(const Eigen::Vector2d& world) { cursor_ = world; }
  // The gesture's points when this release completes it.
  std::optional<std::vector<BuildPoint>> release(const BuildPoint& point, double pickRadius);
  // Enter: the clicks so far, when they complete the gesture (a polygon's corners).
  std::optional<std::vector<BuildPoint>> finishClicks();
  void cancelGesture();
  bool gestureInProgress() const { return !pending_.empty(); }
  const std::vector<BuildPoint>& pending() const { return pending_; }  // points of the gesture so far
  const std::optional<Eigen::Vector2d>& cursor() const { return cursor_; }

  // --- the rest of the state ----------------------------------------------------
  std::optional<ObjectRef> selection;  // none: the panel edits the scene's own fields
  EditHistory history;
  double grid = 0.0;                        // > 0: points not on a particle snap to multiples of it (world units)
  std::string file = "built-scene.json";    // the file field: s saves the scene to it, o opens it

 private:
  bool active_ = false;
  std::size_t tool_ = 0;
  std::vector<Json> fields_;  // per tool
  std::vector<BuildPoint> pending_;
  bool pressed_ = false;
  std::optional<Eigen::Vector2d> cursor_;
};

}  // namespace demo
