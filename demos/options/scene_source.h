#pragma once
// The options that choose a scene, the same in both programs (particle-lab's
// subcommands and particle-demo): --scene NAME [--preset NAME]
// [--param key=value ...] or --scene-file PATH.
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "scene.h"

namespace options {

struct SceneSource {
  std::string scene;  // a default set before addOptions is shown in --help
  std::string sceneFile;
  std::vector<std::string> params;  // key=value
  std::string preset = scenes::kDefaultPreset;

  void addOptions(CLI::App& app);
  // The --param overrides split at their first '='; throws UsageError for one
  // without a key or an '='.
  std::map<std::string, std::string> overrides() const;
  // Checks what needs no scene built (the --param form, the preset's name):
  // throws UsageError or std::invalid_argument with the same message load() would.
  void validate() const;
  // Builds or loads the scene; throws UsageError, std::invalid_argument
  // (scene table) or SceneFileError.
  scenes::Scene load() const;
  // "scene file 'PATH'" or "scene 'NAME'", for messages about the scene as a whole.
  std::string describe() const;
};

}  // namespace options
