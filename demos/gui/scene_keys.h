#pragma once
// Which scene each number key loads: every built-in scene, with the cloth
// twice (4-way and 8-way springs), in the order of the scene table.
#include <map>
#include <string>
#include <vector>

#include "scene.h"

namespace demo {

// A scene to build: a built-in by name with parameter overrides, or a file.
struct SceneChoice {
  std::string label;  // shown on screen: "cloth (8-way)"
  std::string name;   // built-in scene name; empty for a file
  std::map<std::string, std::string> params;
  std::string file;   // JSON scene file
  std::string preset = scenes::kDefaultPreset;  // parameter preset of a built-in (scenes::presetTable())
};

struct SceneKey {
  unsigned char key;
  SceneChoice choice;
};

// Keys '1'…'9', '0' in order; scenes beyond ten are reachable from the panel.
std::vector<SceneKey> sceneKeys();

}  // namespace demo

namespace demo {
// Builds the chosen scene; throws std::invalid_argument for a bad name or
// parameter, scenes::SceneFileError for a file that cannot be read or is malformed.
scenes::Scene buildChoice(const SceneChoice& choice);
}  // namespace demo
