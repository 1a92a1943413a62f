// The demo as a new user finds it: a cloth pulled over itself recovers, the
// help shows every key at small and default sizes, messages say what
// happened and what to do, compare's top bar names its panes, the wind
// leaves the curtain on its rail, a pull rips the cloth along a line of faces,
// the panel saves the state and records frames, and the gallery's scenes
// load from the panel's list. Behaviour is read from the state log and the
// screenshots, never from timings.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "demo_driver.h"

using namespace demotest;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The default cloth's faces (a width × height grid, row by row): how many
// are turned over (negative signed area) in the logged state.
int invertedFaces(const LoggedPane& pane, int width, int height) {
  int inverted = 0;
  auto x = [&](int row, int col) { return pane.particles.at(static_cast<std::size_t>(row * width + col)).x; };
  for (int row = 0; row + 1 < height; ++row)
    for (int col = 0; col + 1 < width; ++col) {
      const std::array<Eigen::Vector2d, 4> c = {x(row, col), x(row + 1, col), x(row + 1, col + 1), x(row, col + 1)};
      double twice = 0.0;
      for (int k = 0; k < 4; ++k) twice += c[k].x() * c[(k + 1) % 4].y() - c[(k + 1) % 4].x() * c[k].y();
      inverted += twice < 0.0;
    }
  return inverted;
}

// A scripted click on a widget: the pointer there a frame before the press,
// the release a frame after.
std::string clickAt(long long frame, const LoggedOverlay& w) {
  std::ostringstream s;
  const double x = w.x + 0.5 * w.width, y = w.y + 0.5 * w.height;
  s << frame << " move window " << x << " " << y << "\n"
    << frame + 1 << " down window " << x << " " << y << "\n"
    << frame + 2 << " up window " << x << " " << y << "\n";
  return s.str();
}

// A drag of the mouse joint along world points, `frames` frames per leg,
// released at the last one.
std::string dragAlong(long long frame, const std::vector<Eigen::Vector2d>& points, int frames) {
  std::ostringstream s;
  s << frame << " down world " << points[0].x() << " " << points[0].y() << "\n";
  long long f = frame;
  for (std::size_t k = 1; k < points.size(); ++k)
    for (int j = 1; j <= frames; ++j) {
      const Eigen::Vector2d p = points[k - 1] + (points[k] - points[k - 1]) * (static_cast<double>(j) / frames);
      s << ++f << " move world " << p.x() << " " << p.y() << "\n";
    }
  s << ++f << " up world " << points.back().x() << " " << points.back().y() << "\n";
  return s.str();
}

}  // namespace

// The tangle: the 8-way cloth's lower left corner dragged up over
// the rail and across to the right, turning the cloth over itself, and let
// go. Without the faces' area floor it stays crumpled with tens of faces
// turned over; with it, no more than 2 of the 81 are within 5 s of the release.
TEST(DemoNewUser, ATangledClothRecoversWithinFiveSecondsOfRelease) {
  const std::string dir = outputDirectory("Tangle");
  const std::string cloth = "--scene cloth --param links=8 --no-panel --window 900x700 ";  // key 2
  const std::string args = cloth + "--frames 480 --log-state ";
  ASSERT_EQ(runDemo(dir, cloth + "--frames 60 --log-state start.txt").exitCode, 0);
  const LoggedPane start = readStateLog(dir + "/start.txt").panes.at(0);
  const Eigen::Vector2d corner = start.particles.at(90).x;  // row 9, column 0
  const Eigen::Vector2d rail = start.particles.at(0).x;
  const std::string drag = dragAlong(60, {corner, {rail.x() - 0.1, rail.y() + 0.35}, {rail.x() + 0.55, rail.y() + 0.25},
                                          {rail.x() + 0.45, rail.y() - 0.2}}, 30);
  // Released at frame 151: 5 s later is frame 451.
  ASSERT_EQ(runDemo(dir, args + "folded.txt --param area-stiffness=0", drag).exitCode, 0);
  const int withoutFloor = invertedFaces(readStateLog(dir + "/folded.txt").panes.at(0), 10, 10);
  ASSERT_EQ(runDemo(dir, args + "recovered.txt --screenshot recovered.png", drag).exitCode, 0);
  const int withFloor = invertedFaces(readStateLog(dir + "/recovered.txt").panes.at(0), 10, 10);
  std::printf("[ tangle   ] faces turned over 5 s after the release: %d without the area floor, %d with it\n",
              withoutFloor, withFloor);
  EXPECT_GE(withoutFloor, 10) << "the drag does not fold the cloth: the test proves nothing";
  EXPECT_LE(withFloor, 2);
}

// Every key the help lists (scene keys, actions, mouse) is drawn, inside the
// window, at the default size and at 800x600, and its text-fit record says
// nothing was left out; the panel takes less than half the window.
TEST(DemoNewUser, TheHelpShowsEveryKeyAtTheDefaultSizeAnd800x600) {
  const std::string dir = outputDirectory("HelpFits");
  for (const char* window : {"1180x760", "800x600"}) {
    SCOPED_TRACE(window);
    ASSERT_EQ(runDemo(dir, std::string("--window ") + window + " --frames 3 --log-state help.txt", "0 key h\n").exitCode, 0);
    const StateLog log = readStateLog(dir + "/help.txt");
    const LoggedOverlay* help = log.overlay("help");
    ASSERT_NE(help, nullptr);
    const LoggedOverlay* panel = log.overlay("panel");
    ASSERT_NE(panel, nullptr);
    const int width = std::stoi(std::string(window).substr(0, std::string(window).find('x')));
    const int height = std::stoi(std::string(window).substr(std::string(window).find('x') + 1));
    EXPECT_GE(help->x, 0);
    EXPECT_GE(help->y, 0);
    EXPECT_LE(help->x + help->width, width);
    EXPECT_LE(help->y + help->height, height);
    EXPECT_LE(help->textWidth, help->width) << help->text;
    EXPECT_LE(help->textHeight, help->height) << help->text;
    EXPECT_FALSE(help->shortened) << help->text;
    EXPECT_LT(panel->width, width / 2);
    for (const char* key : {"1: cloth (4-way)", "9: pendulum", "0: stiff cloth", "i: next integrator", "k: screenshot",
                            "h: this help", "Esc / q: quit", "left drag: pull", "wheel: zoom"})
      EXPECT_TRUE(contains(help->text, key)) << key << " missing from\n" << help->text;
  }
}

// Explicit Euler on the cloth at its default dt gains energy until the cloth
// flies apart (a particle flung far out of the scene, a constraint drifted
// off, or a particle too fast for the contact pass): the message says so in
// words, never as the failure's code, with what the keys can do about it.
TEST(DemoNewUser, ADivergenceSaysWhatHappenedAndWhatToDo) {
  const std::string dir = outputDirectory("DivergenceWords");
  ASSERT_EQ(runDemo(dir, "--scene cloth --integrator euler --frames 300 --log-state state.txt").exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  ASSERT_TRUE(log.panes.at(0).diverged);
  const std::string bar = log.overlay("top-bar")->text + log.overlay("hud")->text;
  EXPECT_FALSE(contains(bar, "contact-cap")) << bar;
  EXPECT_TRUE(contains(bar, "- halves dt, i tries another integrator")) << bar;
  EXPECT_TRUE(contains(bar, "too fast for this step") || contains(bar, "too long for this integrator") ||
              contains(bar, "a particle was flung far out of the scene"))
      << bar;
}

// i says what the scheme it switches to is: its order, when it is stable,
// what a step costs.
TEST(DemoNewUser, SwitchingIntegratorsSaysWhatTheSchemeIs) {
  const std::string dir = outputDirectory("IntegratorLine");
  ASSERT_EQ(runDemo(dir, "--scene pendulum --integrator rk4 --frames 5 --log-state state.txt", "1 key i\n").exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  EXPECT_EQ(log.panes.at(0).integrator, "verlet");
  const std::string bar = log.overlay("top-bar")->text;
  EXPECT_TRUE(contains(bar, "integrator: verlet (order 2): symplectic")) << bar;
  EXPECT_TRUE(contains(bar, "force evaluation a step")) << bar;
}

// --compare's top bar names the panes it runs, each with its own dt, in pane
// order; v on the hair names them too, with no "..." in the bar.
TEST(DemoNewUser, ComparesTopBarNamesItsPanes) {
  const std::string dir = outputDirectory("CompareBar");
  ASSERT_EQ(runDemo(dir, "--scene test-chain --compare euler,symplectic-euler,midpoint,rk4 --dt 0.005 --frames 20 "
                         "--log-state state.txt")
                .exitCode,
            0);
  const std::string bar = readStateLog(dir + "/state.txt").overlay("top-bar")->text;
  EXPECT_TRUE(contains(bar, "compare: 1 euler dt 0.005, 2 symplectic-euler dt 0.005, 3 midpoint dt 0.005, 4 rk4 dt 0.005"))
      << bar;
  ASSERT_EQ(runDemo(dir, "--scene hair --frames 20 --log-state hair.txt", "2 key v\n").exitCode, 0);
  const StateLog hair = readStateLog(dir + "/hair.txt");
  const LoggedOverlay* top = hair.overlay("top-bar");
  // The second line is the panes, whole (the first may shorten the scene's summary).
  const std::string second = top->text.substr(top->text.find(" | ") + 3);  // lines logged as " | "
  EXPECT_EQ(second.rfind("compare: 1 rk4 dt 0.0005, 2 euler dt 0.002", 0), 0u) << top->text;
  EXPECT_FALSE(contains(second, "...")) << top->text;
  EXPECT_FALSE(top->shortened);
}

// Key 0's long name and hint never push the scene's name and time out of the
// top bar, at the default width and at 1280 px.
TEST(DemoNewUser, KeyZeroKeepsTheScenesNameAndTimeInTheTopBar) {
  const std::string dir = outputDirectory("KeyZero");
  for (const char* window : {"1180x760", "1280x800"}) {
    ASSERT_EQ(runDemo(dir, std::string("--window ") + window + " --frames 3 --log-state state.txt", "1 key 0\n").exitCode, 0);
    const StateLog log = readStateLog(dir + "/state.txt");
    const LoggedOverlay* top = log.overlay("top-bar");
    ASSERT_NE(top, nullptr);
    EXPECT_TRUE(contains(top->text, "stiff cloth 64x64")) << window << ": " << top->text;
    EXPECT_TRUE(contains(top->text, "t = ")) << window << ": " << top->text;
    EXPECT_FALSE(top->shortened) << window << ": " << top->text;
  }
}

TEST(DemoNewUser, HelpNamesKAsTheScreenshotKey) {
  const std::string dir = outputDirectory("HelpK");
  const RunResult run = runDemo(dir, "--help");
  ASSERT_EQ(run.exitCode, 0);
  EXPECT_TRUE(contains(run.out, "the k key's screenshots")) << run.out;
  EXPECT_FALSE(contains(run.out, "the o key")) << run.out;
}

// A point placed in build mode on a 0.05 grid is saved as 0.3, not as
// 0.30000000000000004 (6 × 0.05 in binary).
TEST(DemoNewUser, GridPointsAreTheDecimalsTheyRead) {
  const std::string dir = outputDirectory("GridDecimals");
  const std::string script = "0 key e\n1 key N\n2 key n\n3 edit build grid 0.05\n"
                             "4 down world 0.299 0.101\n5 up world 0.299 0.101\n6 edit build file p.json\n7 key s\n";
  ASSERT_EQ(runDemo(dir, "--scene cloth --frames 10", script).exitCode, 0);
  std::ifstream file(dir + "/p.json");
  std::stringstream text;
  text << file.rdbuf();
  EXPECT_TRUE(contains(text.str(), "[0.3, 0.1]") || contains(text.str(), "[0.3,0.1]")) << text.str();
  EXPECT_FALSE(contains(text.str(), "0.30000000000000004")) << text.str();
}

// The wind on the 4-way cloth (w): a 5 m/s gusty wind pushes the curtain
// against the rail's end stop, where it billows; 10 s on, every particle is
// still in view and the top row on the rail.
TEST(DemoNewUser, TheWindLeavesTheCurtainOnItsRail) {
  const std::string dir = outputDirectory("WindCurtain");
  ASSERT_EQ(runDemo(dir, "--scene cloth --frames 660 --log-state state.txt", "60 key w\n").exitCode, 0);
  const StateLog log = readStateLog(dir + "/state.txt");
  const LoggedPane& pane = log.panes.at(0);
  EXPECT_GT(pane.wind.speed, 0.0);
  const double railY = pane.particles.at(0).x.y();
  for (int col = 0; col < 10; ++col) EXPECT_NEAR(pane.particles.at(col).x.y(), railY, 1e-6) << col;
  int inView = 0;
  for (const LoggedParticle& p : pane.particles)
    inView += p.x.x() >= pane.worldMin.x() && p.x.x() <= pane.worldMax.x() && p.x.y() >= pane.worldMin.y() &&
              p.x.y() <= pane.worldMax.y();
  EXPECT_EQ(inView, static_cast<int>(pane.particles.size()));
}

// The recipe of SCRIPTING.md's torn-cloth picture: the 8-way 16 x 14 cloth in a 2 m/s wind with tearing at
// 15% strain, a particle in its middle pulled down 40 cm. Links break across
// the cloth, along a line of faces, not only at the grabbed particle: more
// than 10 of them far from it (two rows or columns away and more), in at
// least 8 different columns.
TEST(DemoNewUser, APullRipsTheClothAlongALineOfFaces) {
  const std::string dir = outputDirectory("Rip");
  const std::string args = "--scene cloth --param links=8 --param width=16 --param height=14 --param wind=2 "
                           "--param tear-strain=0.15 --no-panel --window 900x700 ";
  ASSERT_EQ(runDemo(dir, args + "--frames 120 --log-state start.txt").exitCode, 0);
  const int grabbed = 7 * 16 + 8;
  const Eigen::Vector2d at = readStateLog(dir + "/start.txt").panes.at(0).particles.at(grabbed).x;
  std::ostringstream script;
  script << "120 down world " << at.x() << " " << at.y() << "\n";
  for (int k = 1; k <= 60; ++k) script << 120 + k << " move world " << at.x() + 0.1 * k / 60 << " " << at.y() - 0.4 * k / 60 << "\n";
  ASSERT_EQ(runDemo(dir, args + "--frames 220 --log-state torn.txt --screenshot torn.png", script.str()).exitCode, 0);
  const LoggedPane torn = readStateLog(dir + "/torn.txt").panes.at(0);
  ASSERT_GT(torn.brokenLinks, 0);
  // Which links broke: a side of the grid is broken when its two ends are
  // now much further apart than a rest length (a torn spring pulls no more).
  int far = 0;
  std::set<int> columns;
  auto x = [&](int row, int col) { return torn.particles.at(static_cast<std::size_t>(row * 16 + col)).x; };
  for (int row = 0; row + 1 < 14; ++row)
    for (int col = 0; col < 16; ++col) {
      const bool apart = (x(row + 1, col) - x(row, col)).norm() > 0.05 * 1.6;
      const bool nearGrab = std::abs(row - 7) <= 1 && std::abs(col - 8) <= 1;
      if (apart && !nearGrab) {
        ++far;
        columns.insert(col);
      }
    }
  std::printf("[ rip      ] %lld links broken; %d vertical sides torn open away from the hand, in %zu columns\n",
              torn.brokenLinks, far, columns.size());
  EXPECT_GT(far, 10);
  EXPECT_GE(columns.size(), 8u);
}

// Save state writes the scene as it is (paused, so the log holds the same
// state), and the file runs from there: its particles and clock bit for bit;
// Load state brings it back into a running demo. Record writes frames.
TEST(DemoNewUser, ThePanelSavesTheStateLoadsItBackAndRecords) {
  const std::string dir = outputDirectory("SaveState");
  std::filesystem::remove(dir + "/state.json");
  std::filesystem::remove_all(dir + "/particle-demo-frames");
  // The panel as it is while paused (Run is narrower than Pause, so the buttons wrap otherwise).
  ASSERT_EQ(runDemo(dir, "--scene hair --paused --frames 2 --log-state layout.txt").exitCode, 0);
  const StateLog layout = readStateLog(dir + "/layout.txt");
  for (const char* name : {"save-state", "load-state", "record"}) ASSERT_NE(layout.widget(name), nullptr) << name;
  const std::string save = "40 key space\n" + clickAt(45, *layout.widget("save-state")) + clickAt(50, *layout.widget("record")) +
                           clickAt(55, *layout.widget("record"));
  ASSERT_EQ(runDemo(dir, "--scene hair --frames 60 --log-state saved.txt", save).exitCode, 0);
  const LoggedPane saved = readStateLog(dir + "/saved.txt").panes.at(0);
  ASSERT_TRUE(std::filesystem::exists(dir + "/state.json"));
  int frames = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/particle-demo-frames"))
    frames += entry.path().extension() == ".png";
  EXPECT_GE(frames, 3);  // from the click on Record to the click that stops it
  EXPECT_LE(frames, 6);

  ASSERT_EQ(runDemo(dir, "--scene-file state.json --paused --frames 2 --log-state loaded.txt").exitCode, 0);
  const LoggedPane loaded = readStateLog(dir + "/loaded.txt").panes.at(0);
  EXPECT_EQ(loaded.time, saved.time);
  EXPECT_EQ(loaded.integrator, saved.integrator);
  ASSERT_EQ(loaded.particles.size(), saved.particles.size());
  for (std::size_t i = 0; i < saved.particles.size(); ++i) {
    EXPECT_EQ(loaded.particles[i].x, saved.particles[i].x) << i;
    EXPECT_EQ(loaded.particles[i].v, saved.particles[i].v) << i;
  }
  // Load state into a demo running another scene: it runs on from the saved clock.
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 2 --log-state pendulum.txt").exitCode, 0);
  const StateLog pendulum = readStateLog(dir + "/pendulum.txt");
  const LoggedOverlay* load = pendulum.widget("load-state");
  ASSERT_NE(load, nullptr);
  ASSERT_EQ(runDemo(dir, "--scene pendulum --frames 30 --log-state back.txt", clickAt(12, *load)).exitCode, 0);
  const LoggedPane back = readStateLog(dir + "/back.txt").panes.at(0);
  EXPECT_EQ(back.scene, "state.json");
  ASSERT_EQ(back.particles.size(), saved.particles.size());
  EXPECT_GT(back.time, saved.time);
  EXPECT_LT(back.time, saved.time + 0.5);
}

// The gallery's scenes are in the panel's list after the number keys' scenes
// and run from it; each starts and runs 1.5 s in the demo without stopping
// (tests/test_scenes.cpp runs them 3 s and more without the window).
TEST(DemoNewUser, TheGallerysScenesRunFromThePanelsList) {
  const std::string dir = outputDirectory("Gallery");
  for (const char* scene : {"hourglass", "newtons-cradle", "capstan", "rope-bridge", "soft-body"}) {
    // No stepping budget: every frame simulates its whole 1/60 s however slow the machine.
    ASSERT_EQ(runDemo(dir, std::string("--scene ") + scene +
                               " --no-panel --window 640x480 --step-budget 1000000 --frames 90 --log-state state.txt")
                  .exitCode,
              0)
        << scene;
    const StateLog log = readStateLog(dir + "/state.txt");
    EXPECT_FALSE(log.panes.at(0).diverged) << scene;
    EXPECT_NEAR(log.panes.at(0).time, 1.5, 0.01) << scene;
    EXPECT_TRUE(contains(log.overlay("top-bar")->text, scene)) << log.overlay("top-bar")->text;
  }
  // The capstan's caption compares the loads' ratio with e^(mu pi) on screen.
  ASSERT_EQ(runDemo(dir, "--scene capstan --frames 2 --log-state capstan.txt").exitCode, 0);
  const std::string top = readStateLog(dir + "/capstan.txt").overlay("top-bar")->text;
  EXPECT_TRUE(contains(top, "mass ratio 2 <= e^(mu pi) = e^(0.3 pi) = 2.57")) << top;
  // Opened from the list: the list's last entry is the gallery's last scene.
  ASSERT_EQ(runDemo(dir, "--scene cloth --frames 2 --log-state list.txt").exitCode, 0);
  const StateLog closed = readStateLog(dir + "/list.txt");
  const LoggedOverlay* combo = closed.widget("scene");
  ASSERT_NE(combo, nullptr);
  ASSERT_EQ(runDemo(dir, "--scene cloth --frames 8 --log-state open.txt", clickAt(2, *combo)).exitCode, 0);
  const StateLog open = readStateLog(dir + "/open.txt");
  const LoggedOverlay* list = open.widget("scene-list");
  ASSERT_NE(list, nullptr);
  // The last entry of the list: a click a row above its bottom edge.
  std::ostringstream pick;
  const double x = list->x + 0.3 * list->width, y = list->y + list->height - 12;
  pick << clickAt(2, *combo) << "8 move window " << x << " " << y << "\n9 down window " << x << " " << y
       << "\n10 up window " << x << " " << y << "\n";
  ASSERT_EQ(runDemo(dir, "--scene cloth --frames 14 --log-state picked.txt", pick.str()).exitCode, 0);
  EXPECT_EQ(readStateLog(dir + "/picked.txt").panes.at(0).scene, "soft-body");
}
