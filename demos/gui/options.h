#pragma once
// Command-line options of particle-demo.
#include <optional>
#include <string>
#include <vector>

#include "frame_budget.h"
#include "options/scene_source.h"
#include "options/usage.h"
#include "particles/grab.h"
#include "particles/threads.h"

namespace demo {

// One pane of --compare: an integrator, with its own dt or the first pane's
// ("rk4" or "rk4:0.02").
struct ComparePane {
  std::string integrator;
  std::optional<double> dt;
};

// Reads one --compare entry; throws std::invalid_argument naming it.
ComparePane parseComparePane(const std::string& entry);

// Sets one field of the mouse joint from a --grab entry "key=value" (keys
// frequency, damping-ratio, stiffness-ratio; particles/grab.h); throws
// std::invalid_argument naming the entry.
void parseGrabSetting(const std::string& entry, particles::MouseJointSettings& joint);

struct DemoOptions {
  options::SceneSource source;                  // --scene (default cloth), --scene-file, --param, --preset
  std::optional<char> sceneKey;                 // --key K: the scene of number key K instead (scene_keys.h)
  std::optional<std::string> integrator;        // default: the scene's
  std::optional<double> dt;                     // default: the scene's
  double tolerance = particles::IntegratorSettings{}.dopri5.tolerance;  // --tolerance: dopri5's local error tolerance
  std::vector<ComparePane> compare;             // --compare euler,rk4: start in compare mode, 2 to 4 panes
  bool lockstep = false;
  particles::MouseJointSettings grab;           // --grab frequency=F, damping-ratio=Z, stiffness-ratio=R
  double stepBudgetMs = defaultStepBudgetMs;    // --step-budget: wall time a frame may spend stepping
  int threads = particles::affinityCpuCount();  // --threads: the engine's parallel loops (panel: "threads")
  bool hidePanel = false;
  bool startPaused = false;
  bool realtime = false;                        // scripted runs at 60 frames/s instead of flat out
  // Frames follow the 60 Hz clock: interactive runs, and scripted ones with --realtime.
  bool paced() const { return !((frames || !script.empty()) && !realtime); }
  int windowWidth = 1180, windowHeight = 760;
  std::string script;                           // --script FILE
  std::optional<long long> frames;              // --frames N: exit after N frames
  std::string screenshot;                       // --screenshot FILE.png: the last frame (PNG only)
  std::string record;                           // --record DIR: every frame as DIR/frame-NNNNNN.png;
                                                // the k key's screenshots go there too
  std::string logState;                         // --log-state FILE: the state at exit
};

// Exit codes, as particle-lab's: 0 success, 2 a bad command line (one line on
// stderr), 4 an output that could not be written (--screenshot, --log-state,
// --record's frames, the k key's screenshots; one line on stderr each).
constexpr int exitBadUsage = options::kBadUsageExit;
constexpr int exitOutputFailed = options::kWriteFailedExit;

// Writes "particle-demo: <message>" as one line on stderr, as particle-lab does.
inline void reportBadUsage(const std::string& message) { options::printErrorLine("particle-demo", message); }

// Parses argv; on --help prints the help and exits 0; on a bad value prints
// one line "particle-demo: …" and exits 2. Checks values that need no
// window (scene and integrator names, dt, files; that --screenshot and
// --log-state can be written) so errors come before GLUT and the run.
DemoOptions parseOptions(int argc, char** argv);

}  // namespace demo
