#pragma once
// JSON scene files (format: demos/scenes/FORMAT.md): everything a built-in
// scene can hold — particles, forces, constraints, walls, the integrator, dt
// and the solver settings — read and written losslessly, so that a scene
// exported and loaded back steps bit for bit like the original.
#include <string>

#include "scene.h"
#include "scene_file/json_node.h"

namespace scenes {

// Builds the scene a file's text describes. source names the file in errors:
// anything malformed throws SceneFileError with one line
// "<source>: <JSON path>: expected <what>, got <value>".
Scene readScene(const std::string& text, const std::string& source);

// Builds the scene a document already parsed describes (the demo's build
// mode edits one), as readScene reads the same document's text.
Scene readSceneDocument(const Json& document, const std::string& source);

// Reads the file at path (SceneFileError also when it cannot be read).
Scene loadSceneFile(const std::string& path);

// The scene as a JSON document (every field written, doubles exactly).
Json sceneToJson(const Scene& scene);
// Its "integratorSettings" member: the settings as a scene file holds them.
Json integratorSettingsToJson(const particles::IntegratorSettings& settings);
std::string writeScene(const Scene& scene);  // sceneToJson, indented, with a final newline

}  // namespace scenes
