#include "cli/scene_source.h"

#include "cli/command.h"
#include "join_names.h"
#include "scene_file/scene_file.h"

namespace cli {

void SceneSource::addOptions(CLI::App& app) {
  auto* byName = app.add_option("--scene", scene, "built-in scene: " + scenes::joinNames(scenes::sceneTable()) +
                                                      " (parameters: particle-lab list)");
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

scenes::Scene SceneSource::load() const {
  if (!sceneFile.empty()) return scenes::loadSceneFile(sceneFile);
  if (scene.empty()) throw UsageError("choose a scene with --scene NAME or --scene-file PATH");
  std::map<std::string, std::string> overrides;
  for (const std::string& param : params) {
    const auto eq = param.find('=');
    if (eq == std::string::npos || eq == 0)
      throw UsageError("--param expects key=value, got '" + param + "'");
    overrides[param.substr(0, eq)] = param.substr(eq + 1);
  }
  return scenes::buildScene(scene, overrides, preset);
}

}  // namespace cli
