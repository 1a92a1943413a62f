#pragma once
// Where everything goes in the window, so that no text covers the scene:
// reserved margins for the text (a top bar for the scene's name, hints and
// messages; a bottom bar for the HUD, the keys and the force legend; in
// compare mode a header strip at the top of each pane), the control panel at
// the right edge, and for each pane the rectangle where the world is drawn,
// inset by a gutter that holds the out-of-view indicators.
#include <vector>

#include "view.h"

namespace demo {

// The bars' lines are those they hold at their natural width; a narrower
// bar holds proportionally more, since its text wraps (wrappedLines).
struct LayoutMetrics {
  int lineHeight = 18;       // pixels per line of HUD text (15 px font)
  int padding = 4;           // around the text of a bar
  int topLines = 2;          // scene · time · summary; hint or message (a long message takes both)
  int bottomLines = 5;       // single pane: four HUD lines (the integrator, its state, timings, numbers) and the keys
  int compareBottomLines = 1;  // compare mode: the keys
  int legendLines = 1;       // the force legend, when the arrows are shown (either mode)
  int barWidth = 840;        // the top and bottom bars' natural width
  int paneHeaderLines = 3;   // compare mode: each pane's integrator, numbers, state
  int paneHeaderWidth = 560;  // and its natural width
  int gutter = 12;           // around each pane's world, for the edge indicators
  // The control panel, when shown: panelWidth in a wide window, narrower in a
  // small one (panelFraction of it, no less than minPanelWidth, at most half).
  int panelWidth = 340;
  double panelFraction = 0.3;
  int minPanelWidth = 260;
};

struct Layout {
  PixelRect topBar, bottomBar, panel;  // panel has zero width when hidden
  std::vector<PixelRect> panes;        // each pane's whole rectangle
  std::vector<PixelRect> headers;      // compare mode: each pane's text strip (empty rectangles otherwise)
  std::vector<PixelRect> worlds;       // where each pane draws the world
};

// Lines a bar of `width` pixels needs for text that takes `lines` at `naturalWidth`.
int wrappedLines(int lines, int naturalWidth, int width);

Layout computeLayout(int windowWidth, int windowHeight, bool panelShown, int paneCount,
                     const LayoutMetrics& metrics = {});

// Whether two rectangles share a pixel.
bool intersects(const PixelRect& a, const PixelRect& b);

}  // namespace demo
