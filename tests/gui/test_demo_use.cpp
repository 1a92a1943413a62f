// particle-demo as a new user meets it: the layout, the camera, the mouse
// joint, onboarding and honest drawing, and each bug found by use (numbered
// B01, B02, ... in the test names).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>

#include "particles/constants.h"
#include "demo_driver.h"
#include "exact_motion.h"
#include "scene.h"

using namespace demotest;

namespace {
const char* const noPanel = "--no-panel --window 900x700";

// A scripted click: the pointer moves there a frame before the press (so that
// ImGui knows it is over the panel), the release a frame after.
std::string clickAt(long long frame, const LoggedOverlay& w) {
  std::ostringstream s;
  const Eigen::Vector2d c = w.centre();
  s << frame << " move window " << c.x() << " " << c.y() << "\n"
    << frame + 1 << " down window " << c.x() << " " << c.y() << "\n"
    << frame + 2 << " up window " << c.x() << " " << c.y() << "\n";
  return s.str();
}

std::string dragScript(const Eigen::Vector2d& from, const Eigen::Vector2d& to, int startFrame, int frames) {
  std::ostringstream s;
  s << startFrame << " down world " << from.x() << " " << from.y() << "\n";
  for (int k = 1; k <= frames; ++k) {
    const Eigen::Vector2d at = from + (to - from) * (double(k) / frames);
    s << startFrame + k << " move world " << at.x() << " " << at.y() << "\n";
  }
  return s.str();
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Every particle drawn in its pane's world rectangle lies under no overlay
// (the help, shown only on request, aside).
void expectNoOverlayOnAParticle(const StateLog& log) {
  for (const LoggedPane& pane : log.panes)
    for (const LoggedParticle& q : pane.particles) {
      const Eigen::Vector2d px = pane.toPixel(q.x);
      if (!pane.inWorldRect(px)) continue;
      for (const LoggedOverlay& o : log.overlays)
        if (o.kind != "help") {
          EXPECT_FALSE(o.covers(px, 0)) << o.kind << " covers a particle at " << px.transpose();
        }
    }
}
}  // namespace

// ---------------------------------------------------------------------------
// Layout: text in reserved margins, never on the scene

TEST(DemoLayout, NoOverlayCoversTheWorldInAnyModeOrScene) {
  const std::string dir = outputDirectory("LayoutNoOverlay");
  for (const std::string& args : {std::string("--scene cloth"), std::string("--scene test-chain --compare euler,rk4,midpoint,verlet"),
                                  std::string("--scene hair"), std::string("--scene wire --compare rk4:0.5,rk4")}) {
    SCOPED_TRACE(args);
    // f shows the legend, and a long message fills the top bar.
    ASSERT_EQ(runDemo(dir, args + " --frames 90 --log-state state.txt", "2 key f\n3 key +\n").exitCode, 0);
    const StateLog log = readStateLog(dir + "/state.txt");
    for (const LoggedPane& pane : log.panes) {
      const LoggedOverlay world{"world", pane.pixelX, pane.pixelY, pane.pixelWidth, pane.pixelHeight, ""};
      for (const LoggedOverlay& o : log.overlays) {
        EXPECT_FALSE(o.x < world.x + world.width && world.x < o.x + o.width && o.y < world.y + world.height &&
                     world.y < o.y + o.height)
            << o.kind << " at " << o.x << "," << o.y << " " << o.width << "x" << o.height << " overlaps the world";
      }
    }
    expectNoOverlayOnAParticle(log);
  }
}

TEST(DemoLayout, LongErrorMessageWrapsInsideTheTopBar) {
  const std::string dir = outputDirectory("LongMessage");
  // The panel's scene parameter field is the place for a long error; here a
  // dt doubled past the largest double gives one from the keyboard.
  const RunResult r = runDemo(dir, std::string(noPanel) + " --scene oscillator --dt 1e308 --frames 5 --log-state state.txt",
                              "1 key +\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  const LoggedOverlay* top = log.overlay("top-bar");
  ASSERT_NE(top, nullptr);
  EXPECT_TRUE(contains(top->text, "cannot be doubled further")) << top->text;
  EXPECT_EQ(top->x, 0);
  EXPECT_EQ(top->width, 900);
}

// ---------------------------------------------------------------------------
// Camera

TEST(DemoCamera, WheelZoomsAboutTheCursor) {
  const std::string dir = outputDirectory("Zoom");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --paused --frames 3 --log-state before.txt").exitCode, 0);
  const LoggedPane before = readStateLog(dir + "/before.txt").panes.at(0);
  const Eigen::Vector2d at(0.3, -0.2);
  ASSERT_EQ(runDemo(dir, "--scene pendulum --paused --frames 3 --log-state after.txt", "1 wheel world 0.3 -0.2 3\n").exitCode, 0);
  const LoggedPane after = readStateLog(dir + "/after.txt").panes.at(0);
  const double zoom = (before.worldMax.x() - before.worldMin.x()) / (after.worldMax.x() - after.worldMin.x());
  EXPECT_NEAR(zoom, 1.2 * 1.2 * 1.2, 1e-9);
  // The world point under the cursor keeps its pixel (the cursor is on a whole pixel).
  EXPECT_LT((before.toPixel(at) - after.toPixel(at)).norm(), 0.5);
}

// A (shift+a) brings back the scene's own view after a zoom and a frame-all,
// and the scene runs on: its steps and time are those of a run without it.
TEST(DemoCamera, SceneViewKeyResetsTheCameraAndKeepsTheScene) {
  const std::string dir = outputDirectory("SceneView");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 20 --log-state plain.txt").exitCode, 0);
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 20 --log-state moved.txt", "2 wheel world 0.3 -0.2 3\n4 key a\n").exitCode,
            0);
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 20 --log-state back.txt", "2 wheel world 0.3 -0.2 3\n4 key a\n6 key A\n")
                .exitCode, 0);
  const LoggedPane plain = readStateLog(dir + "/plain.txt").panes.at(0);
  const LoggedPane moved = readStateLog(dir + "/moved.txt").panes.at(0);
  const LoggedPane back = readStateLog(dir + "/back.txt").panes.at(0);
  EXPECT_GT((moved.worldMin - plain.worldMin).norm(), 1e-3);  // the view did move
  EXPECT_LT((back.worldMin - plain.worldMin).norm(), 1e-12);
  EXPECT_LT((back.worldMax - plain.worldMax).norm(), 1e-12);
  EXPECT_EQ(back.steps, plain.steps);
  EXPECT_EQ(back.particles.back().x, plain.particles.back().x);
}

TEST(DemoCamera, MiddleDragAndSpaceDragPanWithoutPausing) {
  const std::string dir = outputDirectory("Pan");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 3 --log-state before.txt").exitCode, 0);
  const LoggedPane before = readStateLog(dir + "/before.txt").panes.at(0);
  const int x = before.pixelX + 100, y = before.pixelY + 100;
  for (const std::string& press : {std::string("1 down window X Y middle\n"), std::string("0 keydown space\n1 down window X Y\n")}) {
    SCOPED_TRACE(press);
    std::string script = std::regex_replace(std::regex_replace(press, std::regex("X"), std::to_string(x)), std::regex("Y"),
                                            std::to_string(y));
    script += "2 move window " + std::to_string(x + 50) + " " + std::to_string(y + 20) + "\n3 up window " +
              std::to_string(x + 50) + " " + std::to_string(y + 20) + "\n4 keyup space\n";
    ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 6 --log-state after.txt", script).exitCode, 0);
    const StateLog log = readStateLog(dir + "/after.txt");
    const LoggedPane& after = log.panes.at(0);
    const double ppu = before.pixelWidth / (before.worldMax.x() - before.worldMin.x());
    EXPECT_NEAR(after.worldMin.x() - before.worldMin.x(), -50 / ppu, 1e-9);
    EXPECT_NEAR(after.worldMin.y() - before.worldMin.y(), 20 / ppu, 1e-9);
    EXPECT_FALSE(log.paused);          // space used for a pan is not a pause
    EXPECT_EQ(after.mouseSprings, 0);  // and grabbed nothing
  }
}

TEST(DemoCamera, ParticlesOutOfViewAreIndicatedAndFrameAllBringsThemBack) {
  // The test chain's root unpinned: the chain falls out of view for good.
  const std::string dir = outputDirectory("FrameAll");
  ASSERT_EQ(runDemo(dir, "--scene test-chain --frames 1 --paused --log-state start.txt").exitCode, 0);
  const LoggedPane start = readStateLog(dir + "/start.txt").panes.at(0);
  int root = -1;
  for (std::size_t i = 0; i < start.particles.size(); ++i)
    if (start.particles[i].pinned) root = static_cast<int>(i);
  ASSERT_GE(root, 0);
  const Eigen::Vector2d r = start.particles[root].x;
  std::ostringstream unpin;
  unpin << "2 down world " << r.x() << " " << r.y() << " right\n3 up world " << r.x() << " " << r.y() << " right\n";
  ASSERT_EQ(runDemo(dir, std::string(noPanel) + " --scene test-chain --frames 600 --log-state fallen.txt", unpin.str())
                .exitCode, 0);
  const StateLog fallen = readStateLog(dir + "/fallen.txt");
  const LoggedPane& pane = fallen.panes.at(0);
  int visible = 0;
  for (const LoggedParticle& q : pane.particles) visible += pane.inWorldRect(pane.toPixel(q.x));
  ASSERT_EQ(visible, 0) << "the chain should have fallen out of view";
  const LoggedOverlay* indicator = fallen.overlay("indicator");
  ASSERT_NE(indicator, nullptr);
  EXPECT_GT(indicator->y, pane.pixelY + pane.pixelHeight - 1);  // in the gutter below the world
  EXPECT_TRUE(contains(fallen.overlay("top-bar")->text, "out of view")) << fallen.overlay("top-bar")->text;
  EXPECT_TRUE(contains(fallen.overlay("top-bar")->text, "a frames all"));

  ASSERT_EQ(runDemo(dir, std::string(noPanel) + " --scene test-chain --frames 601 --log-state framed.txt",
                    unpin.str() + "600 key space\n600 key a\n").exitCode, 0);  // paused, so the framed chain stays put
  const StateLog framed = readStateLog(dir + "/framed.txt");
  const LoggedPane& again = framed.panes.at(0);
  for (const LoggedParticle& q : again.particles) EXPECT_TRUE(again.inWorldRect(again.toPixel(q.x)));
  EXPECT_EQ(framed.overlay("indicator"), nullptr);
}

TEST(DemoCamera, PickingGoesThroughTheCamera) {
  // Zoomed and panned, a press on a particle's pixel still grabs it.
  const std::string dir = outputDirectory("PickThroughCamera");
  ASSERT_EQ(runDemo(dir, "--scene test-chain --paused --frames 1 --log-state start.txt").exitCode, 0);
  // A particle near the root, which stays in view when zoomed in about the root.
  const Eigen::Vector2d tip = readStateLog(dir + "/start.txt").panes.at(0).particles.at(2).x;
  std::ostringstream s;
  s << "1 wheel world 0 0 4\n2 down window 300 300 middle\n3 move window 340 330\n4 up window 340 330 middle\n"
    << "6 down world " << tip.x() << " " << tip.y() << "\n7 move world " << tip.x() << " " << tip.y() << "\n";
  ASSERT_EQ(runDemo(dir, "--scene test-chain --paused --frames 9 --log-state state.txt", s.str()).exitCode, 0);
  EXPECT_EQ(readStateLog(dir + "/state.txt").panes.at(0).mouseSprings, 1);
}

// ---------------------------------------------------------------------------
// The mouse joint

TEST(DemoMouse, TheJointFollowsTheCursorBrisklyInEveryScene) {
  // A 5 Hz joint with damping ratio 0.7 settles in well under half a second:
  // 0.5 s after the cursor stops, the particle is within a few per cent of the
  // pull of the target (the seed's 0.8 Hz spring was 0.1 units behind here).
  const std::string dir = outputDirectory("BriskJoint");
  // Scenes where the grabbed particle is free to reach the target (a bead on
  // a wire or a rod's end is held back by its constraint, a hair bead by its
  // strand's stiff bending springs, not by the joint).
  for (const char* scene : {"cloth", "oscillator"}) {
    SCOPED_TRACE(scene);
    ASSERT_EQ(runDemo(dir, std::string("--scene ") + scene + " --paused --frames 1 --log-state start.txt").exitCode, 0);
    const LoggedPane start = readStateLog(dir + "/start.txt").panes.at(0);
    // The free particle nearest the middle of the view.
    int pick = -1;
    const Eigen::Vector2d middle = 0.5 * (start.worldMin + start.worldMax);
    for (std::size_t i = 0; i < start.particles.size(); ++i)
      if (!start.particles[i].pinned &&
          (pick < 0 || (start.particles[i].x - middle).norm() < (start.particles[pick].x - middle).norm()))
        pick = static_cast<int>(i);
    ASSERT_GE(pick, 0);
    const Eigen::Vector2d from = start.particles[pick].x;
    const double reach = 0.1 * (start.worldMax - start.worldMin).norm();
    const Eigen::Vector2d to = from + Eigen::Vector2d(0.6, 0.8) * reach;
    // Drag over 6 frames, then hold still for 30 frames (0.5 s).
    ASSERT_EQ(runDemo(dir, std::string("--scene ") + scene + " --frames 37 --log-state held.txt", dragScript(from, to, 0, 6))
                  .exitCode, 0);
    const LoggedPane held = readStateLog(dir + "/held.txt").panes.at(0);
    EXPECT_EQ(held.mouseSprings, 1);
    EXPECT_LT((held.particles[pick].x - to).norm(), 0.35 * reach) << "the particle lags the cursor";
  }
}

// ---------------------------------------------------------------------------
// Onboarding and honest drawing

TEST(DemoOnboarding, EachSceneOpensWithItsSummaryAndAHint) {
  const std::string dir = outputDirectory("Onboarding");
  for (const scenes::SceneInfo& info : scenes::sceneTable()) {
    SCOPED_TRACE(info.name);
    ASSERT_EQ(runDemo(dir, std::string("--scene ") + info.name + " --frames 3 --log-state state.txt").exitCode, 0);
    const std::string top = readStateLog(dir + "/state.txt").overlay("top-bar")->text;
    // A scene with a caption (the capstan's mass ratio against e^(mu theta)) shows it in place of the summary.
    const std::string caption = scenes::buildScene(info.name).caption;
    EXPECT_TRUE(contains(top, caption.empty() ? std::string(info.summary) : caption)) << top;
    EXPECT_TRUE(contains(top, info.hint)) << top;
  }
}

TEST(DemoOnboarding, HudSaysOneParticleInTheSingular) {
  const std::string dir = outputDirectory("OneParticle");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 3 --log-state state.txt").exitCode, 0);
  const std::string hud = readStateLog(dir + "/state.txt").overlay("hud")->text;
  EXPECT_TRUE(contains(hud, "1 particle ")) << hud;
  EXPECT_FALSE(contains(hud, "1 particles")) << hud;
}

TEST(DemoOnboarding, CompareKeyOnTheDefaultClothShowsPanesThatDiffer) {
  const std::string dir = outputDirectory("ComparePresets");
  ASSERT_EQ(runDemo(dir, "--frames 181 --log-state state.txt", "1 key v\n2 key v\n3 key v\n").exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_EQ(log.panes.size(), 4u);
  for (std::size_t k = 1; k < 4; ++k) {
    SCOPED_TRACE(log.panes[k].integrator);
    const bool sameScheme = log.panes[k].integrator == log.panes[0].integrator && log.panes[k].dt == log.panes[0].dt;
    EXPECT_FALSE(sameScheme);
    double largest = 0.0;
    for (std::size_t i = 0; i < log.panes[0].particles.size(); ++i)
      largest = std::max(largest, (log.panes[k].particles[i].x - log.panes[0].particles[i].x).norm());
    EXPECT_GT(largest, 1e-3) << "pane " << k + 1 << " draws the same picture as pane 1";
  }
}

TEST(DemoDrawing, ParticlesAreAtLeastSixPixelsAcross) {
  const std::string dir = outputDirectory("ParticleSize");
  for (const char* scene : {"rod-chain", "wire", "cloth"}) {
    SCOPED_TRACE(scene);
    ASSERT_EQ(runDemo(dir, std::string(noPanel) + " --scene " + scene + " --paused --frames 2 --screenshot shot.png --log-state state.txt",
                      "0 key c\n").exitCode, 0);
    const Image image = readPng(dir + "/shot.png");
    const LoggedPane pane = readStateLog(dir + "/state.txt").panes.at(0);
    int measured = 0;
    for (const LoggedParticle& q : pane.particles) {
      if (q.pinned) continue;
      const Eigen::Vector2d px = pane.toPixel(q.x);
      if (!pane.inWorldRect(px)) continue;
      // The run of particle-coloured pixels through its centre, horizontally.
      int width = 0;
      for (int dx = -8; dx <= 8; ++dx)
        width += image.inside(int(px.x()) + dx, int(px.y())) &&
                 near(image.at(int(px.x()) + dx, int(px.y())), demo::palette::particle, 40);
      EXPECT_GE(width, 5) << "at " << px.transpose();  // 6 px, less a pixel of antialiased edge
      if (++measured == 10) break;
    }
    EXPECT_GT(measured, 0);
  }
}

// A colour of the stress map: a spring's at a strain within ±20%, or a
// rod's at any load.
static bool onStressMap(demo::Rgb c) {
  for (int k = 0; k <= 20; ++k) {
    const double t = k / 20.0;
    if (near(c, demo::palette::strainColour(demo::palette::spring, 0.4 * t - 0.2), 30) ||
        near(c, demo::palette::constraintColour(demo::palette::constraint, t), 30))
      return true;
  }
  return false;
}

TEST(DemoDrawing, OscillatorSpringAndPendulumRodAreDrawn) {
  const std::string dir = outputDirectory("SpringAndRod");
  for (const char* scene : {"oscillator", "pendulum"}) {
    SCOPED_TRACE(scene);
    ASSERT_EQ(runDemo(dir, std::string(noPanel) + " --scene " + scene + " --paused --frames 2 --screenshot shot.png --log-state state.txt",
                      "0 key g\n").exitCode, 0);
    const Image image = readPng(dir + "/shot.png");
    const LoggedPane pane = readStateLog(dir + "/state.txt").panes.at(0);
    // Sample the segment from the pivot or anchor (the world origin) to the
    // last particle, away from both ends: spring or rod colour must be there.
    const Eigen::Vector2d a = pane.toPixel({0.0, 0.0}), b = pane.toPixel(pane.particles.back().x);
    int hits = 0, samples = 0;
    for (double s = 0.25; s <= 0.75; s += 0.05, ++samples) {
      const Eigen::Vector2d p = a + s * (b - a);
      bool found = false;
      for (int dy = -8; dy <= 8 && !found; ++dy)
        for (int dx = -1; dx <= 1 && !found; ++dx) {
          const demo::Rgb c = image.at(int(p.x()) + dx, int(p.y()) + dy);
          found = onStressMap(c);
        }
      hits += found;
    }
    EXPECT_GE(hits, samples - 1);
  }
}

TEST(DemoDrawing, ClosedFormGhostMatchesTheExactSolution) {
  // The pendulum's ghost from the inverted elliptic integral has the period
  // 4 K(k) / ω₀ and returns to its start; RK4 at the scene's dt stays on it.
  const double k = std::sin(0.5 * 60.0 * particles::kPi / 180.0);
  const double K = std::comp_ellint_1(k);
  for (double u : {0.1, 0.7, 1.3}) {
    // sn is the inverse of F: F(asin(sn(u)), k) = u on the first quarter period.
    EXPECT_NEAR(std::ellint_1(k, std::asin(demo::jacobiSn(u, k))), u, 1e-12);
  }
  EXPECT_NEAR(demo::jacobiSn(K, k), 1.0, 1e-12);
  EXPECT_NEAR(demo::jacobiSn(2 * K + 0.3, k), -demo::jacobiSn(0.3, k), 1e-12);

  const std::string dir = outputDirectory("Ghost");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 120 --log-state state.txt").exitCode, 0);
  const LoggedPane pane = readStateLog(dir + "/state.txt").panes.at(0);
  demo::SceneChoice choice;
  choice.name = choice.label = "pendulum";
  const scenes::Scene scene = scenes::buildScene("pendulum");
  const demo::ExactMotion exact = demo::exactMotion(choice, *scene.system);
  ASSERT_TRUE(exact);
  const demo::GhostFrame ghost = exact(pane.time);
  ASSERT_EQ(ghost.points.size(), 1u);
  EXPECT_LT((ghost.points[0] - pane.particles[0].x).norm(), 1e-4);
}

// ---------------------------------------------------------------------------
// The bugs found by use, numbered B01, B02, ...

TEST(DemoBugs, B01_EscClosesAnOpenComboInsteadOfQuitting) {
  const std::string dir = outputDirectory("EscCombo");
  ASSERT_EQ(runDemo(dir, "--frames 2 --log-state layout.txt").exitCode, 0);
  const StateLog layout = readStateLog(dir + "/layout.txt");
  const LoggedOverlay* combo = layout.widget("scene");
  ASSERT_NE(combo, nullptr);
  const std::string open = clickAt(2, *combo);
  ASSERT_EQ(runDemo(dir, "--frames 8 --log-state opened.txt", open).exitCode, 0);
  EXPECT_NE(readStateLog(dir + "/opened.txt").widget("scene-list"), nullptr) << "the click opens the list";
  const RunResult r = runDemo(dir, "--frames 30 --log-state state.txt", open + "8 key esc\n");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  EXPECT_EQ(log.frames, 30) << "Esc quit instead of closing the list";
  EXPECT_EQ(log.widget("scene-list"), nullptr);
  // With no list open, Esc quits.
  EXPECT_EQ((runDemo(dir, "--frames 30 --log-state state.txt", "8 key esc\n").exitCode), 0);
  EXPECT_EQ(readStateLog(dir + "/state.txt").frames, 9);
}

TEST(DemoBugs, B02_RewindBringsEveryComparePaneToOneTime) {
  // One pane diverges early, the others run on for 18 s, far past what a
  // fixed window of snapshots keeps; b must still find one common time.
  const std::string dir = outputDirectory("RewindCommonTime");
  const std::string args = std::string(noPanel) + " --scene test-chain --compare rk4:0.5,rk4:0.01,midpoint:0.01,verlet:0.01 ";
  ASSERT_EQ(runDemo(dir, args + "--frames 1082 --log-state state.txt", "1080 key b\n").exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_EQ(log.panes.size(), 4u);
  EXPECT_TRUE(log.paused);
  for (const LoggedPane& pane : log.panes) {
    SCOPED_TRACE(pane.integrator);
    EXPECT_FALSE(pane.diverged);
    EXPECT_EQ(pane.framesAdvanced, log.panes[0].framesAdvanced);
    // t + owed time is the shared clock, frames / 60 s.
    EXPECT_NEAR(pane.time + pane.owedTime, pane.framesAdvanced / 60.0, 1e-9);
  }
  EXPECT_EQ(log.panes[1].time, log.panes[2].time);
  EXPECT_EQ(log.panes[1].time, log.panes[3].time);
  EXPECT_TRUE(contains(log.overlay("top-bar")->text, "rewound to t = ")) << log.overlay("top-bar")->text;
}

TEST(DemoBugs, B03_PanesAddedWithVStartOnTheFirstPanesClock) {
  const std::string dir = outputDirectory("AddedPanesClock");
  // dt 0.01 against frames of 1/60 s: the first pane owes part of a step at frame 7.
  ASSERT_EQ(runDemo(dir, "--scene test-chain --frames 8 --log-state state.txt", "7 key v\n7 key v\n7 key v\n").exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_EQ(log.panes.size(), 4u);
  for (const LoggedPane& pane : log.panes) {
    SCOPED_TRACE(pane.integrator);
    EXPECT_EQ(pane.framesAdvanced, 8);
    EXPECT_NEAR(pane.time + pane.owedTime, 8 / 60.0, 1e-9);
  }
}

TEST(DemoBugs, B04_RewindRestoresTheStepCounterAndRestartsThePlots) {
  const std::string dir = outputDirectory("RewindCounters");
  ASSERT_EQ(runDemo(dir, "--scene test-chain --frames 122 --log-state state.txt", "120 key b\n").exitCode, 0);
  const LoggedPane pane = readStateLog(dir + "/state.txt").panes.at(0);
  EXPECT_LT(pane.time, 120 / 60.0 - 0.9);
  EXPECT_EQ(pane.steps, std::llround(pane.time / pane.dt));
  EXPECT_EQ(pane.plotPoints, 0);  // paused right after the rewind: no stale plot points from the dropped future
}

TEST(DemoBugs, B05_TinyDtOnABigClothRunsInSlowMotionWithinTheFrameBudget) {
  const std::string dir = outputDirectory("SlowMotion");
  const RunResult r = runDemo(dir, std::string(noPanel) + " --scene cloth --param width=64 --param height=64 --param links=8 "
                              "--dt 1e-6 --frames 4 --log-state state.txt");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const StateLog log = readStateLog(dir + "/state.txt");
  const LoggedPane& pane = log.panes.at(0);
  EXPECT_TRUE(pane.slowMotion);
  // A frame of 1/60 s would take 16,667 steps, the old cap 2,000: the budget stops it far sooner.
  EXPECT_LT(pane.substeps, 2000);
  EXPECT_GT(pane.substeps, 0);
  EXPECT_LT(pane.time, 4 / 60.0);
  EXPECT_TRUE(contains(log.overlay("top-bar")->text, "slow motion")) << log.overlay("top-bar")->text;
}

TEST(DemoBugs, B06_ADtLongerThanAFrameSaysWhyNothingMoves) {
  const std::string dir = outputDirectory("DtOverFrame");
  ASSERT_EQ(runDemo(dir, "--scene test-chain --frames 10 --log-state state.txt", "1 key +\n2 key +\n3 key +\n4 key +\n5 key +\n")
                .exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  const double dt = log.panes.at(0).dt;
  ASSERT_GT(dt, 1.0 / 60.0) << "five doublings should pass one frame";
  const std::string hud = log.overlay("hud")->text;
  const std::string every = "a step every " + std::to_string(static_cast<int>(std::ceil(dt * 60.0 - 1e-9))) + " frames";
  EXPECT_TRUE(contains(hud, every)) << hud;
}

TEST(DemoBugs, B07_OutputsAreCheckedBeforeTheRun) {
  const std::string dir = outputDirectory("OutputsChecked");
  for (const std::string& args : {std::string("--screenshot /no/such/dir/shot.png"), std::string("--log-state /no/such/dir/state.txt"),
                                  std::string("--screenshot x.jpg"), std::string("--compare ''"), std::string("--log-state .")}) {
    SCOPED_TRACE(args);
    const RunResult r = runDemo(dir, args + " --frames 2");
    EXPECT_EQ(r.exitCode, 2);
    ASSERT_EQ(r.errLines().size(), 1u) << r.err;
    EXPECT_EQ(r.errLines()[0].rfind("particle-demo: ", 0), 0u);
  }
  std::ifstream jpg(dir + "/x.jpg");
  EXPECT_FALSE(jpg.good()) << "no PNG data written under a .jpg name";
}

TEST(DemoBugs, B08_TheScriptingGuidesExampleGrabsAParticle) {
  // The example block of demos/gui/SCRIPTING.md, cut before its release.
  std::ifstream doc(SCRIPTING_MD);
  std::stringstream text;
  text << doc.rdbuf();
  const std::string all = text.str();
  const auto start = all.find("# grab the cloth");
  ASSERT_NE(start, std::string::npos);
  const std::string example = all.substr(start, all.find("```", start) - start);
  const std::string dir = outputDirectory("ScriptingExample");
  ASSERT_EQ(runDemo(dir, "--frames 100 --log-state state.txt", example).exitCode, 0);
  EXPECT_EQ(readStateLog(dir + "/state.txt").panes.at(0).mouseSprings, 1);
}

TEST(DemoBugs, B09_TheHudsEnergyLeavesOutTheMouseSpring) {
  const std::string dir = outputDirectory("EnergyApart");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --paused --frames 1 --log-state start.txt").exitCode, 0);
  const Eigen::Vector2d bead = readStateLog(dir + "/start.txt").panes.at(0).particles.at(0).x;
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 40 --log-state state.txt",
                    dragScript(bead, bead + Eigen::Vector2d(0.3, 0.4), 0, 4)).exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  const LoggedPane& pane = log.panes.at(0);
  ASSERT_EQ(pane.mouseSprings, 1);
  EXPECT_GT(pane.mouseSpringEnergy, 0.0);
  // The logged energy is the scene's alone: the same state in a fresh pendulum.
  scenes::Scene scene = scenes::buildScene("pendulum");
  scene.system->setPosition(0, pane.particles[0].x);
  scene.system->setVelocity(0, pane.particles[0].v);
  EXPECT_NEAR(pane.energy, scene.system->totalEnergy(), 1e-9 * (1.0 + std::abs(pane.energy)));
  EXPECT_TRUE(contains(log.overlay("hud")->text, "(mouse spring")) << log.overlay("hud")->text;
}

TEST(DemoBugs, B10_ConstraintKeyHidesOnlyTheDrawingAndSaysSo) {
  const std::string dir = outputDirectory("ConstraintKey");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 120 --log-state state.txt", "1 key c\n2 key h\n").exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_NE(log.overlay("help"), nullptr);
  EXPECT_TRUE(contains(log.overlay("help")->text, "c: constraint drawing on / off")) << log.overlay("help")->text;
  EXPECT_LT(log.panes.at(0).maxConstraintError, 1e-4);  // the wire still holds the bead
}

TEST(DemoBugs, B11_EveryComparePaneShowsItsOwnTime) {
  const std::string dir = outputDirectory("PaneTimes");
  ASSERT_EQ(runDemo(dir, "--scene test-chain --compare rk4:0.5,rk4 --frames 300 --log-state state.txt").exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_TRUE(log.panes.at(0).diverged);
  std::vector<std::string> headers;
  for (const LoggedOverlay& o : log.overlays)
    if (o.kind == "pane-hud") headers.push_back(o.text);
  ASSERT_EQ(headers.size(), 2u);
  EXPECT_TRUE(contains(headers[0], "diverged at t = ")) << headers[0];
  EXPECT_TRUE(contains(headers[1], "t = 5.00 s")) << headers[1];  // pane 2 ran on after pane 1 stopped
}

TEST(DemoBugs, B12_TheDrawTimeIncludesTheTextAndThePanel) {
  const std::string dir = outputDirectory("DrawTime");
  ASSERT_EQ(runDemo(dir, "--scene cloth --frames 30 --log-state state.txt").exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  EXPECT_TRUE(log.panelShown);
  EXPECT_GT(log.overlayDrawMs, 0.0);
  EXPECT_EQ(log.measuredFrames, 20);  // the frame-time summary covers the frames after a 10-frame warm-up
  EXPECT_GT(log.medianFrameMs, 0.0);
  // "draw T ms (scene S + text and panel P)" with T = S + P.
  const std::smatch m = [&] {
    std::smatch match;
    static const std::regex pattern("draw +([0-9.]+) ms \\(scene +([0-9.]+) \\+ text and panel +([0-9.]+)\\)");
    const std::string& hud = log.overlay("hud")->text;
    std::regex_search(hud, match, pattern);
    return match;
  }();
  ASSERT_EQ(m.size(), 4u) << log.overlay("hud")->text;
  EXPECT_NEAR(std::stod(m[1]), std::stod(m[2]) + std::stod(m[3]), 0.11);
  EXPECT_GT(std::stod(m[3]), 0.0);
}

TEST(DemoBugs, B13_ScriptedClicksReachThePanel) {
  const std::string dir = outputDirectory("PanelClicks");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 2 --log-state layout.txt").exitCode, 0);
  const StateLog layout = readStateLog(dir + "/layout.txt");
  ASSERT_NE(layout.widget("pause"), nullptr);
  ASSERT_NE(layout.widget("step"), nullptr);
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 12 --log-state state.txt", clickAt(2, *layout.widget("pause"))).exitCode, 0);
  const StateLog paused = readStateLog(dir + "/state.txt");
  EXPECT_TRUE(paused.paused);
  EXPECT_LT(paused.panes.at(0).framesAdvanced, 12);
  // Step (.) on the panel: one step while paused.
  ASSERT_EQ(runDemo(dir, "--scene pendulum --paused --frames 12 --log-state state.txt", clickAt(2, *layout.widget("step"))).exitCode, 0);
  EXPECT_EQ(readStateLog(dir + "/state.txt").panes.at(0).steps, 1);
}

TEST(DemoDrawing, ASurfacesFacesAreShaded) {
  // Scenes that expose the faces of a surface (the cloth's grid cells) draw
  // them as filled quads: the centre of a face shows the cloth's colour.
  const scenes::Scene scene = scenes::buildScene("cloth");
  if (scene.faces.empty()) GTEST_SKIP() << "the cloth scene exposes no faces";
  const std::string dir = outputDirectory("Faces");
  ASSERT_EQ(runDemo(dir, std::string(noPanel) + " --scene cloth --paused --frames 2 --screenshot shot.png --log-state state.txt")
                .exitCode, 0);
  const Image image = readPng(dir + "/shot.png");
  const LoggedPane pane = readStateLog(dir + "/state.txt").panes.at(0);
  int shaded = 0, checked = 0;
  for (const auto& face : scene.faces) {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (int i : face) centre += 0.25 * pane.particles.at(i).x;
    const Eigen::Vector2d px = pane.toPixel(centre);
    if (!pane.inWorldRect(px)) continue;
    ++checked;
    const demo::Rgb c = image.at(int(px.x()), int(px.y()));
    shaded += near(c, demo::palette::clothFront, 70) || near(c, demo::palette::clothBack, 70);
  }
  EXPECT_GT(checked, 0);
  EXPECT_GE(shaded, checked * 9 / 10);
}

// --record writes every frame as a numbered PNG, the last of them the very
// image --screenshot takes; the k key writes a screenshot beside them, and
// the status line names it. A directory that cannot be made is refused
// before the run.
TEST(DemoRecording, RecordWritesEveryFrameAndTheKeyAScreenshot) {
  const std::string dir = outputDirectory("Record");
  const RunResult run =
      runDemo(dir, "--scene pendulum --frames 6 --record frames --screenshot last.png --log-state state.txt",
              "3 key k\n");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  for (int frame = 1; frame <= 6; ++frame) {
    char name[32];
    std::snprintf(name, sizeof name, "/frames/frame-%06d.png", frame);
    const Image image = readPng(dir + name);
    EXPECT_EQ(image.width, 1180) << name;
    EXPECT_EQ(image.height, 760) << name;
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/frames/frame-000007.png"));
  const auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  EXPECT_TRUE(bytes(dir + "/frames/frame-000006.png") == bytes(dir + "/last.png"));
  // One screenshot, the image of the frame it names.
  std::vector<std::string> shots;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/frames"))
    if (entry.path().filename().string().rfind("screenshot-", 0) == 0) shots.push_back(entry.path().filename().string());
  ASSERT_EQ(shots.size(), 1u);
  const std::string number = shots[0].substr(std::string("screenshot-").size());
  EXPECT_TRUE(bytes(dir + "/frames/" + shots[0]) == bytes(dir + "/frames/frame-" + number)) << shots[0];
  const RunResult refused = runDemo(dir, "--frames 2 --record last.png/sub");
  EXPECT_EQ(refused.exitCode, 2);
  ASSERT_EQ(refused.errLines().size(), 1u) << refused.err;
  EXPECT_NE(refused.errLines()[0].find("--record"), std::string::npos) << refused.err;
}
