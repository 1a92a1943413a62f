// Text around the panes, in the margins the layout reserves for it (layout.h):
// the top bar (scene, hint, messages), the bottom bar (HUD, keys, force
// legend), the per-pane headers of compare mode, the out-of-view indicators
// in each pane's gutter, and the help overlay (key h), the one text drawn
// over the scene, on request.
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "app.h"
#include "divergence_words.h"
#include "output/format_number.h"
#include "particles/threads.h"
#include "text_layout.h"

namespace demo {

namespace {
// What the mouse does, for the help overlay (the keys come from App::keyBindings()).
struct MouseHelp {
  const char* buttons;
  const char* action;
};
constexpr MouseHelp mouseHelp[] = {
    {"left drag", "pull a particle with the mouse joint (5 Hz, damping ratio 0.7)"},
    {"right drag, shift+left", "pin a particle and move it; click a pinned one to unpin"},
    {"wheel", "zoom about the cursor"},
    {"middle drag, space+drag", "pan"},
};

// The HUD's text ({fmt}: the same presentations as printf's).
using fmt::format;

ImU32 colour(Rgb c, int alpha = 255) { return IM_COL32(c.r, c.g, c.b, alpha); }
const ImU32 titleColour = IM_COL32(255, 217, 115, 255);
const ImU32 dimColour = IM_COL32(150, 155, 165, 255);
constexpr Rgb barColour{14, 16, 20};

// Fills the bar (a backdrop, App::backdrops_) and writes its lines, wrapped
// to its width: the bar is the overlay's rectangle, its text the overlay's text. Lines beyond what the
// bar holds are left out, the last one kept ending in "...", and the overlay
// says so.
// `text` keeps the bar's layout between frames (text_layout.h).
Overlay drawBar(const char* kind, const PixelRect& r, const std::vector<Line>& lines, int lineHeight, int padding,
                WrappedText& text, std::vector<Backdrop>& backdrops) {
  constexpr float margin = 8.0f;
  const float width = r.width - 2.0f * margin;
  const std::size_t holds = static_cast<std::size_t>(std::max((r.height - 2 * padding) / lineHeight, 1));
  const std::vector<Line>& wrapped = text.layout(lines, width, holds, dimColour);
  Overlay overlay{kind, r, ""};
  overlay.shortened = text.shortened();
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const ImVec2 a(r.x, r.y), b(r.x + r.width, r.y + r.height);
  backdrops.push_back({r, barColour});
  draw->PushClipRect(a, b, true);
  float y = r.y + padding;
  for (const Line& line : wrapped) {
    float x = r.x + margin;
    for (const Piece& piece : line) {
      draw->AddText(ImVec2(x, y), piece.colour, piece.text.c_str());
      x += textWidth(piece.text);
      overlay.text += piece.text;
    }
    overlay.textWidth = std::max(overlay.textWidth, static_cast<int>(std::ceil(x - r.x + margin)));
    overlay.text += "\n";
    y += lineHeight;
  }
  overlay.textHeight = static_cast<int>(wrapped.size()) * lineHeight + 2 * padding;
  draw->PopClipRect();
  return overlay;
}

using output::plural;
}  // namespace

// Why a pane shows what it shows, beyond its numbers: stopped, slow motion,
// or a dt longer than a frame.
std::string App::paneStateLine(const Simulation& sim, bool brief) const {
  if (sim.divergedAt())
    return brief ? format("diverged at t = {:.3f} s ({}): r resets, b rewinds", *sim.divergedAt(),
                          divergenceInWords(sim.divergence(), true))
                 : format("diverged at t = {:.3f} s: {}. {}", *sim.divergedAt(), divergenceInWords(sim.divergence()),
                          divergenceRemedy());
  if (sim.refusal()) return *sim.refusal() + ": press i for another integrator";
  // The frame's stepping budget (frame_budget.h), shared by the panes.
  const FrameStats& f = sim.lastFrame();
  const double budget = options_.stepBudgetMs;
  if (f.longestStepMs > budget)
    return format("one step takes {:.3g} ms, more than the {:.3g} ms stepping budget of a frame (slow motion)",
                  f.longestStepMs, budget);
  if (f.waited) return format("waiting: the other panes spent this frame's {:.3g} ms stepping budget (slow motion)", budget);
  if (f.capped) return format("slow motion: {} steps/frame fill the {:.3g} ms stepping budget (+ doubles dt)", f.substeps, budget);
  // Paced frames that fall behind the wall clock for any reason (drawing, a
  // slow machine): said as slow motion, with where the frame's time goes.
  if (paced_ && !paused_ && realTime_.known() && realTime_.ratio() < RealTimeMeter::kSlowMotionBelow)
    return format("slow motion: {:.2f}x real time (a frame: stepping {:.0f} ms, drawing {:.0f} ms)", realTime_.ratio(),
                  f.simulationMs, sceneDrawMs_ + overlayDrawMs_);
  const double frameTime = speed_ / 60.0;
  if (stepMode_ == StepMode::FixedTime && sim.dt() > frameTime)
    return format("dt {:g} s > one frame ({:.3g} s): a step every {:.0f} frames, drawn between steps (- halves dt)",
                  sim.dt(), frameTime, std::ceil(sim.dt() / frameTime));
  return "";
}

// "0.98x real time" over the last second; "flat out" names a scripted run
// that does not keep to the clock.
std::string App::realTimeReadout() const {
  if (paused_) return "paused";
  if (!realTime_.known()) return "real time: measuring";
  return format("{:.2f}x real time{}", realTime_.ratio(), paced_ ? "" : " (flat out)");
}

// What the ghost shows, where the scene has a closed form and it is on.
std::string App::ghostLabel() const {
  if (!exact_ || !drawOptions_.ghost) return "";
  if (disturbedAt_) return format("   ghost off: moved by the mouse at t = {:.2f} s (r resets)", *disturbedAt_);
  return "   ghost: the closed form from the start";
}

// The title's summary: the first pane's scene's caption, else its table
// summary, else "scene file".
std::string App::sceneSummary() const {
  const Simulation& first = *panes_.front();
  if (!first.scene().caption.empty()) return first.scene().caption;
  const scenes::SceneInfo* info = scenes::findScene(scene_.name);
  return info ? info->summary : "scene file";
}

// The first pane's particles outside its view (not counting non-finite ones).
int App::particlesOutOfView() const {
  const Simulation& first = *panes_.front();
  const ViewTransform view = paneViews()[0];
  int outside = 0;
  for (int i = 0; i < first.system().size(); ++i) {
    const Eigen::Vector2d x = first.system().position(i);
    if (!x.allFinite()) continue;
    outside += x.x() < view.worldMin.x() || x.x() > view.worldMax.x() || x.y() < view.worldMin.y() ||
               x.y() > view.worldMax.y();
  }
  return outside;
}

void App::drawTopBar() {
  const LayoutMetrics m;
  const Layout l = layout();
  const Simulation& first = *panes_.front();
  const std::string summary = sceneSummary();
  // The title line: the scene, its time, then its summary, which is what a
  // narrow window shortens.
  Line title{{scene_.label, titleColour}};
  if (panes_.size() == 1)
    title.push_back({format("   t = {:.2f} s{}", first.timeReached(), paused_ ? "   [paused]" : ""), colour(palette::hudText)});
  else
    title.push_back({paused_ ? "   [paused]" : "   " + realTimeReadout(), colour(palette::hudText)});
  title.push_back({"   " + summary, dimColour});

  // The message line: an error or status first, then what the single pane's
  // state needs said, then the scene's hint (for its first seconds), then
  // particles out of view, then the first-run hint. A long message takes the title's line too.
  std::string message;
  ImU32 messageColour = colour(palette::hudText);
  const int outOfView = particlesOutOfView();
  // In compare mode the first pane that stopped says why in full here (its header says it briefly).
  std::string state = panes_.size() == 1 ? paneStateLine(first) : "";
  for (std::size_t k = 0; k < panes_.size() && panes_.size() > 1 && state.empty(); ++k)
    if (panes_[k]->stopped()) state = format("pane {} ({}): {}", k + 1, panes_[k]->integratorName(), paneStateLine(*panes_[k]));
  if (statusFrames_ > 0) {
    message = status_;
    if (statusIsError_) messageColour = colour(palette::divergenceText);
  } else if (!state.empty()) {
    message = state;
    if (first.stopped() || panes_.size() > 1) messageColour = colour(palette::divergenceText);
  } else if (frame_ < hintUntilFrame_ && !sceneHint_.empty()) {
    message = sceneHint_;  // the table's line, "try this: ..."
  } else if (outOfView > 0) {
    message = plural(outOfView, "particle") + " out of view (arrows at the edge): a frames all";
    messageColour = titleColour;
  } else if (!grabbedOnce_) {
    message = "drag any particle with the left mouse button; h lists the keys";
  }
  // The scene's name and time always lead; a message too long for the lines
  // below the title follows them on the title's line instead of the summary.
  const float width = l.topBar.width - 16.0f;
  const std::size_t holds = static_cast<std::size_t>((l.topBar.height - 2 * m.padding) / m.lineHeight);
  std::vector<Line> lines;
  if (message.empty() || wrapLine({{message, messageColour}}, width).size() < holds) {
    const std::vector<Line> titleLines = wrapLine(title, width);
    lines.push_back(titleLines.size() > 1 ? shortened(titleLines.front(), width, dimColour) : titleLines.front());
    if (!message.empty()) lines.push_back({{message, messageColour}});
  } else {
    Line nameAndMessage(title.begin(), title.end() - 1);  // without the summary
    nameAndMessage.push_back({"   " + message, messageColour});
    lines.push_back(nameAndMessage);
  }
  overlays_.push_back(drawBar("top-bar", l.topBar, lines, m.lineHeight, m.padding, barText_["top-bar"], backdrops_));
}

void App::drawBottomBar() {
  const LayoutMetrics m;
  const Layout l = layout();
  std::vector<Line> lines;
  if (panes_.size() == 1) {
    const Simulation& sim = *panes_.front();
    const particles::ParticleSystem& s = sim.system();
    const FrameStats& f = sim.lastFrame();
    const ImU32 text = colour(palette::hudText);
    const std::string state = paneStateLine(sim, true);  // the top bar says it in full
    // Steps of dt per frame; xpbd's own substeps within each step apart.
    const auto& scheme = particles::integratorTable()[sim.integratorIndex()];
    const std::string within =
        scheme.usesSubsteps ? format(" ({} each)", plural(sim.integratorSettings().xpbd.substeps, "xpbd substep")) : "";
    lines.push_back({{format("{}   dt {:g} s   {}/frame{}{}", sim.integratorName(), sim.dt(), plural(f.substeps, "step"),
                             within, stepMode_ == StepMode::Lockstep ? " (lockstep)" : ""),
                      text},
                     {ghostLabel(), colour(palette::ghost)}});
    // The pane's state on a line of its own (the top bar may show a status instead).
    lines.push_back({{state, sim.stopped() ? colour(palette::divergenceText) : titleColour}});
    // Fixed-width numbers, so that the line does not jitter from frame to frame.
    lines.push_back({{format("simulation {:7.2f} ms   draw {:6.1f} ms (scene {:5.1f} + text and panel {:5.1f})   per frame   {}",
                             f.simulationMs, sceneDrawMs_ + overlayDrawMs_, sceneDrawMs_, overlayDrawMs_,
                             realTimeReadout()),
                      text}});
    std::string numbers = plural(s.size(), "particle");
    // The last step's statistics: every solve of it, not only the last one.
    const particles::StepStats& step = s.lastStepStats();
    if (step.solves > 0)
      numbers += step.cgIterations == 0
                     ? format("   {}, residual {:.1e}", plural(step.solves, "solve"), step.maxResidual)
                     : format("   {}, CG {} iterations, residual {:.1e}", plural(step.solves, "solve"),
                              step.cgIterations, step.maxResidual);
    numbers += format("   max |C| {:.2e}   energy {: .5e}   threads {}/{}", s.maxConstraintError(), sim.sceneEnergy(),
                      step.threads, particles::threadCount());
    if (s.colliding()) numbers += format("   contacts {}   asleep {}", s.contactsLastStep(), step.sleeping);
    if (sim.mouseSpring()) numbers += format("   (mouse spring {: .3e} apart)", sim.mouseSpringEnergy());
    lines.push_back({{numbers, text}});
  }
  lines.push_back({{"h help   p panel   v compare   a frame all   wheel zoom   middle-drag pan", dimColour}});
  if (drawOptions_.forces) {
    Line legend;
    // Which colour is which force type, for the types in the first pane.
    const particles::ParticleSystem& s = panes_.front()->system();
    std::vector<std::string> types;
    for (const auto& force : s.forceObjects())
      if (std::find(types.begin(), types.end(), force->type()) == types.end()) types.push_back(force->type());
    legend.push_back({"arrows:", dimColour});
    for (const std::string& type : types) legend.push_back({" --> " + type, colour(forceArrowColour(type.c_str())), true});
    if (!s.constraints().empty()) legend.push_back({" --> J^T lambda", colour(palette::constraintForceArrow), true});
    lines.push_back(legend);
  }
  overlays_.push_back(drawBar("hud", l.bottomBar, lines, m.lineHeight, m.padding, barText_["hud"], backdrops_));
}

void App::drawPaneHeaders() {
  const LayoutMetrics m;
  const Layout l = layout();
  for (std::size_t k = 0; k < panes_.size(); ++k) {
    const Simulation& sim = *panes_[k];
    const particles::ParticleSystem& s = sim.system();
    const ImU32 text = colour(palette::hudText);
    std::vector<Line> lines;
    lines.push_back({{format("{}  {}", k + 1, sim.integratorName()), titleColour},
                     {format("   dt {:g} s   t = {:.2f} s   {} steps", sim.dt(), sim.timeReached(), sim.steps()), text}});
    lines.push_back({{format("E {: .5e}   max |C| {:.1e}   {:.2f} ms/frame", sim.sceneEnergy(), s.maxConstraintError(),
                             sim.lastFrame().simulationMs),
                      text}});
    lines.push_back({{paneStateLine(sim, true), sim.stopped() ? colour(palette::divergenceText) : titleColour}});
    overlays_.push_back(
        drawBar("pane-hud", l.headers[k], lines, m.lineHeight, m.padding, barText_["pane-hud " + std::to_string(k)], backdrops_));
  }
}

// Where particles have left the view: a triangle in the gutter on each side
// they are beyond, pointing at them, and a frame around a stopped pane.
void App::drawOutOfViewIndicators() {
  const std::vector<ViewTransform> views = paneViews();
  const LayoutMetrics m;
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  for (std::size_t k = 0; k < panes_.size(); ++k) {
    const ViewTransform& v = views[k];
    const PixelRect& p = v.pane;
    if (panes_[k]->stopped())
      draw->AddRect(ImVec2(p.x - 3, p.y - 3), ImVec2(p.x + p.width + 3, p.y + p.height + 3), colour(palette::divergenceText),
                    0.0f, 0, 2.0f);
    // Per side: how many are beyond it, and the mean of their clamped pixel positions along it.
    int count[4] = {0, 0, 0, 0};
    double along[4] = {0, 0, 0, 0};
    const particles::ParticleSystem& s = panes_[k]->system();
    for (int i = 0; i < s.size(); ++i) {
      const Eigen::Vector2d x = s.position(i);
      if (!x.allFinite()) continue;
      const Eigen::Vector2d px = v.toPixel(x);
      const double cx = std::clamp(px.x(), double(p.x), double(p.x + p.width));
      const double cy = std::clamp(px.y(), double(p.y), double(p.y + p.height));
      const int side = px.x() < p.x ? 0 : px.x() > p.x + p.width ? 1 : px.y() < p.y ? 2 : px.y() > p.y + p.height ? 3 : -1;
      if (side < 0) continue;
      ++count[side];
      along[side] += side < 2 ? cy : cx;
    }
    const float g = static_cast<float>(m.gutter), h = 0.5f * g;
    for (int side = 0; side < 4; ++side) {
      if (count[side] == 0) continue;
      const float t = static_cast<float>(along[side] / count[side]);
      ImVec2 tip, b, c;
      switch (side) {
        case 0: tip = {p.x - g + 1, t}; b = {p.x - 1.0f, t - h}; c = {p.x - 1.0f, t + h}; break;
        case 1: tip = {p.x + p.width + g - 1, t}; b = {p.x + p.width + 1.0f, t - h}; c = {p.x + p.width + 1.0f, t + h}; break;
        case 2: tip = {t, p.y - g + 1}; b = {t - h, p.y - 1.0f}; c = {t + h, p.y - 1.0f}; break;
        default: tip = {t, p.y + p.height + g - 1}; b = {t - h, p.y + p.height + 1.0f}; c = {t + h, p.y + p.height + 1.0f};
      }
      draw->AddTriangleFilled(tip, b, c, titleColour);
      const float x0 = std::min({tip.x, b.x, c.x}), y0 = std::min({tip.y, b.y, c.y});
      const float x1 = std::max({tip.x, b.x, c.x}), y1 = std::max({tip.y, b.y, c.y});
      overlays_.push_back({"indicator",
                           {static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(x1 - x0) + 1, static_cast<int>(y1 - y0) + 1},
                           plural(count[side], "particle") + " out of view"});
    }
  }
}

namespace {
// One row of the help: keys and what they do, or a heading.
struct HelpRow {
  std::string keys, action;
  bool heading = false;
};

// The help's rows laid out in `columns` columns of equal width across
// `width` pixels: each action wrapped beside its keys (below them, indented,
// when the keys are wider than the key column), rows filling a column to
// `heightLines` lines before the next begins. fits: every row placed.
struct HelpLayout {
  static constexpr float gap = 18.0f, keyGap = 10.0f;
  int columns = 1;
  float columnWidth = 0.0f, keyWidth = 0.0f;
  std::vector<std::vector<Line>> actions;  // per row, the action's lines
  std::vector<bool> keysAbove;             // per row: its keys on a line of their own
  std::vector<int> column;                 // per row, its column (−1: left out)
  int tallest = 0;                         // the fullest column's lines
  bool fits = true;
  int lines(std::size_t row) const { return static_cast<int>(actions[row].size()) + (keysAbove[row] ? 1 : 0); }
};

HelpLayout layoutHelp(const std::vector<HelpRow>& rows, int columns, float width, int heightLines) {
  HelpLayout l;
  l.columns = columns;
  l.columnWidth = (width - HelpLayout::gap * static_cast<float>(columns - 1)) / static_cast<float>(columns);
  // The key column is as wide as the widest keys that fit in a third of the column.
  const float keyLimit = l.columnWidth / 3.0f;
  for (const HelpRow& row : rows)
    if (!row.heading && textWidth(row.keys) + HelpLayout::keyGap <= keyLimit)
      l.keyWidth = std::max(l.keyWidth, textWidth(row.keys) + HelpLayout::keyGap);
  int column = 0, used = 0;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const HelpRow& row = rows[r];
    l.keysAbove.push_back(!row.heading && textWidth(row.keys) + HelpLayout::keyGap > l.keyWidth);
    l.actions.push_back(row.heading ? std::vector<Line>{{{row.keys, titleColour}}}
                                    : wrapLine({{row.action, colour(palette::hudText)}}, l.columnWidth - l.keyWidth));
    const int lines = l.lines(r);
    // A heading never ends a column: it starts the next one instead.
    const int needed = row.heading && r + 1 < rows.size() ? lines + 1 : lines;
    if (used + needed > heightLines && used > 0) {
      ++column;
      used = 0;
    }
    if (column >= columns || lines > heightLines) {
      l.column.push_back(-1);
      l.fits = false;
      continue;
    }
    l.column.push_back(column);
    used += lines;
    l.tallest = std::max(l.tallest, used);
  }
  return l;
}
// Draws the laid-out rows below the title line from `origin` (the box's
// corner inside its padding), appending each row to `text`; returns the
// rightmost x drawn.
float drawHelpRows(ImDrawList* draw, const std::vector<HelpRow>& rows, const HelpLayout& layout, ImVec2 origin,
                   float lineHeight, std::string& text) {
  const float columnStep = layout.columnWidth + HelpLayout::gap;
  std::vector<int> usedLines(static_cast<std::size_t>(layout.columns), 1);
  float right = origin.x;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const int c = layout.column[r];
    if (c < 0) continue;
    const float x = origin.x + static_cast<float>(c) * columnStep;
    float y = origin.y + static_cast<float>(usedLines[c]) * lineHeight;
    usedLines[c] += layout.lines(r);
    draw->AddText(ImVec2(x, y), titleColour, rows[r].keys.c_str());
    right = std::max(right, x + textWidth(rows[r].keys));
    if (rows[r].heading) {
      text += rows[r].keys + ":\n";
      continue;
    }
    if (layout.keysAbove[r]) y += lineHeight;
    for (const Line& line : layout.actions[r]) {
      float lx = x + layout.keyWidth;
      for (const Piece& piece : line) {
        draw->AddText(ImVec2(lx, y), piece.colour, piece.text.c_str());
        lx += textWidth(piece.text);
      }
      right = std::max(right, lx);
      y += lineHeight;
    }
    text += rows[r].keys + ": " + rows[r].action + "\n";
  }
  return right;
}
}  // namespace

// The help (key h): every scene key, key and mouse action, drawn over the
// window (the one text over the scene and the panel, on request) in as few
// columns as hold every row; the overlay records what it drew and whether
// every row found a place.
void App::drawHelp() {
  const LayoutMetrics m;
  std::vector<HelpRow> rows;
  rows.push_back({"scenes (the panel's list has the gallery too)", "", true});
  for (const SceneKey& k : sceneKeys()) rows.push_back({std::string(1, static_cast<char>(k.key)), k.choice.label});
  rows.push_back({"keys", "", true});
  for (const KeyBinding& k : keyBindings())
    if (k.label) rows.push_back({k.label, k.help});
  rows.push_back({"mouse", "", true});
  for (const MouseHelp& mh : mouseHelp) rows.push_back({mh.buttons, mh.action});

  constexpr float margin = 6.0f, padding = 10.0f;
  const float width = static_cast<float>(windowWidth_) - 2.0f * (margin + padding);
  // The lines below the title line.
  const int heightLines = std::max(1, static_cast<int>((static_cast<float>(windowHeight_) - 2.0f * (margin + padding)) /
                                                       static_cast<float>(m.lineHeight)) - 1);
  HelpLayout layout = layoutHelp(rows, 1, width, heightLines);
  for (int columns = 2; !layout.fits && columns <= 4; ++columns) layout = layoutHelp(rows, columns, width, heightLines);

  // One column is as wide as its longest line; more fill the width.
  float usedWidth = width;
  if (layout.columns == 1) {
    usedWidth = 0.0f;
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (const Line& line : layout.actions[r])
        usedWidth = std::max(usedWidth, (rows[r].heading ? 0.0f : layout.keyWidth) + lineWidth(line));
  }
  const float boxWidth = usedWidth + 2.0f * padding;
  const float boxHeight = static_cast<float>((layout.tallest + 1) * m.lineHeight) + 2.0f * padding;
  const float x0 = std::floor(std::max(margin, 0.5f * (static_cast<float>(windowWidth_) - boxWidth)));
  const float y0 = std::floor(std::max(margin, 0.5f * (static_cast<float>(windowHeight_) - boxHeight)));
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  draw->AddRectFilled(ImVec2(x0, y0), ImVec2(x0 + boxWidth, y0 + boxHeight), IM_COL32(14, 16, 20, 242), 4.0f);
  draw->AddRect(ImVec2(x0, y0), ImVec2(x0 + boxWidth, y0 + boxHeight), colour(palette::paneBorder), 4.0f);
  Overlay overlay{"help", {static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(std::ceil(boxWidth)),
                           static_cast<int>(std::ceil(boxHeight))}, ""};
  const std::string title = layout.fits ? "the keys (h closes this)" : "the keys (h closes this; the window is too small for all)";
  draw->AddText(ImVec2(x0 + padding, y0 + padding), dimColour, title.c_str());
  float right = padding + textWidth(title);
  right = std::max(right, drawHelpRows(draw, rows, layout, ImVec2(x0 + padding, y0 + padding),
                                       static_cast<float>(m.lineHeight), overlay.text) - x0);
  overlay.textWidth = static_cast<int>(std::ceil(right + padding));
  overlay.textHeight = static_cast<int>(std::ceil(static_cast<float>((layout.tallest + 1) * m.lineHeight) + 2.0f * padding));
  overlay.shortened = !layout.fits;
  overlays_.push_back(overlay);
}

}  // namespace demo
