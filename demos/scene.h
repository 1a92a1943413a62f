#pragma once
// Scenes: named builders of a ParticleSystem, shared by the demo, the headless
// runner, the tests and the benchmarks through one explicit table.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "particles/particle_system.h"

namespace scenes {

// One scene parameter as listed by `particle-lab list` and set by --param.
struct ParamSpec {
  std::string name;
  std::string defaultValue;
  std::string help;  // meaning and unit
};

// Parameter values by name, checked against a scene's specs: an unknown name
// or a value of the wrong kind throws std::invalid_argument listing what is valid.
class SceneParams {
 public:
  SceneParams(const std::vector<ParamSpec>& specs, const std::map<std::string, std::string>& values);
  double number(const std::string& name) const;
  int integer(const std::string& name) const;
  const std::string& text(const std::string& name) const;

 private:
  const std::string& raw(const std::string& name) const;
  std::map<std::string, std::string> values_;
  std::string validNames_;
};

// A built scene: the system with everything it needs and nothing else, and
// the settings it is meant to run with.
struct Scene {
  std::string name;
  std::unique_ptr<particles::ParticleSystem> system;
  std::string integrator = "rk4";
  particles::IntegratorSettings integratorSettings;  // adaptive-rk4's tolerance, xpbd's substeps
  double dt = 0.01;                           // simulated seconds per step
  Eigen::Vector2d viewMin{-1.0, -1.0};        // world rectangle shown by the demo
  Eigen::Vector2d viewMax{1.0, 1.0};
};

struct SceneInfo {
  const char* name;
  const char* summary;
  std::vector<ParamSpec> params;
  Scene (*build)(const SceneParams&);
};

// Every built-in scene, in the order of the demo's number keys.
const std::vector<SceneInfo>& sceneTable();

// Builds a scene by name with parameter overrides; throws std::invalid_argument
// for an unknown scene (listing the valid ones) or a bad parameter.
Scene buildScene(const std::string& name, const std::map<std::string, std::string>& overrides = {});

}  // namespace scenes
