#include "scene_keys.h"

#include <stdexcept>

#include "scene.h"
#include "scene_file/scene_file.h"

namespace demo {

namespace {
// Scenes shown under more than one key, with the parameters that tell them apart.
struct Variant {
  const char* scene;
  const char* label;
  std::map<std::string, std::string> params;
};
const std::vector<Variant>& variants() {
  static const std::vector<Variant> table = {
      {"cloth", "cloth (4-way)", {{"links", "4"}}},
      {"cloth", "cloth (8-way)", {{"links", "8"}}},
  };
  return table;
}
}  // namespace

std::vector<SceneKey> sceneKeys() {
  static const char keys[] = "1234567890";
  std::vector<SceneChoice> choices;
  for (const scenes::SceneInfo& info : scenes::sceneTable()) {
    bool varied = false;
    for (const Variant& v : variants())
      if (info.name == std::string(v.scene)) {
        choices.push_back({v.label, info.name, v.params, ""});
        varied = true;
      }
    if (!varied) choices.push_back({info.name, info.name, {}, ""});
  }
  std::vector<SceneKey> result;
  for (std::size_t k = 0; k < choices.size() && k < sizeof(keys) - 1; ++k)
    result.push_back({static_cast<unsigned char>(keys[k]), choices[k]});
  return result;
}

}  // namespace demo

namespace demo {
scenes::Scene buildChoice(const SceneChoice& choice) {
  if (!choice.file.empty()) return scenes::loadSceneFile(choice.file);
  return scenes::buildScene(choice.name, choice.params, choice.preset);
}
}  // namespace demo
