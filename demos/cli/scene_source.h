#pragma once
// The options that choose a scene, shared by the subcommands that need one:
// --scene NAME [--preset NAME] [--param key=value ...] or --scene-file PATH.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "scene.h"

namespace cli {

struct SceneSource {
  std::string scene;
  std::string sceneFile;
  std::vector<std::string> params;  // key=value
  std::string preset = scenes::kDefaultPreset;

  void addOptions(CLI::App& app);
  // Builds or loads the scene; throws UsageError, std::invalid_argument
  // (scene table) or SceneFileError.
  scenes::Scene load() const;
};

}  // namespace cli
