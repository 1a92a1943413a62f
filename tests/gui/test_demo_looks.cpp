// particle-demo's looks: the stress colour map, the detail a dense surface
// is drawn in, and text that fits its bars and panel at 800x600 and up.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "demo_driver.h"
#include "palette.h"
#include "renderer.h"
#include "scene.h"

using namespace demotest;

namespace {

// The pixel (column, row) of a world point, rounded as the screenshot's.
demo::Rgb pixelAt(const Image& image, const LoggedPane& pane, const Eigen::Vector2d& world) {
  const Eigen::Vector2d px = pane.toPixel(world);
  return image.at(static_cast<int>(px.x()), static_cast<int>(px.y()));
}

int distance(demo::Rgb a, demo::Rgb b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

// Every bar's text within its rectangle, nothing shortened, and every panel
// control within the panel; `what` names the run in failures.
void expectTextFits(const StateLog& log, const std::string& what) {
  SCOPED_TRACE(what);
  int bars = 0;
  for (const LoggedOverlay& o : log.overlays) {
    if (o.kind != "top-bar" && o.kind != "hud" && o.kind != "pane-hud") continue;
    ++bars;
    EXPECT_LE(o.textWidth, o.width) << o.kind << ": " << o.text;
    EXPECT_LE(o.textHeight, o.height) << o.kind << ": " << o.text;
    EXPECT_FALSE(o.shortened) << o.kind << ": " << o.text;
  }
  EXPECT_GE(bars, 2);
  if (const LoggedOverlay* panel = log.overlay("panel"))
    for (const LoggedOverlay& w : log.widgets) {
      EXPECT_GE(w.x, panel->x) << w.kind;
      EXPECT_LE(w.x + w.width, panel->x + panel->width) << w.kind;
    }
}

}  // namespace

// A face's colour is the stress map's for its strain, √(area / rest area) − 1:
// checked at the centre of every face of the swinging 4-way cloth (no spring
// crosses a face's centre there), against the strain computed from the
// logged positions; and the map is visible, its stretched faces far from
// the rest colour.
TEST(DemoLooks, FacesShowTheirStrainInTheStressColourMap) {
  const scenes::Scene scene = scenes::buildScene("cloth");
  ASSERT_FALSE(scene.faces.empty());
  const std::string dir = outputDirectory("StressMap");
  ASSERT_EQ(runDemo(dir, "--no-panel --window 900x700 --scene cloth --frames 45 --screenshot shot.png --log-state state.txt")
                .exitCode, 0);
  const Image image = readPng(dir + "/shot.png");
  const LoggedPane pane = readStateLog(dir + "/state.txt").panes.at(0);
  auto area = [&](const std::vector<Eigen::Vector2d>& x, const std::array<int, 4>& f) {
    double twice = 0.0;
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d& a = x[f[k]];
      const Eigen::Vector2d& b = x[f[(k + 1) % 4]];
      twice += a.x() * b.y() - b.x() * a.y();
    }
    return 0.5 * twice;
  };
  std::vector<Eigen::Vector2d> rest, now;
  for (int i = 0; i < scene.system->size(); ++i) rest.push_back(scene.system->position(i));
  for (const LoggedParticle& q : pane.particles) now.push_back(q.x);
  int checked = 0, matched = 0, visiblyStretched = 0;
  double largestStrain = 0.0;
  for (const auto& f : scene.faces) {
    const double ratio = area(now, f) / area(rest, f);
    const double strain = std::sqrt(std::abs(ratio)) - 1.0;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (int i : f) centre += 0.25 * now[i];
    if (!pane.inWorldRect(pane.toPixel(centre)) || ratio <= 0.0) continue;
    ++checked;
    const demo::Rgb expected = demo::palette::strainColour(demo::palette::clothFront, strain);
    const demo::Rgb seen = pixelAt(image, pane, centre);
    matched += distance(seen, expected) <= 12;
    largestStrain = std::max(largestStrain, strain);
    visiblyStretched += strain > 0.04 && distance(seen, demo::palette::clothFront) >= 40;
  }
  EXPECT_GT(checked, 40);
  EXPECT_GE(matched, checked * 9 / 10);
  // The swinging cloth stretches by more than 4% somewhere, and there it shows.
  EXPECT_GT(largestStrain, 0.04);
  EXPECT_GT(visiblyStretched, 0);
}

// A 64x64 cloth framed whole is a few pixels per particle: it is drawn as its
// shaded faces, with no springs and no free particles (which would fill it
// solid white); the 10x10 cloth keeps its whole mesh.
TEST(DemoLooks, ADenseSurfaceIsDrawnAsItsShadedFaces) {
  const std::string dir = outputDirectory("SurfaceDetail");
  ASSERT_EQ(runDemo(dir, "--no-panel --window 900x700 --key 0 --paused --frames 2 --screenshot dense.png --log-state dense.txt")
                .exitCode, 0);
  const LoggedPane dense = readStateLog(dir + "/dense.txt").panes.at(0);
  EXPECT_LT(dense.spacingPixels, demo::meshLinePixels);
  EXPECT_FALSE(dense.springsDrawn);
  EXPECT_FALSE(dense.particlesDrawn);
  EXPECT_GT(dense.facesShaded, 3000);
  const Image image = readPng(dir + "/dense.png");
  // At the particles' pixels: the faces' colour, never the free particles'.
  int checked = 0, white = 0, shaded = 0;
  for (const LoggedParticle& q : dense.particles) {
    if (q.pinned || !dense.inWorldRect(dense.toPixel(q.x)) || ++checked > 600) continue;
    const demo::Rgb c = pixelAt(image, dense, q.x);
    white += near(c, demo::palette::particle, 30);
    shaded += !near(c, demo::palette::background, 8);
  }
  EXPECT_GT(checked, 600);
  EXPECT_EQ(white, 0);
  EXPECT_GE(shaded, 600 * 9 / 10);

  ASSERT_EQ(runDemo(dir, "--no-panel --window 900x700 --scene cloth --paused --frames 2 --log-state coarse.txt").exitCode, 0);
  const LoggedPane coarse = readStateLog(dir + "/coarse.txt").panes.at(0);
  EXPECT_GE(coarse.spacingPixels, demo::meshDotPixels);
  EXPECT_TRUE(coarse.springsDrawn);
  EXPECT_TRUE(coarse.particlesDrawn);
}

// At 800x600 with the panel shown, the scene's name stays in the top bar and
// no bar's text or panel control is cut: the bars wrap and grow, the panel's
// buttons wrap onto a new row. Checked on the default cloth, a diverged test
// chain (its message and keys in both bars), the force legend of a rod chain,
// and four compare panes.
TEST(DemoLooks, TextFitsAt800x600) {
  const std::string dir = outputDirectory("TextFit");
  const std::string small = " --window 800x600 --log-state state.txt";
  ASSERT_EQ(runDemo(dir, "--scene cloth --frames 30" + small).exitCode, 0);
  const StateLog cloth = readStateLog(dir + "/state.txt");
  expectTextFits(cloth, "cloth");
  ASSERT_NE(cloth.overlay("top-bar"), nullptr);
  EXPECT_NE(cloth.overlay("top-bar")->text.find("cloth (4-way)"), std::string::npos) << cloth.overlay("top-bar")->text;
  ASSERT_NE(cloth.widget("rewind"), nullptr);

  ASSERT_EQ(runDemo(dir, "--scene test-chain --preset seed --integrator rk4 --dt 0.5 --frames 300" + small).exitCode, 0);
  const StateLog diverged = readStateLog(dir + "/state.txt");
  ASSERT_TRUE(diverged.panes.at(0).diverged);
  expectTextFits(diverged, "diverged");
  for (const char* bar : {"top-bar", "hud"}) {
    const std::string text = diverged.overlay(bar)->joined();
    EXPECT_NE(text.find("r resets, b rewinds"), std::string::npos) << diverged.overlay(bar)->text;
  }

  ASSERT_EQ(runDemo(dir, "--scene rod-chain --frames 30" + small, "1 key f\n").exitCode, 0);
  const StateLog forces = readStateLog(dir + "/state.txt");
  expectTextFits(forces, "force legend");
  EXPECT_NE(forces.overlay("hud")->text.find("J^T lambda"), std::string::npos) << forces.overlay("hud")->text;

  ASSERT_EQ(runDemo(dir, "--scene test-chain --compare euler,midpoint,rk4,verlet --frames 30" + small).exitCode, 0);
  expectTextFits(readStateLog(dir + "/state.txt"), "compare");

  // And at the default size, the same runs keep their one-line bars' layout.
  ASSERT_EQ(runDemo(dir, "--scene cloth --frames 30 --log-state state.txt").exitCode, 0);
  expectTextFits(readStateLog(dir + "/state.txt"), "cloth at the default size");
}

// With a dt longer than a frame, the drawing moves between steps: the
// pendulum at dt 0.1 s (six frames a step) after 9 frames has stepped once
// and owes half a step, so its bob is drawn halfway from the start to the
// state after that step (each logged by a run stopped there), not at the state.
TEST(DemoLooks, ADtLongerThanAFrameIsDrawnBetweenSteps) {
  const std::string dir = outputDirectory("Interpolated");
  const std::string args = "--no-panel --window 900x700 --scene pendulum --integrator rk4 --dt 0.1 ";
  const std::string noGhost = "0 key g\n";
  ASSERT_EQ(runDemo(dir, args + "--frames 3 --log-state before.txt", noGhost).exitCode, 0);
  ASSERT_EQ(runDemo(dir, args + "--frames 9 --screenshot between.png --log-state between.txt", noGhost).exitCode, 0);
  const LoggedPane before = readStateLog(dir + "/before.txt").panes.at(0);
  const LoggedPane after = readStateLog(dir + "/between.txt").panes.at(0);
  ASSERT_EQ(before.steps, 0);
  ASSERT_EQ(after.steps, 1);
  EXPECT_NEAR(after.drawnFraction, 0.5, 1e-9);
  const Image image = readPng(dir + "/between.png");
  const Eigen::Vector2d start = before.particles.back().x, state = after.particles.back().x;
  const Eigen::Vector2d expected = after.toPixel(start + after.drawnFraction * (state - start));
  // The centroid of the bob's pixels near where it should be drawn.
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int count = 0;
  for (int dy = -15; dy <= 15; ++dy)
    for (int dx = -15; dx <= 15; ++dx) {
      const int x = static_cast<int>(expected.x()) + dx, y = static_cast<int>(expected.y()) + dy;
      if (image.inside(x, y) && near(image.at(x, y), demo::palette::particle, 40)) sum += Eigen::Vector2d(x + 0.5, y + 0.5), ++count;
    }
  ASSERT_GT(count, 10);
  EXPECT_LT((sum / count - expected).norm(), 1.5) << "drawn at " << (sum / count).transpose() << ", expected "
                                                  << expected.transpose();
  // And that is not where the state is.
  EXPECT_GT((after.toPixel(state) - expected).norm(), 4.0);
}

// The ghost is the closed form of the undisturbed motion: the HUD says so,
// and once the mouse moves the scene it is hidden and the HUD says when; r
// brings it back.
TEST(DemoLooks, TheGhostSaysWhatItShowsAndHidesOnceTheMouseMovesTheScene) {
  const std::string dir = outputDirectory("GhostLabel");
  // Explicit Euler at 10 ms drifts from the closed form, so the two are apart.
  const std::string args = "--no-panel --window 900x700 --scene pendulum --integrator euler --dt 0.01 --frames 60 ";
  ASSERT_EQ(runDemo(dir, args + "--screenshot plain.png --log-state plain.txt").exitCode, 0);
  const StateLog plain = readStateLog(dir + "/plain.txt");
  EXPECT_NE(plain.overlay("hud")->text.find("ghost: the closed form from the start"), std::string::npos)
      << plain.overlay("hud")->text;
  // In the pane's world only (the HUD's label is in the ghost's colour too).
  const LoggedPane& pane = plain.panes.at(0);
  auto ghostPixels = [&](const Image& image) {
    int count = 0;
    for (int y = pane.pixelY; y < pane.pixelY + pane.pixelHeight; ++y)
      for (int x = pane.pixelX; x < pane.pixelX + pane.pixelWidth; ++x)
        count += near(image.at(x, y), demo::palette::mix(demo::palette::background, demo::palette::ghost, 170 / 255.0), 25);
    return count;
  };
  EXPECT_GT(ghostPixels(readPng(dir + "/plain.png")), 20);

  // The bob where it is when the drag starts, at frame 3.
  ASSERT_EQ(runDemo(dir, "--no-panel --window 900x700 --scene pendulum --integrator euler --dt 0.01 --frames 3 "
                         "--log-state early.txt").exitCode, 0);
  const Eigen::Vector2d bob = readStateLog(dir + "/early.txt").panes.at(0).particles.back().x;
  std::ostringstream drag;
  drag << "3 down world " << bob.x() << " " << bob.y() << "\n6 move world " << bob.x() + 0.1 << " " << bob.y()
       << "\n";
  ASSERT_EQ(runDemo(dir, args + "--screenshot moved.png --log-state moved.txt", drag.str()).exitCode, 0);
  const StateLog moved = readStateLog(dir + "/moved.txt");
  EXPECT_NE(moved.overlay("hud")->text.find("ghost off: moved by the mouse at t = 0.05 s"), std::string::npos)
      << moved.overlay("hud")->text;
  EXPECT_EQ(ghostPixels(readPng(dir + "/moved.png")), 0);

  ASSERT_EQ(runDemo(dir, args + "--log-state reset.txt", drag.str() + "8 up world 0 0\n9 key r\n").exitCode, 0);
  const StateLog reset = readStateLog(dir + "/reset.txt");
  EXPECT_NE(reset.overlay("hud")->text.find("ghost: the closed form from the start"), std::string::npos)
      << reset.overlay("hud")->text;
}
