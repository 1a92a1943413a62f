#include "options.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <CLI/CLI.hpp>

#include "decimal_number.h"
#include "options/option_checks.h"
#include "options/thread_option.h"
#include "options/usage.h"
#include "particles/check.h"
#include "particles/integrator.h"
#include "scene_keys.h"

namespace demo {

namespace {
// At most 10^12 frames (over 500 years at 60 frames/s), as particle-lab's steps.
constexpr long long kMaxFrames = 1000000000000LL;

[[noreturn]] void badUsage(const std::string& message) {
  reportBadUsage(message);
  std::exit(exitBadUsage);
}

// Whether an output file can be written, before the run rather than after
// it: opens it for appending (a file that did not exist is removed again).
void requireWritable(const char* option, const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) badUsage(std::string(option) + ": '" + path + "' is a directory");
  const bool existed = std::filesystem::exists(path, error);
  {
    std::ofstream probe(path, std::ios::app);
    if (!probe) badUsage(std::string(option) + ": cannot write '" + path + "'");
  }
  if (!existed) std::filesystem::remove(path, error);
}

bool endsWith(std::string text, const std::string& suffix) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Each --compare entry, checked as CLI11 reads it.
CLI::Validator comparePane() {
  return CLI::Validator(
      [](std::string& entry) -> std::string {
        try {
          parseComparePane(entry);
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
        return {};
      },
      "INTEGRATOR[:DT]");
}

// Each --grab entry, checked as CLI11 reads it.
CLI::Validator grabSetting() {
  return CLI::Validator(
      [](std::string& entry) -> std::string {
        try {
          particles::MouseJointSettings joint;
          parseGrabSetting(entry, joint);
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
        return {};
      },
      "KEY=VALUE");
}

// What CLI11 reads into locals before it is checked and copied into
// DemoOptions, with the options that say whether each was given.
struct CommandLine {
  std::vector<std::string> grab;
  std::string key, integrator;
  double dt = 0.0;
  long long frames = 0;
  std::vector<std::string> compare;
  std::pair<int, int> window;
  CLI::Option* keyOption = nullptr;
  CLI::Option* integratorOption = nullptr;
  CLI::Option* dtOption = nullptr;
  CLI::Option* compareOption = nullptr;
  CLI::Option* framesOption = nullptr;
};

// The options in --help order, in groups by what they set.
// The scene: its source (shared with particle-lab) or a number key.
void addSceneOptions(CLI::App& cli, DemoOptions& o, CommandLine& c) {
  o.source.addOptions(cli);
  c.keyOption = cli.add_option("--key", c.key,
                               "start with the scene of a number key, 1-9 or 0, as pressing it (0: the stiff "
                               "64x64 cloth with xpbd at 60 Hz; press h in the window for the list)");
  for (const char* other : {"--scene", "--scene-file", "--param", "--preset"}) c.keyOption->excludes(cli.get_option(other));
}

// How the panes step: integrator, dt, compare mode, lockstep.
void addSteppingOptions(CLI::App& cli, DemoOptions& o, CommandLine& c) {
  c.integratorOption = cli.add_option("--integrator", c.integrator, "integrator (default: the scene's)")
                           ->check(options::integratorName());
  c.dtOption = cli.add_option("--dt", c.dt, "time step in simulated seconds (default: the scene's)")
                   ->check(options::positiveNumber());
  c.compareOption =
      cli.add_option("--compare", c.compare,
                     "start in compare mode, one pane per integrator, each with an optional dt: e.g. euler,rk4 or "
                     "rk4:0.02,rk4:0.005 (2 to 4)")
          ->delimiter(',')
          ->expected(2, 4)
          ->check(comparePane());
  cli.add_flag("--lockstep", o.lockstep, "one dt step per frame instead of a fixed simulated time per frame");
  cli.add_option("--grab", c.grab,
                 "the mouse joint, repeatable: frequency=HZ (default 5), damping-ratio=Z (0.7), stiffness-ratio=R "
                 "(9: at least R times the grabbed particle's spring stiffness; see demos/gui/SCRIPTING.md)")
      ->check(grabSetting());
  cli.add_option("--step-budget", o.stepBudgetMs,
                 "wall time in ms a frame may spend stepping, shared by the panes; past it the rest of the frame's "
                 "simulated time is dropped (slow motion), and a frame takes at least one step")
      ->capture_default_str()
      ->check(options::numberInRange(0.0, 1e6));
  options::addThreadsOption(cli, o.threads);
}

// How the window starts: panel, pause, pacing, size.
void addWindowOptions(CLI::App& cli, DemoOptions& o, CommandLine& c) {
  cli.add_flag("--no-panel", o.hidePanel, "start with the control panel hidden (key p shows it)");
  cli.add_flag("--paused", o.startPaused, "start paused");
  cli.add_flag("--realtime", o.realtime, "with --script or --frames: keep to 60 frames per second instead of running flat out");
  // WIDTHxHEIGHT: split at the x, each side a decimal integer in its range.
  cli.add_option("--window", c.window, "window size WIDTHxHEIGHT in pixels, from 200x150 to 8192x8192 (default 1180x760)")
      ->delimiter('x')
      ->check(options::decimalInteger(200, 8192).application_index(0))
      ->check(options::decimalInteger(150, 8192).application_index(1));
}

// A scripted run and what it writes (with dopri5's tolerance, which --help
// lists between them).
void addRunOptions(CLI::App& cli, DemoOptions& o, CommandLine& c) {
  cli.add_option("--script", o.script, "timed input events to play (see demos/gui/SCRIPTING.md)");
  c.framesOption = cli.add_option("--frames", c.frames, "exit after this many frames")
                       ->check(options::decimalInteger(1, kMaxFrames));
  cli.add_option("--tolerance", o.tolerance, "local error tolerance of dopri5")
      ->capture_default_str()
      ->check(options::integratorTolerance());
  cli.add_option("--screenshot", o.screenshot, "write the last frame to this PNG file");
  cli.add_option("--record", o.record,
                 "write every frame as DIR/frame-000001.png, frame-000002.png, ... (created if missing; the k "
                 "key's screenshots go there too); a video: ffmpeg -framerate 60 -i DIR/frame-%06d.png -pix_fmt "
                 "yuv420p out.mp4");
  cli.add_option("--log-state", o.logState, "write the state at exit to this file (see demos/gui/SCRIPTING.md)");
}

void parseCommandLine(CLI::App& cli, int argc, char** argv) {
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {  // --help, --version: their text is the result
      cli.exit(e);
      if (const std::string error = options::flushStandardOutput(); !error.empty()) {
        reportBadUsage(error);
        std::exit(exitOutputFailed);
      }
      std::exit(0);
    }
    badUsage(e.what());
  }
}

// The scene source (shared with particle-lab) and the integrator by its table name.
void takeSceneAndStepping(DemoOptions& o, const CommandLine& c) {
  try {
    o.source.validate();
    if (*c.integratorOption) o.integrator = particles::requireIntegrator(c.integrator).name;
    if (*c.dtOption) o.dt = c.dt;
  } catch (const std::invalid_argument& e) {
    badUsage(e.what());
  }
}

void takeSceneKey(DemoOptions& o, const CommandLine& c) {
  if (!*c.keyOption) return;
  std::string keys;
  for (const SceneKey& k : sceneKeys()) {
    if (c.key.size() == 1 && static_cast<unsigned char>(c.key[0]) == k.key) o.sceneKey = c.key[0];
    keys += std::string(keys.empty() ? "" : ", ") + static_cast<char>(k.key);
  }
  if (!o.sceneKey) badUsage("--key expects one of " + keys + ", got '" + c.key + "'");
}

void checkOutputs(const DemoOptions& o) {
  if (!o.screenshot.empty()) {
    // The screenshot is written as PNG, so the name must say PNG.
    if (!endsWith(o.screenshot, ".png"))
      badUsage("--screenshot writes PNG images: expected a name ending in .png, got '" + o.screenshot + "'");
    requireWritable("--screenshot", o.screenshot);
  }
  if (!o.logState.empty()) requireWritable("--log-state", o.logState);
  if (!o.record.empty()) {
    std::error_code error;
    std::filesystem::create_directories(o.record, error);
    if (!std::filesystem::is_directory(o.record, error))
      badUsage("--record: cannot create the directory '" + o.record + "'");
    requireWritable("--record", (std::filesystem::path(o.record) / "frame-000001.png").string());
  }
}
}  // namespace

void parseGrabSetting(const std::string& entry, particles::MouseJointSettings& joint) {
  const auto equals = entry.find('=');
  const std::string key = entry.substr(0, equals);
  double value = 0.0;
  try {
    if (equals != std::string::npos) value = scenes::readDecimalNumber(entry.substr(equals + 1));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("--grab " + entry + ": " + e.what());
  }
  if (equals == std::string::npos || !std::isfinite(value))
    throw std::invalid_argument("--grab expects KEY=NUMBER (frequency, damping-ratio, stiffness-ratio), got '" +
                                entry + "'");
  if (key == "frequency") joint.frequency = value;
  else if (key == "damping-ratio") joint.dampingRatio = value;
  else if (key == "stiffness-ratio") joint.stiffnessRatio = value;
  else
    throw std::invalid_argument("--grab: unknown setting '" + key +
                                "' (valid: frequency, damping-ratio, stiffness-ratio)");
  joint.validate();
}

ComparePane parseComparePane(const std::string& entry) {
  const auto colon = entry.find(':');
  ComparePane pane;
  pane.integrator = particles::requireIntegrator(entry.substr(0, colon)).name;
  if (colon != std::string::npos) {
    double dt = 0.0;
    try {
      dt = scenes::readDecimalNumber(entry.substr(colon + 1));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("dt in '" + entry + "': " + e.what());
    }
    if (!(dt > 0.0) || !std::isfinite(dt)) throw std::invalid_argument("dt in '" + entry + "' must be a finite number > 0");
    pane.dt = dt;
  }
  return pane;
}

DemoOptions parseOptions(int argc, char** argv) {
  DemoOptions o;
  CommandLine c;
  c.window = {o.windowWidth, o.windowHeight};
  CLI::App cli{"particle-demo: the interactive particle-system laboratory (press h in the window for the keys)"};
  o.source.scene = "cloth";
  cli.name("particle-demo");
  cli.set_version_flag("--version", options::versionLine("particle-demo"));
  addSceneOptions(cli, o, c);
  addSteppingOptions(cli, o, c);
  addWindowOptions(cli, o, c);
  addRunOptions(cli, o, c);
  parseCommandLine(cli, argc, argv);

  takeSceneAndStepping(o, c);
  takeSceneKey(o, c);
  if (*c.framesOption) o.frames = c.frames;
  if (*c.compareOption)
    for (const std::string& entry : c.compare) o.compare.push_back(parseComparePane(entry));
  for (const std::string& entry : c.grab) parseGrabSetting(entry, o.grab);
  checkOutputs(o);
  o.windowWidth = c.window.first;
  o.windowHeight = c.window.second;
  return o;
}

}  // namespace demo
