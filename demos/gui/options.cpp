#include "options.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "particles/check.h"
#include "join_names.h"
#include "particles/integrator.h"
#include "scene_keys.h"

namespace demo {

void reportBadUsage(const std::string& message) {
  std::string line = message;
  for (char& c : line)
    if (c == '\n') c = ' ';
  std::fprintf(stderr, "particle-demo: %s\n", line.c_str());
}

namespace {
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

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) items.push_back(item);
  return items;
}
}  // namespace

DemoOptions parseOptions(int argc, char** argv) {
  DemoOptions o;
  CLI::App cli{"particle-demo: the interactive particle-system laboratory (press h in the window for the keys)"};
  std::vector<std::string> params;
  std::string compare, window;
  double dt = 0.0;
  long long frames = 0;
  std::string integrator;
  auto* byName =
      cli.add_option("--scene", o.scene, "built-in scene to start with (see particle-lab list)")->capture_default_str();
  auto* byFile = cli.add_option("--scene-file", o.sceneFile, "JSON scene file to start with (format: demos/scenes/FORMAT.md)");
  byName->excludes(byFile);
  std::string key;
  auto* byKey = cli.add_option("--key", key,
                               "start with the scene of a number key, 1-9 or 0, as pressing it (0: the stiff 64x64 "
                               "cloth with xpbd at 60 Hz; press h in the window for the list)");
  byKey->excludes(byName)->excludes(byFile);
  auto* paramOption = cli.add_option("--param", params, "scene parameter override key=value (repeatable)");
  paramOption->excludes(byFile)->excludes(byKey);
  cli.add_option("--preset", o.preset,
                 "parameter preset of the built-in scenes: " +
                     scenes::joinNames(scenes::presetTable()) + " (see particle-lab list)")
      ->capture_default_str()
      ->excludes(byFile)
      ->excludes(byKey);
  auto* integratorOption = cli.add_option("--integrator", integrator, "integrator (default: the scene's)");
  auto* dtOption = cli.add_option("--dt", dt, "time step in simulated seconds (default: the scene's)");
  auto* compareOption = cli.add_option("--compare", compare, "start in compare mode, one pane per integrator, each with an optional dt: e.g. euler,rk4 or rk4:0.02,rk4:0.005 (2 to 4)");
  cli.add_flag("--lockstep", o.lockstep, "one dt step per frame instead of a fixed simulated time per frame");
  cli.add_flag("--no-panel", o.hidePanel, "start with the control panel hidden (key p shows it)");
  cli.add_flag("--paused", o.startPaused, "start paused");
  cli.add_flag("--realtime", o.realtime, "with --script or --frames: keep to 60 frames per second instead of running flat out");
  cli.add_option("--window", window, "window size WIDTHxHEIGHT in pixels (default 1180x760)");
  cli.add_option("--script", o.script, "timed input events to play (see demos/gui/SCRIPTING.md)");
  auto* framesOption = cli.add_option("--frames", frames, "exit after this many frames");
  cli.add_option("--tolerance", o.tolerance, "local error tolerance of adaptive-rk4")->capture_default_str();
  cli.add_option("--screenshot", o.screenshot, "write the last frame to this PNG file");
  cli.add_option("--log-state", o.logState, "write the state at exit to this file (see demos/gui/SCRIPTING.md)");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    std::exit(cli.exit(e));
  } catch (const CLI::ParseError& e) {
    badUsage(e.what());
  }

  for (const std::string& p : params) {
    const auto eq = p.find('=');
    if (eq == std::string::npos || eq == 0) badUsage("--param expects key=value, got '" + p + "'");
    o.params[p.substr(0, eq)] = p.substr(eq + 1);
  }
  try {
    scenes::presetIndex(o.preset);
  } catch (const std::invalid_argument& e) {
    badUsage(e.what());  // the same message as particle-lab's
  }
  if (*byKey) {
    bool known = false;
    std::string keys;
    for (const SceneKey& k : sceneKeys()) {
      known |= key.size() == 1 && static_cast<unsigned char>(key[0]) == k.key;
      keys += std::string(keys.empty() ? "" : ", ") + static_cast<char>(k.key);
    }
    if (!known) badUsage("--key expects one of " + keys + ", got '" + key + "'");
    o.sceneKey = key[0];
  }
  if (*integratorOption) o.integrator = integrator;
  try {
    particles::IntegratorSettings settings;
    settings.tolerance = o.tolerance;
    settings.validate();
  } catch (const std::invalid_argument& e) {
    badUsage(std::string("--tolerance: ") + e.what());
  }
  if (*dtOption) {
    try {
      particles::requirePositive("--dt", dt);  // the same message as particle-lab's
    } catch (const std::invalid_argument& e) {
      badUsage(e.what());
    }
    o.dt = dt;
  }
  if (*framesOption) {
    if (frames < 1) badUsage("--frames must be at least 1, got " + std::to_string(frames));
    o.frames = frames;
  }
  if (*compareOption) {
    o.compare = splitList(compare);
    if (o.compare.size() < 2 || o.compare.size() > 4)
      badUsage("--compare needs 2 to 4 comma-separated integrators, got '" + compare + "'");
  }
  if (!o.screenshot.empty()) {
    // The screenshot is written as PNG, so the name must say PNG.
    if (!endsWith(o.screenshot, ".png"))
      badUsage("--screenshot writes PNG images: expected a name ending in .png, got '" + o.screenshot + "'");
    requireWritable("--screenshot", o.screenshot);
  }
  if (!o.logState.empty()) requireWritable("--log-state", o.logState);
  if (!window.empty()) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(window.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 200 || h < 150 ||
        w > 8192 || h > 8192)
      badUsage("--window expects WIDTHxHEIGHT between 200x150 and 8192x8192, got '" + window + "'");
    o.windowWidth = w;
    o.windowHeight = h;
  }
  return o;
}

}  // namespace demo
