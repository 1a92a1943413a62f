#pragma once
// --log-state: the state at exit as a small CSV-like text file, one record per
// line, the first field naming the record:
//   # comment
//   frame,<frames drawn>
//   paused,<0|1>
//   pane,<pane>,<scene label>,<integrator>,<dt>,<t>,<steps>,<diverged 0|1>,<mouse springs>,<energy>,<max |C|>,
//        <mouse spring energy>,<slow motion 0|1>,<substeps last frame>,<frames advanced>,<owed time>,<plot points>,
//        <waited last frame 0|1>,<longest step last frame ms>,<frames waited>
//     (energy is the scene's, without the mouse spring's)
//   faces,<pane>,<faces shaded>,<faces left unshaded>,<shaded pixels>,<pane pixels>
//   budget,<budget ms>,<steps last frame>,<panes stepped>,<panes waiting>,<a step over the budget 0|1>,
//          <stepping ms>,<longest step ms>,<frames stepped>,<frames the budget ran out>,<frames a pane waited>,
//          <frames with a step over the budget>,<frames over the budget by more than their longest step>,
//          <largest stepping ms>,<largest step ms>
//   view,<pane>,<pixel x>,<pixel y>,<pixel width>,<pixel height>,<world xmin>,<world ymin>,<world xmax>,<world ymax>
//     (the pixel rectangle is where the pane draws the world: no overlay may cover it)
//   particle,<pane>,<index>,<x>,<y>,<vx>,<vy>,<mass>,<pinned 0|1>
//   wall,<pane>,<xmin>,<ymin>,<xmax>,<ymax>
//   grab,<pane>,<particle>,<target x>,<target y>,<stiffness>,<damping>,<frames averaged>,<mean x>,<mean y>
//     (while the mouse joint holds a particle: its gains, particles/grab.h, and
//     the particle's mean position over the last frames it was held, at most 60)
//   wind,<pane>,<speed>,<direction>,<drag>,<gust>,<gust period>,<seed>,<air x>,<air y>
//     (while the wind blows: its settings and the air velocity of the last step)
//   tearing,<pane>,<tear strain (0: off)>,<links broken>
//   overlay,<kind>,<pixel x>,<pixel y>,<pixel width>,<pixel height>,<text>
//     (text and panels drawn in the last frame: top-bar, hud (the bottom bar),
//     pane-hud, indicator, help, panel; text's line breaks written as " | ";
//     bars and the help are followed by their text-fit record)
//   widget,<name>,<pixel x>,<pixel y>,<pixel width>,<pixel height>
//     (the panel's controls, for scripted clicks: scene, reset, pause, step, rewind,
//     save-state, load-state, record, wind-and-tearing (its section's header),
//     advice (its section's header), advise-error, advise-horizon, advise, advise-cancel, advise-apply)
//   advice,<state>,<progress 0..1>,<integrator>,<dt>,<tolerance>,<frames drawn while it ran>,<applied>
//     (the panel's advice: idle, running, done, cancelled or failed; the
//     cheapest pick when done, else empty and 0; the options last applied, if any)
//   timing,<scene draw ms>,<text and panel draw ms>,<panel shown 0|1>,<timed frames>,<median scene draw ms>,
//          <median text and panel ms>,<10th percentile>,<90th percentile>
//     (the first three of the last timed frame; the drawing is timed on one frame in 30, GL work
//     included, the first frame left out: it compiles the shaders)
//   build,<active 0|1>,<tool>,<selection: list[index], or scene>,<history state>,<history states>,<gesture points>,<grid>,<file>
//     (build mode: the history's current state counts from 1)
//   frame-times,<frames>,<median ms>,<10th percentile>,<90th percentile>,<median stepping ms>
//     (wall time per frame after the first 10: input, stepping, drawing and the buffer swap)
//   real-time,<simulated over wall time in the last second>,<simulated seconds>,<wall seconds>,<paced 0|1>
//     (the HUD's "x real time"; the seconds summed over the frames that ran, not paused or
//     stopped; paced: frames on the 60 Hz clock, 0 when a script runs them flat out)
// view maps the pane's pixel rectangle (window pixels, origin top-left, as in
// the screenshot) onto the world rectangle it shows, at one scale on both axes.
// Numbers are written with 17 significant digits.
#include <string>
#include <vector>

#include "frame_budget.h"
#include "renderer.h"
#include "simulation.h"
#include "view.h"

namespace demo {

// A rectangle of text or controls, and the text it shows.
struct Overlay {
  std::string kind;
  PixelRect rect;
  std::string text;
  // A bar's text as drawn: its widest line and its lines in pixels, and
  // whether it was shortened ("...") because its lines outnumbered the bar's
  // (0 and false for overlays that are not bars).
  int textWidth = 0, textHeight = 0;
  bool shortened = false;
};

struct AdviceRecord {
  std::string state = "idle";
  double progress = 0.0;
  std::string integrator;  // the cheapest pick; empty unless done with one
  double dt = 0.0, tolerance = 0.0;
  long long framesWhileRunning = 0;
  std::string applied;     // "--integrator NAME --dt X [--tolerance Y]" last applied
};

struct BuildRecord {
  bool active = false;
  std::string tool, selection = "scene", file;
  std::size_t historyState = 0, historyStates = 0, gesturePoints = 0;
  double grid = 0.0;
};

struct StateExtras {
  std::vector<Overlay> overlays, widgets;
  AdviceRecord advice;
  BuildRecord build;
  double sceneDrawMs = 0.0, overlayDrawMs = 0.0;       // the last timed frame's
  std::vector<double> sceneDrawSamples, overlayDrawSamples;  // every timed frame's after the first
  bool panelShown = false;
  std::vector<double> frameMs, frameSimulationMs;  // every frame's wall time and its stepping part
  FrameBudget lastBudget;                          // the last frame's stepping budget (frame_budget.h)
  BudgetTally budgetTally;                         // and every frame's since the start
  struct {
    double lastSecond = 0.0;             // the HUD's readout (0 before it is known)
    double simSeconds = 0.0, wallSeconds = 0.0;  // every running frame's
    bool paced = true;
  } realTime;
};

struct PaneState {
  std::string sceneLabel;
  const Simulation* simulation;
  ViewTransform view;
  Renderer::PaneDrawing drawing;  // what its last frame drew
};

// Returns an error message, empty on success.
std::string writeStateFile(const std::string& path, const std::vector<PaneState>& panes,
                           const StateExtras& extras, long long frames, bool paused);

}  // namespace demo
