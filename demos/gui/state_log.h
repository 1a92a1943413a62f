#pragma once
// --log-state: the state at exit as a small CSV-like text file, one record per
// line, the first field naming the record:
//   # comment
//   frame,<frames drawn>
//   paused,<0|1>
//   pane,<pane>,<scene label>,<integrator>,<dt>,<t>,<steps>,<diverged 0|1>,<mouse springs>,<energy>,<max |C|>,
//        <mouse spring energy>,<slow motion 0|1>,<substeps last frame>,<frames advanced>,<owed time>,<plot points>
//     (energy is the scene's, without the mouse spring's)
//   view,<pane>,<pixel x>,<pixel y>,<pixel width>,<pixel height>,<world xmin>,<world ymin>,<world xmax>,<world ymax>
//     (the pixel rectangle is where the pane draws the world: no overlay may cover it)
//   particle,<pane>,<index>,<x>,<y>,<vx>,<vy>,<mass>,<pinned 0|1>
//   wall,<pane>,<xmin>,<ymin>,<xmax>,<ymax>
//   overlay,<kind>,<pixel x>,<pixel y>,<pixel width>,<pixel height>,<text>
//     (text and panels drawn in the last frame: top-bar, hud (the bottom bar),
//     pane-hud, indicator, help, panel; text's line breaks written as " | ")
//   widget,<name>,<pixel x>,<pixel y>,<pixel width>,<pixel height>
//     (the panel's controls, for scripted clicks: scene, reset, pause, step, rewind)
//   timing,<scene draw ms>,<text and panel draw ms>,<panel shown 0|1>
//   frame-times,<frames>,<median ms>,<10th percentile>,<90th percentile>,<median stepping ms>
//     (wall time per frame after the first 10: input, stepping, drawing and the buffer swap)
// view maps the pane's pixel rectangle (window pixels, origin top-left, as in
// the screenshot) onto the world rectangle it shows, at one scale on both axes.
// Numbers are written with 17 significant digits.
#include <string>
#include <vector>

#include "simulation.h"
#include "view.h"

namespace demo {

// A rectangle of text or controls, and the text it shows.
struct Overlay {
  std::string kind;
  PixelRect rect;
  std::string text;
};

struct StateExtras {
  std::vector<Overlay> overlays, widgets;
  double sceneDrawMs = 0.0, overlayDrawMs = 0.0;
  bool panelShown = false;
  std::vector<double> frameMs, frameSimulationMs;  // every frame's wall time and its stepping part
};

struct PaneState {
  std::string sceneLabel;
  const Simulation* simulation;
  ViewTransform view;
};

// Returns an error message, empty on success.
std::string writeStateFile(const std::string& path, const std::vector<PaneState>& panes,
                           const StateExtras& extras, long long frames, bool paused);

}  // namespace demo
