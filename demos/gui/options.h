#pragma once
// Command-line options of particle-demo.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scene.h"

namespace demo {

struct DemoOptions {
  std::string scene = "cloth";
  std::string sceneFile;                        // overrides scene when set
  std::optional<char> sceneKey;                 // --key K: the scene of number key K (scene_keys.h)
  std::map<std::string, std::string> params;    // --param key=value
  std::string preset = scenes::kDefaultPreset;              // --preset NAME: parameter preset of the built-in scenes
  std::optional<std::string> integrator;        // default: the scene's
  std::optional<double> dt;                     // default: the scene's
  double tolerance = 1e-6;                      // --tolerance: adaptive-rk4's local error tolerance
  std::vector<std::string> compare;             // --compare euler,rk4: start in compare mode
  bool lockstep = false;
  bool hidePanel = false;
  bool startPaused = false;
  bool realtime = false;                        // scripted runs at 60 frames/s instead of flat out
  int windowWidth = 1180, windowHeight = 760;
  std::string script;                           // --script FILE
  std::optional<long long> frames;              // --frames N: exit after N frames
  std::string screenshot;                       // --screenshot FILE.png: the last frame (PNG only)
  std::string logState;                         // --log-state FILE: the state at exit
};

// Exit codes: 0 success, 2 a bad command line (one line on stderr), 1 an
// output (--screenshot, --log-state) that could not be written at the end.
constexpr int exitBadUsage = 2;
constexpr int exitOutputFailed = 1;

// Writes "particle-demo: <message>" as one line on stderr, as particle-lab does.
void reportBadUsage(const std::string& message);

// Parses argv; on --help prints the help and exits 0; on a bad value prints
// one line "particle-demo: …" and exits 2. Checks values that need no
// window (scene and integrator names, dt, files; that --screenshot and
// --log-state can be written) so errors come before GLUT and the run.
DemoOptions parseOptions(int argc, char** argv);

}  // namespace demo
