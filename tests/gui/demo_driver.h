#pragma once
// Runs particle-demo as a user would (options, a script of timed input) and
// reads back what it wrote: the screenshot and the state log.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "palette.h"

namespace demotest {

struct RunResult {
  int exitCode = -1;
  std::string out, err;
  std::vector<std::string> errLines() const;
};

// Runs the demo with `args` (shell words) in `directory`; if `script` is not
// empty it is written to directory/script.txt and passed with --script.
RunResult runDemo(const std::string& directory, const std::string& args, const std::string& script = "");

// Runs the headless runner particle-lab with `args` in `directory`, to hold
// the demo's options against it.
RunResult runParticleLab(const std::string& directory, const std::string& args);

// A fresh directory for one test's files, kept after the run for inspection.
std::string outputDirectory(const std::string& testName);

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // rows top to bottom
  demo::Rgb at(int x, int y) const;
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
};
Image readPng(const std::string& path);  // throws on failure

struct LoggedParticle {
  Eigen::Vector2d x, v;
  double mass = 0.0;
  bool pinned = false;
};
struct LoggedWall {
  Eigen::Vector2d min, max;
};
// The mouse joint while it holds a particle: its target and gains, and the
// particle's mean position over the last frames held (at most 60).
struct LoggedGrab {
  int particle = -1;
  Eigen::Vector2d target, mean;
  double stiffness = 0.0, damping = 0.0;
  long long framesAveraged = 0;
};
// The wind while it blows (speed 0: none), and the tearing.
struct LoggedWind {
  double speed = 0.0, direction = 0.0, drag = 0.0, gust = 0.0, gustPeriod = 0.0;
  int seed = 0;
  Eigen::Vector2d air = Eigen::Vector2d::Zero();
};
struct LoggedPane {
  std::string scene, integrator;
  double dt = 0.0, time = 0.0, energy = 0.0, maxConstraintError = 0.0;
  double mouseSpringEnergy = 0.0;  // apart from energy, the scene's own
  double owedTime = 0.0;           // time + owedTime is the clock all panes share
  int plotPoints = 0;
  double plottedEnergy = 0.0, plottedConstraintError = 0.0;  // the plots' newest points (floats)
  long long steps = 0, framesAdvanced = 0;
  bool diverged = false, slowMotion = false;
  int mouseSprings = 0, substeps = 0;
  // The frame's stepping budget: the pane owed a step and took none last
  // frame (waited), its longest step then, and the frames it waited in all.
  bool waited = false;
  double longestStepMs = 0.0;
  long long framesWaited = 0;
  // Its shaded faces last frame: drawn, left out by the fill budget, and the
  // pixels they cover against the pane's.
  int facesShaded = 0, facesLeftOut = 0;
  double shadedPixels = 0.0, panePixels = 0.0;
  // The surface's detail: its particles' spacing on screen, and whether its
  // springs and free particles were drawn.
  double spacingPixels = 0.0;
  bool springsDrawn = true, particlesDrawn = true;
  double drawnFraction = 1.0;  // 1: the state drawn; less: between the last two steps
  int pixelX = 0, pixelY = 0, pixelWidth = 0, pixelHeight = 0;
  Eigen::Vector2d worldMin, worldMax;
  std::vector<LoggedParticle> particles;
  std::vector<LoggedWall> walls;
  std::vector<LoggedGrab> grabs;  // one while the mouse joint holds
  LoggedWind wind;
  double tearStrain = 0.0;
  long long brokenLinks = 0;
  // Window pixel (column, row) of a world point, as the demo's view maps it.
  Eigen::Vector2d toPixel(const Eigen::Vector2d& world) const;
  bool inWorldRect(const Eigen::Vector2d& pixel) const {
    return pixel.x() >= pixelX && pixel.y() >= pixelY && pixel.x() < pixelX + pixelWidth && pixel.y() < pixelY + pixelHeight;
  }
};
struct LoggedOverlay {
  std::string kind;  // top-bar, hud, pane-hud, indicator, help, panel; widget names for widgets
  int x = 0, y = 0, width = 0, height = 0;
  std::string text;  // line breaks as " | "
  // The text with its line breaks as spaces: a message read whole wherever
  // the bar wrapped it (a long path wraps where its width decides).
  std::string joined() const {
    std::string whole = text;
    for (std::size_t at = whole.find(" | "); at != std::string::npos; at = whole.find(" | ", at)) whole.replace(at, 3, " ");
    return whole;
  }
  // A bar's text-fit record: its widest line and its lines in pixels, and
  // whether it was shortened with "...".
  int textWidth = 0, textHeight = 0;
  bool shortened = false;
  Eigen::Vector2d centre() const { return {x + 0.5 * width, y + 0.5 * height}; }
  bool covers(const Eigen::Vector2d& pixel, double margin) const {
    return pixel.x() > x - margin && pixel.x() < x + width + margin && pixel.y() > y - margin &&
           pixel.y() < y + height + margin;
  }
};
// The panel's advice: its state, the cheapest pick when done, what was applied.
struct LoggedAdvice {
  std::string state, integrator, applied;
  double progress = 0.0, dt = 0.0, tolerance = 0.0;
  long long framesWhileRunning = 0;
};
// Build mode: on or off, the tool in hand, the selection, the edit history.
struct LoggedBuild {
  bool active = false;
  std::string tool, selection, file;
  long long historyState = 0, historyStates = 0, gesturePoints = 0;
  double grid = 0.0;
};
// The frame's stepping budget (demos/gui/frame_budget.h): the last frame's,
// then counts over every frame that stepped. No times: they vary by machine.
struct LoggedBudget {
  double budgetMs = 0.0;
  int steps = 0, panesStepped = 0, panesWaiting = 0;
  bool stepOverBudget = false;
  long long framesStepped = 0, framesSpent = 0, framesWithPaneWaiting = 0, framesWithStepOverBudget = 0;
};
struct StateLog {
  LoggedBudget budget;
  long long frames = 0;
  LoggedAdvice advice;
  LoggedBuild build;
  bool paused = false;
  std::vector<LoggedPane> panes;
  std::vector<LoggedOverlay> overlays, widgets;
  double sceneDrawMs = 0.0, overlayDrawMs = 0.0;
  bool panelShown = false;
  long long measuredFrames = 0;  // frame-times: frames after the warm-up, and their median wall time
  double medianFrameMs = 0.0;
  // real-time: the HUD's readout over the last second, and the simulated and
  // wall seconds of every running frame; paced as the 60 Hz clock runs frames.
  double realTimeLastSecond = 0.0, realTimeSimSeconds = 0.0, realTimeWallSeconds = 0.0;
  bool realTimePaced = false;
  const LoggedOverlay* widget(const std::string& name) const {
    for (const LoggedOverlay& w : widgets)
      if (w.kind == name) return &w;
    return nullptr;
  }
  // Every overlay's text, one after another.
  std::string text() const {
    std::string all;
    for (const LoggedOverlay& o : overlays) all += o.text + "\n";
    return all;
  }
  // Whether text or a panel is drawn at (or within margin pixels of) a pixel.
  bool underOverlay(const Eigen::Vector2d& pixel, double margin = 3) const {
    for (const LoggedOverlay& o : overlays)
      if (o.covers(pixel, margin)) return true;
    return false;
  }
  const LoggedOverlay* overlay(const std::string& kind) const {
    for (const LoggedOverlay& o : overlays)
      if (o.kind == kind) return &o;
    return nullptr;
  }
};
StateLog readStateLog(const std::string& path);  // throws on failure

bool near(demo::Rgb a, demo::Rgb b, int tolerance);

}  // namespace demotest
