#include "options/scene_source.h"

#include "output/printable.h"

#include "join_names.h"
#include "options/usage.h"
#include "scene_file/scene_file.h"

namespace options {

void SceneSource::addOptions(CLI::App& app) {
  auto* byName = app.add_option("--scene", scene, "built-in scene: " + scenes::joinNames(scenes::sceneTable()) +
                                                      " (parameters: particle-lab list)");
  if (!scene.empty()) byName->capture_default_str();
  auto* byFile = app.add_option("--scene-file", sceneFile, "JSON scene file (format: demos/scenes/FORMAT.md)");
  byName->excludes(byFile);
  app.add_option("--param", params,
                 "set a parameter of the built-in scene, key=value; repeatable (particle-lab list shows them)")
      ->excludes(byFile);
  app.add_option("--preset", preset,
                 "parameter preset of the built-in scene: " + scenes::joinNames(scenes::presetTable()) +
                     " (particle-lab list shows both)")
      ->capture_default_str()
      ->excludes(byFile);
}

std::map<std::string, std::string> SceneSource::overrides() const {
  std::map<std::string, std::string> result;
  for (const std::string& param : params) {
    const auto eq = param.find('=');
    if (eq == std::string::npos || eq == 0)
      throw UsageError("--param expects key=value, got '" + param + "'");
    result[param.substr(0, eq)] = param.substr(eq + 1);
  }
  return result;
}

void SceneSource::validate() const {
  if (!sceneFile.empty()) return;
  if (scene.empty()) throw UsageError("choose a scene with --scene NAME or --scene-file PATH");
  overrides();
  scenes::presetIndex(preset);
}

scenes::Scene SceneSource::load() const {
  if (!sceneFile.empty()) return scenes::loadSceneFile(sceneFile);
  validate();
  return scenes::buildScene(scene, overrides(), preset);
}

std::string SceneSource::describe() const {
  return sceneFile.empty() ? "scene '" + output::printable(scene) + "'" : "scene file '" + output::printable(sceneFile) + "'";
}

}  // namespace options
