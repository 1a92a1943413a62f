#pragma once
// --log-state: the state at exit as a small CSV-like text file, one record per
// line, the first field naming the record:
//   # comment
//   frame,<frames drawn>
//   paused,<0|1>
//   pane,<pane>,<scene label>,<integrator>,<dt>,<t>,<steps>,<diverged 0|1>,<mouse springs>,<energy>,<max |C|>
//   view,<pane>,<pixel x>,<pixel y>,<pixel width>,<pixel height>,<world xmin>,<world ymin>,<world xmax>,<world ymax>
//   particle,<pane>,<index>,<x>,<y>,<vx>,<vy>,<mass>,<pinned 0|1>
//   wall,<pane>,<xmin>,<ymin>,<xmax>,<ymax>
//   overlay,<kind>,<pixel x>,<pixel y>,<pixel width>,<pixel height>
//     (text and panels drawn over the panes in the last frame: hud, pane-hud,
//     status, divergence, help, legend, panel)
// view maps the pane's pixel rectangle (window pixels, origin top-left, as in
// the screenshot) onto the world rectangle it shows, at one scale on both axes.
// Numbers are written with 17 significant digits.
#include <string>
#include <vector>

#include "simulation.h"
#include "view.h"

namespace demo {

// A rectangle of text or controls drawn over the scene.
struct Overlay {
  std::string kind;
  PixelRect rect;
};

struct PaneState {
  std::string sceneLabel;
  const Simulation* simulation;
  ViewTransform view;
};

// Returns an error message, empty on success.
std::string writeStateFile(const std::string& path, const std::vector<PaneState>& panes,
                           const std::vector<Overlay>& overlays, long long frames, bool paused);

}  // namespace demo
