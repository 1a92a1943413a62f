#include "scene_keys.h"

#include <stdexcept>

#include "scene.h"
#include "scene_file/scene_file.h"
#include "scenes/cloth.h"
#include "scenes/param_fields.h"

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
// Built-in scenes with a parameter set and the integrator and dt they are meant for.
std::vector<SceneChoice> pairedChoices() {
  scenes::ClothParams stiff = scenes::stiffClothParams(64);
  SceneChoice cloth;
  cloth.label = "stiff cloth 64x64 (xpbd at 60 Hz)";
  cloth.name = "cloth";
  cloth.integrator = "xpbd";
  cloth.dt = 1.0 / 60.0;
  cloth.xpbdLines = true;
  // Measured over 1.5 s of this cloth hanging (xpbd's 20 substeps of one
  // pass at 1/60 s, the worst spring of the grid): 0.044 % with its columns
  // solved with the rail, 2.25 % by Gauss–Seidel alone.
  cloth.hint = "try this: slide the curtain along its rail: xpbd at 60 Hz holds every spring within 0.1 %";
  stiff.visit([&](const char* name, const auto& field, const char*) {
    cloth.params[name] = scenes::formatParam(field);
  });
  return {cloth};
}
}  // namespace

std::vector<SceneChoice> sceneChoices() {
  std::vector<SceneChoice> choices;
  auto addScene = [&](const scenes::SceneInfo& info) {
    bool varied = false;
    for (const Variant& v : variants())
      if (info.name == std::string(v.scene)) {
        choices.push_back({v.label, info.name, v.params, ""});
        varied = true;
      }
    if (!varied) choices.push_back({info.name, info.name, {}, ""});
  };
  // The number keys' scenes first (the table's scenes before its gallery),
  // then the paired ones (key 0), then the gallery.
  for (const scenes::SceneInfo& info : scenes::sceneTable())
    if (!info.gallery) addScene(info);
  for (const SceneChoice& paired : pairedChoices()) choices.push_back(paired);
  for (const scenes::SceneInfo& info : scenes::sceneTable())
    if (info.gallery) addScene(info);
  return choices;
}

std::vector<SceneKey> sceneKeys() {
  static const char keys[] = "1234567890";
  const std::vector<SceneChoice> choices = sceneChoices();
  std::vector<SceneKey> result;
  for (std::size_t k = 0; k < choices.size() && k < sizeof(keys) - 1; ++k)
    result.push_back({static_cast<unsigned char>(keys[k]), choices[k]});
  return result;
}

}  // namespace demo

namespace demo {
scenes::Scene buildChoice(const SceneChoice& choice) {
  if (choice.document) return scenes::readSceneDocument(*choice.document, choice.label);
  if (!choice.file.empty()) return scenes::loadSceneFile(choice.file);
  scenes::Scene scene = scenes::buildScene(choice.name, choice.params, choice.preset);
  if (!choice.integrator.empty()) scene.integrator = choice.integrator;
  if (choice.dt > 0.0) scene.dt = choice.dt;
  if (choice.xpbdLines) scene.integratorSettings.xpbd.lines = true;
  return scene;
}
}  // namespace demo
