#include "layout.h"

#include <algorithm>

namespace demo {

namespace {
int barHeight(int lines, const LayoutMetrics& m) { return lines * m.lineHeight + 2 * m.padding; }

PixelRect inset(const PixelRect& r, int by) {
  return {r.x + by, r.y + by, std::max(r.width - 2 * by, 1), std::max(r.height - 2 * by, 1)};
}
}  // namespace

int wrappedLines(int lines, int naturalWidth, int width) {
  if (width >= naturalWidth) return lines;
  return (lines * naturalWidth + std::max(width, 1) - 1) / std::max(width, 1);
}

Layout computeLayout(int windowWidth, int windowHeight, bool panelShown, int paneCount, const LayoutMetrics& m) {
  Layout layout;
  const int fraction = static_cast<int>(m.panelFraction * windowWidth);
  const int panel = panelShown ? std::min({m.panelWidth, std::max(fraction, m.minPanelWidth), windowWidth / 2}) : 0;
  const int width = windowWidth - panel;
  layout.panel = {width, 0, panel, windowHeight};
  const bool compare = paneCount > 1;
  const int top = barHeight(wrappedLines(m.topLines, m.barWidth, width), m);
  const int bottomText = (compare ? m.compareBottomLines : m.bottomLines) + m.legendLines;
  const int bottom = barHeight(wrappedLines(bottomText, m.barWidth, width), m);
  layout.topBar = {0, 0, width, top};
  layout.bottomBar = {0, std::max(windowHeight - bottom, top), width, bottom};
  const PixelRect area{0, top, width, std::max(layout.bottomBar.y - top, 1)};
  layout.panes = splitPanes(area, paneCount);
  for (const PixelRect& pane : layout.panes) {
    PixelRect header{pane.x, pane.y, pane.width, 0};
    PixelRect world = pane;
    if (compare) {
      header.height = std::min(barHeight(wrappedLines(m.paneHeaderLines, m.paneHeaderWidth, pane.width), m), pane.height / 2);
      world.y += header.height;
      world.height -= header.height;
    }
    layout.headers.push_back(header);
    layout.worlds.push_back(inset(world, m.gutter));
  }
  return layout;
}

bool intersects(const PixelRect& a, const PixelRect& b) {
  return a.width > 0 && a.height > 0 && b.width > 0 && b.height > 0 && a.x < b.x + b.width && b.x < a.x + a.width &&
         a.y < b.y + b.height && b.y < a.y + a.height;
}

}  // namespace demo
