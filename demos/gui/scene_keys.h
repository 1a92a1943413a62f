#pragma once
// Which scene each number key loads: every built-in scene but the gallery,
// with the cloth twice (4-way and 8-way springs), in the order of the scene
// table, then the scenes paired with an integrator (the stiff 64×64 cloth
// with xpbd at 60 Hz); the gallery follows in the panel's list.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "scene.h"
#include "scene_file/json_node.h"

namespace demo {

// A scene to build: a built-in by name with parameter overrides, a file, or
// a scene-file document held in memory (one made in build mode).
struct SceneChoice {
  std::string label;  // shown on screen: "cloth (8-way)"
  std::string name;   // built-in scene name; empty for a file
  std::map<std::string, std::string> params;
  std::string file;   // JSON scene file
  std::string preset = scenes::kDefaultPreset;  // parameter preset of a built-in (scenes::presetTable())
  std::string integrator = "";  // non-empty: replaces the scene's integrator (the stiff cloth's xpbd)
  double dt = 0.0;         // > 0: replaces the scene's dt
  bool xpbdLines = false;  // xpbd solves the scene's hanging lines (XpbdSettings::lines)
  std::string hint = "";   // non-empty: replaces the scene table's "try this" line
  // Set: the scene file's document (label names it in errors); shared, never
  // changed, so copies of the choice (the advice's worker) read it safely.
  std::shared_ptr<const scenes::Json> document = nullptr;
};

struct SceneKey {
  unsigned char key;
  SceneChoice choice;
};

// Every scene the demo offers, in the order of its list in the panel: the
// scene table's (the cloth twice) without its gallery, the paired ones, then
// the gallery (scenes::SceneInfo::gallery).
std::vector<SceneChoice> sceneChoices();

// Keys '1'…'9', '0' for the first ten of sceneChoices(); the gallery and any
// scene beyond ten are reached from the panel's list (or --scene NAME).
std::vector<SceneKey> sceneKeys();

}  // namespace demo

namespace demo {
// Builds the chosen scene; throws std::invalid_argument for a bad name or
// parameter, scenes::SceneFileError for a file that cannot be read or is malformed.
scenes::Scene buildChoice(const SceneChoice& choice);
}  // namespace demo
