#pragma once
// Scenes: named builders of a ParticleSystem, shared by the demo, the headless
// runner, the tests and the benchmarks through one explicit table.
#include <array>
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "particles/particle_system.h"

namespace scenes {

// A preset is a named set of values for every built-in scene's parameters
// (and the time step each scene runs with). Explicit --param overrides win
// over the preset's values.
struct PresetInfo {
  const char* name;
  const char* summary;
};

// Every preset; the first is the default.
//   default  real time in SI units: g = 9.81 m/s², sizes in metres, motions
//            with periods of 0.5–3 s, a dt each scene is stable with
//   seed     the seed report's values (g = 0.05 world units/s² on scenes
//            about 1 unit across), which the laboratory reproduces
const std::vector<PresetInfo>& presetTable();
inline const char* const kDefaultPreset = "default";
inline const char* const kSeedPreset = "seed";

// Position of a preset in presetTable(); throws std::invalid_argument
// "unknown preset 'x' (valid: default, seed)".
std::size_t presetIndex(const std::string& preset);

// One scene parameter as listed by `particle-lab list` and set by --param.
struct ParamSpec {
  std::string name;
  std::vector<std::string> values;  // one per preset, in presetTable() order
  std::string help;                 // meaning and unit

  const std::string& value(const std::string& preset) const { return values.at(presetIndex(preset)); }
};

// Parameter values by name under one preset, checked against a scene's specs:
// an unknown name or a value of the wrong kind throws std::invalid_argument
// listing what is valid.
class SceneParams {
 public:
  SceneParams(const std::vector<ParamSpec>& specs, const std::map<std::string, std::string>& values,
              const std::string& preset = kDefaultPreset);
  double number(const std::string& name) const;
  int integer(const std::string& name) const;
  const std::string& text(const std::string& name) const;
  std::size_t preset() const { return preset_; }  // index in presetTable()

 private:
  const std::string& raw(const std::string& name) const;
  std::map<std::string, std::string> values_;
  std::string validNames_;
  std::size_t preset_ = 0;
};

// A built scene: the system with everything it needs and nothing else, and
// the settings it is meant to run with.
struct Scene {
  std::string name;
  std::unique_ptr<particles::ParticleSystem> system;
  std::string integrator = "rk4";
  particles::IntegratorSettings integratorSettings;  // dopri5's tolerance, xpbd's substeps
  double dt = 0.01;                           // simulated seconds per step
  Eigen::Vector2d viewMin{-1.0, -1.0};        // world rectangle shown by the demo
  Eigen::Vector2d viewMax{1.0, 1.0};
  // The faces of a surface (the cloth's grid cells) as quads of particle
  // indices, counter-clockwise at rest; empty for scenes without a surface.
  // The renderer shades them; their sides (faceEdges) are the segments that
  // meet colliders when edge contacts are on.
  std::vector<std::array<int, 4>> faces;
  // True when the scene wants its face edges, not only its particles, to
  // collide with walls and colliders (the cloth catching the nail).
  bool edgeContacts = false;
  // The edges wind pushes on when it blows (a cloth's face sides, a
  // strand's links), whether or not it blows now; empty: no wind reaches it.
  std::vector<std::array<int, 2>> windEdges;
  // One line the builder computes from the parameters, shown in place of the
  // table's summary (the capstan's mass ratio against e^(mu theta)); empty: the summary.
  std::string caption;
};

// The distinct sides of a scene's faces as particle index pairs (i < j), in
// the order they first appear.
std::vector<std::array<int, 2>> faceEdges(const Scene& scene);

struct SceneInfo {
  const char* name;
  const char* summary;  // one line: what the scene shows
  const char* hint;     // one line shown when the scene opens: "try this: ..."
  std::vector<ParamSpec> params;
  Scene (*build)(const SceneParams&);
  // A gallery scene: things meeting each other (discs, walls, ropes over
  // pulleys), listed after the number keys' scenes in the demo's panel.
  bool gallery = false;
};

// Every built-in scene, in the order of the demo's number keys.
const std::vector<SceneInfo>& sceneTable();
// The built-in scene of that name, or nullptr.
const SceneInfo* findScene(const std::string& name);

// Builds a scene by name: the preset fills every parameter, then the overrides
// replace the ones they name. Throws std::invalid_argument for an unknown
// scene or preset (listing the valid ones) or a bad parameter.
Scene buildScene(const std::string& name, const std::map<std::string, std::string>& overrides = {},
                 const std::string& preset = kDefaultPreset);

}  // namespace scenes
